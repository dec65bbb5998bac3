#pragma once
// The batched core shared by every fixed-step integrator. It evaluates the loads on the bodies block by
// block and hands each block, right after its loads, to the integrator's kernel, which updates columns
// in place, one pack of bodies at a time (tumble/math/simd.hpp).
//
// Two ways through a step:
//  - fused (when every force model is local and there are no particles): each block of kBlock bodies
//    is taken through all the stages of a step on its own, its stage variables in per-thread scratch
//    that stays in cache. The only whole-system arrays are the state and the constants (21 doubles per
//    body), read and written once per step, so the rate does not fall with the number of bodies;
//  - staged (otherwise): stage by stage over the whole system, because a system model (a spring) needs
//    every body's stage state before any body can move on; stage variables are whole-system columns.
// The kernels are the same in both; only where the stage variables live differs. Every body is computed
// by the same pack code whatever block or thread it falls in (blocks start at multiples of the pack
// width; padding lanes are harmless), so results are bit-identical for any number of bodies around it,
// either way through the step, and any thread count.
//
// Allocation happens in prepare(), once per run (again only when the model changes size); a step
// allocates nothing.
#include <exception>
#include <initializer_list>
#include <span>
#include <vector>

#include "stages.hpp"
#include "tumble/integrate/system_coordinates.hpp"
#include "tumble/math/simd.hpp"

namespace tumble::engine {

/// The OpenMP thread number inside a parallel region (0 outside, or without OpenMP).
int omp_thread();
/// Hardware threads available to OpenMP.
int max_threads();
/// Whether OpenMP can start threads in this process, noting that it is about to. libgomp is not fork-
/// safe: in a child forked after the parent's threads started (Python multiprocessing's default start
/// method), a parallel region waits forever for threads that do not exist. There the engine steps on
/// the calling thread alone (the same numbers: a body's step does not depend on the thread count).
bool parallel_region_allowed();

/// The pack the build's instruction set offers (AVX-512: 8 doubles, AVX2: 4, SSE2: 2).
using Pack = xsimd::batch<double>;
inline constexpr size_t kWidth = Pack::size;
/// Bodies per block (a multiple of every pack width): two sets of stage variables of a block (2 × 13 ×
/// 256 doubles, 52 KiB) stay in the L2 cache.
inline constexpr size_t kBlock = 64;

// GCC's loop distribution turns a loop of zero stores into a call of memset; this keeps the loop.
// Clang has no such attribute (its builds here are the sanitizer's, which are not measured).
#if defined(__GNUC__) && !defined(__clang__)
#define TUMBLE_NO_MEMSET [[gnu::optimize("no-tree-loop-distribute-patterns")]]
#else
#define TUMBLE_NO_MEMSET
#endif

/// One block as a kernel sees it: bodies [begin, end) (end a multiple of the pack width, so it may
/// include padding lanes), their loads (world force and torque) at the stage being computed, and the
/// integrator's stage variables (block scratch when fused, whole-system columns when staged).
struct Block {
  size_t begin = 0, end = 0;
  const double* f[3] = {};
  const double* tau[3] = {};
  BodyColumnsRef work[3];

  template <class T>
  TUMBLE_INLINE Vec3T<T> force(size_t i) const {
    return {Lanes<T>::load(f[0] + (i - begin)), Lanes<T>::load(f[1] + (i - begin)),
            Lanes<T>::load(f[2] + (i - begin))};
  }
  template <class T>
  TUMBLE_INLINE Vec3T<T> torque(size_t i) const {
    return {Lanes<T>::load(tau[0] + (i - begin)), Lanes<T>::load(tau[1] + (i - begin)),
            Lanes<T>::load(tau[2] + (i - begin))};
  }
};

class Engine {
 public:
  /// Binds the engine to a model and formulation and sizes every buffer, with `work_sets` (≤ 3) sets
  /// of stage variables per block. Cheap when nothing changed. threads ≤ 0: one per hardware thread.
  /// Checks every force model's body references once.
  void prepare(const Model& model, Formulation formulation, int threads, int work_sets = 0);

  /// Whether a step can take each block through all its stages alone (every force model local, no
  /// particles).
  bool fused() const { return system_.empty() && n_particles_ == 0; }
  /// The same for a model, before prepare().
  static bool fusable(const Model& model);

