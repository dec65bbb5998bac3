#pragma once
// The stage loop of the classic fourth-order Runge–Kutta tableau, shared by rk4 and lie_rk4, in the
// low-storage form in which each stage finishes a body before the next body starts:
//   stage s = 1…4:  k_s = f(t + c_s h, y_s),  A += b_s k_s,  y_{s+1} = x + c_{s+1} h k_s,
//   x_{n+1} = x + (h/6) A,  with c = (0, ½, ½, 1), b = (1, 2, 2, 1), y_1 = x.
// The integrator supplies stage(s, block, in): the bodies' part of stage s from the stage state `in`,
// with its stage variables in block.work (engine.hpp). This file runs the stages fused or staged and
// steps the particles (whose variables are all vectors: plain RK4).
#include <initializer_list>
#include <vector>

#include "engine.hpp"

namespace tumble::rk4 {

inline constexpr double c[4] = {0.0, 0.5, 0.5, 1.0};
inline constexpr double b[4] = {1.0, 2.0, 2.0, 1.0};

/// The step length stage s advances x by: c_{s+1} h for the next stage state (s < 3), h/6 for the step's
/// end (s = 3), in double: the kernels broadcast it once per stage, not once per pack.
inline double stage_length(int s, double h) { return s < 3 ? c[s + 1] * h : h / 6; }

/// Stage s of one body (or pack) given its rate k_s = f(y_s) and the step's start x, with
/// `length` = stage_length(s, h): A ← b_s k_s (s = 0) or A + b_s k_s, and the next stage state
/// y_{s+1} = x + c_{s+1} h k_s; the last stage (s = 3) returns the step's end x + (h/6)(A + k_4) and
/// leaves A alone. The batched kernels and the dual-number step (step_tangent) both call it: one source
/// of the tableau.
template <class T>
TUMBLE_INLINE Coordinates<T> stage(int s, const T& length, const Coordinates<T>& x,
                                   const CoordinateRates<T>& k, CoordinateRates<T>& A) {
  if (s < 3) {
    A = s == 0 ? k : axpy<T>(A, T(b[s]), k);
    return advanced<T>(x, length, k);
  }
  return advanced<T>(x, length, axpy<T>(A, T(1.0), k));
}

/// `count` steps of x by h. `y` and `A_particles` are the whole-system stage variables of staged steps
/// (with `work`, the integrator's other whole-system columns: y.bodies first); fused steps leave them
/// untouched, and take each block through all `count` steps while it is in cache (its bodies do not
/// interact: every force is local). The time of each step is accumulated as step-by-step calls would.
template <class Stage>
void steps(engine::Engine& engine, SystemCoordinates& x, double h, long count, SystemCoordinates& y,
           std::vector<ParticleState>& A_particles, std::initializer_list<BodyColumns*> work, Stage&& stage) {
  const size_t n = x.bodies.size(), np = x.particles.size();
  const BodyColumnsRef xr = x.bodies.ref();
  if (engine.fused()) {
    engine.fused_steps(x, h, count, [&](engine::Engine::FusedBlock& fb, double t) {
      for (int s = 0; s < 4; ++s) {
        const BodyColumnsRef in = s == 0 ? xr : fb.work(0);
        stage(s, fb.evaluate(in, t + c[s] * h), in);
      }
    });
    return;
  }
  for (BodyColumns* w : work) w->ensure(n);
  y.particles.resize(np);
  A_particles.resize(np);
  for (long r = 0; r < count; ++r) {
    for (int s = 0; s < 4; ++s) {
      const SystemCoordinates& in = s == 0 ? x : y;
      const BodyColumnsRef in_ref = in.bodies.ref();
      engine.evaluate(
          in, [&](const engine::Block& blk) { stage(s, blk, in_ref); }, work);
      for (size_t p = 0; p < np; ++p) {
        const ParticleState k = engine.particle_rates(p, in.particles[p]);
        if (s < 3) {
          A_particles[p] = s == 0 ? k : axpy(A_particles[p], b[s], k);
          y.particles[p] = advanced(x.particles[p], c[s + 1] * h, k);
        } else {
          x.particles[p] = advanced(x.particles[p], h / 6, axpy(A_particles[p], 1.0, k));
        }
      }
      y.t = x.t + (s < 3 ? c[s + 1] : 1.0) * h;
    }
    x.t += h;
  }
}

}  // namespace tumble::rk4