  /// Fused steps: calls step(FusedBlock&) for every block, in parallel.
  class FusedBlock;
  template <class Step>
  void for_each_fused_block(size_t n, Step&& step);
  /// `count` fused steps of h: each block goes through step(FusedBlock&, t) for every step while it is
  /// in cache (its bodies meet no other block's: every force is local), t accumulated from x.t as
  /// step-by-step calls would; then x.t advances by the same additions.
  template <class Step>
  void fused_steps(SystemCoordinates& x, double h, long count, Step&& step) {
    for_each_fused_block(x.bodies.size(), [&](FusedBlock& fb) {
      double t = x.t;
      for (long r = 0; r < count; ++r, t += h) step(fb, t);
    });
    for (long r = 0; r < count; ++r) x.t += h;
  }

  /// Staged steps: evaluates the loads at y (time y.t) and calls kernel(const Block&) for every block
  /// right after its loads, in parallel; `work` are the whole-system stage variables handed to the
  /// kernel. Particle loads are in particle_rates() afterwards.
  template <class Kernel>
  void evaluate(const SystemCoordinates& y, Kernel&& kernel, std::initializer_list<BodyColumns*> work = {});

  /// Calls kernel(const Block&) for every block without evaluating loads (they read as zero).
  template <class Kernel>
  void for_each_block(size_t n, Kernel&& kernel);

  /// The Newton–Euler rates of body (or pack) i at y, with the loads of its block (newton_euler.hpp).
  template <class T>
  TUMBLE_INLINE CoordinateRates<T> rates(const Block& block, size_t i, const Coordinates<T>& y) const {
    return newton_euler<T>(formulation_, mass<T>(i), y, block.force<T>(i), block.torque<T>(i));
  }
  /// (ẋ, v̇) of particle p at s, with the loads of the last evaluate().
  ParticleState particle_rates(size_t p, const ParticleState& s) const {
    return tumble::particle_rates(model_->particles[p], s, system_loads_.particles[p]);
  }
  std::span<const Vec3> particle_forces() const { return system_loads_.particles; }

  /// Per-body constants, padded with ones: m (kg), Λ (kg·m²), and the reciprocals the rates multiply by
  /// (newton_euler.hpp's MassConstants).
  template <class T>
  TUMBLE_INLINE T m(size_t i) const {
    return Lanes<T>::load(constants_[kM] + i);
  }
  template <class T>
  TUMBLE_INLINE Vec3T<T> Lambda(size_t i) const {
    return load3<T>(kLambda, i);
  }
  template <class T>
  TUMBLE_INLINE MassConstants<T> mass(size_t i) const {
    return {Lanes<T>::load(constants_[kMInv] + i), load3<T>(kLambda, i), load3<T>(kLambdaInv, i)};
  }

 private:
  struct Scratch {
    Columns loads{kBlock, 6};  // f (3), τ (3)
    Columns world{kBlock, 6};  // v, ω in world axes, when the formulation does not integrate them
    Columns work;              // fused steps: the block's stage variables, 13 columns per set
    std::exception_ptr error;
    size_t error_block = 0;
  };
  void system_part(const SystemCoordinates& y);
  /// The loads of the local models on bodies [begin, begin + count) at the state y (time t) into
  /// s.loads; returns the block with its loads.
  Block local_loads(const BodyColumnsRef& y, double t, size_t begin, size_t count, size_t n,
                    Scratch& s) const;
  template <class F>
  void parallel_blocks(size_t n, F&& f);
  /// Pack stores, read through a pointer and a length loaded once: a double store may alias the
  /// Columns' own members, so a loop through c reloads both after every store (10 % of a 10^5-body
  /// rk4 run). GCC would turn the loop into a call of memset, slower for these 3 kB (15 % of a step in
  /// `rep stosb` on some machines), hence the attribute.
  TUMBLE_NO_MEMSET static void zero(Columns& c) {
    double* const first = c[0];
    const size_t total = c.stride() * c.count();
    for (size_t i = 0; i < total; i += kWidth) Pack(0.0).store_aligned(first + i);
  }

  // The columns of constants_.
  static constexpr size_t kM = 0, kLambda = 1, kMInv = 4, kLambdaInv = 5, kConstants = 8;
  template <class T>
  TUMBLE_INLINE Vec3T<T> load3(size_t column, size_t i) const {
    return {Lanes<T>::load(constants_[column] + i), Lanes<T>::load(constants_[column + 1] + i),
            Lanes<T>::load(constants_[column + 2] + i)};
  }

  const Model* model_ = nullptr;
  const RigidBody* bodies_data_ = nullptr;
  size_t n_bodies_ = 0, n_particles_ = 0, n_forces_ = 0;
  Formulation formulation_ = Formulation::mixed;
  int threads_ = 1, work_sets_ = 0;
  Columns constants_;
  std::vector<const LocalForceModel*> local_;
  std::vector<const ForceModel*> system_;
  bool needs_velocity_ = false;
  std::vector<Scratch> scratch_;
  Loads system_loads_;                  // loads of the system models, and every particle load
  std::vector<BodyState> body_states_;  // world structs, gathered only for system models

  friend class FusedBlock;
};

/// A block taken through a whole step: its bodies, its stage variables and its loads at any state.
class Engine::FusedBlock {
 public:
  size_t begin = 0, end = 0, count = 0;
  /// The loads at the state y (which holds this block's bodies) at time t, with the block's stage
  /// variables; valid until the next call.
  const Block& evaluate(const BodyColumnsRef& y, double t) {
    block_ = engine_->local_loads(y, t, begin, count, n_, *scratch_);
    for (size_t k = 0; k < 3; ++k) block_.work[k] = work_[k];
    return block_;
  }
  const BodyColumnsRef& work(size_t k) const { return work_[k]; }

 private:
  friend class Engine;
  const Engine* engine_ = nullptr;
  Scratch* scratch_ = nullptr;
  size_t n_ = 0;
  BodyColumnsRef work_[3];
  Block block_;
};

// ---- templates ------------------------------------------------------------------------------------

template <class F>
void Engine::parallel_blocks(size_t n, F&& f) {
  const size_t blocks = (n + kBlock - 1) / kBlock;
  auto run = [&](size_t b, Scratch& s) {
    try {
      f(b, s);
    } catch (...) {
      if (!s.error || b < s.error_block) {
        s.error = std::current_exception();
        s.error_block = b;
      }
    }
  };
  const int threads = static_cast<int>(std::min<size_t>(static_cast<size_t>(threads_), blocks));
  if (threads <= 1 || !parallel_region_allowed()) {
    for (size_t b = 0; b < blocks; ++b) run(b, scratch_[0]);
  } else {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (size_t b = 0; b < blocks; ++b) run(b, scratch_[static_cast<size_t>(omp_thread())]);
  }
  // The error of the first block that failed, whatever the thread count.
  Scratch* first = nullptr;
  for (Scratch& s : scratch_) {
    if (s.error && (!first || s.error_block < first->error_block)) first = &s;
  }
  if (first) {
    const std::exception_ptr e = first->error;
    for (Scratch& s : scratch_) s.error = nullptr;
    std::rethrow_exception(e);
  }
}

template <class Step>
void Engine::for_each_fused_block(size_t n, Step&& step) {
  parallel_blocks(n, [&](size_t b, Scratch& s) {
    FusedBlock fb;
    fb.begin = b * kBlock;
    fb.count = std::min(kBlock, n - fb.begin);
    fb.end = std::min(fb.begin + kBlock, padded_size(n));
    fb.engine_ = this;
    fb.scratch_ = &s;
    fb.n_ = n;
    for (size_t k = 0; k < static_cast<size_t>(work_sets_); ++k) {
      double* c[BodyColumnsRef::kCount];
      for (size_t j = 0; j < BodyColumnsRef::kCount; ++j) c[j] = s.work[k * BodyColumnsRef::kCount + j];
      fb.work_[k] = BodyColumnsRef(c, fb.begin);
    }
    step(fb);
  });
}

template <class Kernel>
void Engine::evaluate(const SystemCoordinates& y, Kernel&& kernel, std::initializer_list<BodyColumns*> work) {
  system_part(y);
  const size_t n = n_bodies_;
  const BodyColumnsRef y_ref = y.bodies.ref();
  parallel_blocks(n, [&](size_t b, Scratch& s) {
    const size_t begin = b * kBlock, count = std::min(kBlock, n - begin);
    Block block = local_loads(y_ref, y.t, begin, count, n, s);
    if (!system_loads_.bodies.empty()) {
      BlockLoads loads;
      for (size_t k = 0; k < 3; ++k) {
        loads.f[k] = s.loads[k];
        loads.tau[k] = s.loads[3 + k];
      }
      for (size_t j = 0; j < count; ++j) {
        loads.add(j, system_loads_.bodies[begin + j].force, system_loads_.bodies[begin + j].torque);
      }
    }
    size_t k = 0;
    for (BodyColumns* w : work) block.work[k++] = w->ref();
    kernel(static_cast<const Block&>(block));
  });
}

template <class Kernel>
void Engine::for_each_block(size_t n, Kernel&& kernel) {
  parallel_blocks(n, [&](size_t b, Scratch& s) {
    zero(s.loads);
    Block block{b * kBlock, std::min(b * kBlock + kBlock, padded_size(n)), {}, {}, {}};
    for (size_t k = 0; k < 3; ++k) {
      block.f[k] = s.loads[k];
      block.tau[k] = s.loads[3 + k];
    }
    kernel(static_cast<const Block&>(block));
  });
}

}  // namespace tumble::engine
