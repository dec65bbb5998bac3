#include "engine.hpp"

#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <type_traits>

#include "tumble/integrate/integrator.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace tumble::engine {

int omp_thread() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

namespace {
std::atomic<bool> g_threads_started{false};  // this process (or the one it was forked from) ran a region
std::atomic<bool> g_forked_after_threads{false};
extern "C" void note_fork_in_child() {
  if (g_threads_started.load()) g_forked_after_threads.store(true);
}
const int g_atfork_registered = ::pthread_atfork(nullptr, nullptr, note_fork_in_child);
}  // namespace

bool parallel_region_allowed() {
  (void)g_atfork_registered;
  if (g_forked_after_threads.load()) return false;
  g_threads_started.store(true);
  return true;
}

int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace tumble::engine

namespace tumble {
EngineInfo engine_info() { return {xsimd::default_arch::name(), static_cast<int>(engine::kWidth)}; }
}  // namespace tumble

namespace tumble::engine {

bool Engine::fusable(const Model& model) {
  return model.particles.empty() &&
         std::all_of(model.forces.begin(), model.forces.end(), [](const auto& f) { return f->local(); });
}

void Engine::prepare(const Model& model, Formulation formulation, int threads, int work_sets) {
  const int wanted = threads > 0 ? threads : max_threads();
  if (model_ == &model && bodies_data_ == model.bodies.data() && n_bodies_ == model.bodies.size() &&
      n_particles_ == model.particles.size() && n_forces_ == model.forces.size() &&
      formulation_ == formulation && threads_ == wanted && work_sets_ >= work_sets) {
    return;
  }
  work_sets_ = work_sets;
  model_ = &model;
  bodies_data_ = model.bodies.data();
  n_bodies_ = model.bodies.size();
  n_particles_ = model.particles.size();
  n_forces_ = model.forces.size();
  formulation_ = formulation;
  threads_ = wanted;

  constants_.resize(n_bodies_, kConstants);
  for (size_t k = 0; k < kConstants; ++k) std::fill(constants_[k], constants_[k] + constants_.stride(), 1.0);
  for (size_t i = 0; i < n_bodies_; ++i) {
    const double m = model.bodies[i].mass();
    const Vec3 Lambda = model.bodies[i].Lambda();
    const MassConstants<double> c = mass_constants<double>(m, Lambda);
    constants_[kM][i] = m;
    constants_[kMInv][i] = c.m_inv;
    for (size_t k = 0; k < 3; ++k) {
      const auto e = static_cast<Eigen::Index>(k);
      constants_[kLambda + k][i] = Lambda(e);
      constants_[kLambdaInv + k][i] = c.Lambda_inv(e);
    }
  }

  local_.clear();
  system_.clear();
  needs_velocity_ = false;
  for (const auto& force : model.forces) {
    force->check(n_bodies_, n_particles_);
    needs_velocity_ = needs_velocity_ || force->needs_velocity();
    if (force->local()) {
      local_.push_back(static_cast<const LocalForceModel*>(force.get()));
    } else {
      system_.push_back(force.get());
    }
  }
  scratch_.resize(static_cast<size_t>(threads_));
  for (Scratch& s : scratch_) s.work.ensure(kBlock, static_cast<size_t>(work_sets_) * BodyColumnsRef::kCount);
  system_loads_.bodies.assign(system_.empty() ? 0 : n_bodies_, Wrench{});
  system_loads_.particles.assign(n_particles_, Vec3::Zero());
  body_states_.assign(system_.empty() ? 0 : n_bodies_, BodyState{});
}

void Engine::system_part(const SystemCoordinates& y) {
  if (system_.empty() && n_particles_ == 0) return;
  for (Wrench& w : system_loads_.bodies) w = Wrench{};
  for (Vec3& f : system_loads_.particles) f.setZero();
  if (!system_.empty()) {
    for (size_t i = 0; i < n_bodies_; ++i) body_states_[i] = to_state(formulation_, y.bodies.load(i));
  }
  const SystemView view{y.t, model_->bodies, body_states_, model_->particles, y.particles};
  for (const ForceModel* force : system_) force->accumulate(view, system_loads_);
  if (n_particles_ > 0) {
    for (const LocalForceModel* force : local_) force->accumulate_particles(view, system_loads_.particles);
  }
}

Block Engine::local_loads(const BodyColumnsRef& y, double t, size_t begin, size_t count, size_t n,
                          Scratch& s) const {
  zero(s.loads);
  BodyBlock view;
  view.t = t;
  view.begin = begin;
  view.count = count;
  view.bodies = model_->bodies.data() + begin;
  view.m = constants_[kM] + begin;
  for (size_t k = 0; k < 3; ++k) {
    view.Lambda[k] = constants_[kLambda + k] + begin;
    view.o[k] = y.at(BodyColumnsRef::o + k, begin);
  }
  for (size_t k = 0; k < 4; ++k) view.q[k] = y.at(BodyColumnsRef::q + k, begin);
  if (needs_velocity_) {
    // World v and ω: the formulation's own columns where they are world quantities, else rotated into
    // the block's scratch (v_w = R ^bv, ω_w = R ^bω).
    const bool v_world = formulation_ != Formulation::body, omega_world = formulation_ == Formulation::world;
    for (size_t k = 0; k < 3; ++k) {
      view.v[k] = v_world ? y.at(BodyColumnsRef::v + k, begin) : s.world[k];
      view.omega_w[k] = omega_world ? y.at(BodyColumnsRef::omega + k, begin) : s.world[3 + k];
    }
    // A pack of bodies at a time, then the last few alone: rotate<T> is Eigen's formula for q * v on
    // any number type, so a body's world velocities are the same bits wherever it sits in the block.
    const auto rotate_into = [&](auto tag, size_t j, size_t from, double* const* to) {
      using T = decltype(tag);
      const auto load = [&](size_t c) -> T {
        if constexpr (std::is_same_v<T, double>) {
          return y.at(c, begin)[j];
        } else {
          return T::load_unaligned(y.at(c, begin) + j);
        }
      };
      const QuatT<T> q(load(BodyColumnsRef::q), load(BodyColumnsRef::q + 1), load(BodyColumnsRef::q + 2),
                       load(BodyColumnsRef::q + 3));
      const Vec3T<T> r = rotate<T>(q, Vec3T<T>(load(from), load(from + 1), load(from + 2)));
      for (size_t k = 0; k < 3; ++k) {
        if constexpr (std::is_same_v<T, double>) {
          to[k][j] = r(static_cast<Eigen::Index>(k));
        } else {
          r(static_cast<Eigen::Index>(k)).store_unaligned(to[k] + j);
        }
      }
    };
    double* const v_to[3] = {s.world[0], s.world[1], s.world[2]};
    double* const omega_to[3] = {s.world[3], s.world[4], s.world[5]};
    const auto rotate_body = [&](auto tag, size_t j) {
      if (!v_world) rotate_into(tag, j, BodyColumnsRef::v, v_to);
      if (!omega_world) rotate_into(tag, j, BodyColumnsRef::omega, omega_to);
    };
    size_t j = 0;
    for (; j + kWidth <= count; j += kWidth) rotate_body(Pack(), j);
    for (; j < count; ++j) rotate_body(0.0, j);
  }
  BlockLoads loads;
  Block block;
  block.begin = begin;
  block.end = std::min(begin + kBlock, padded_size(n));
  for (size_t k = 0; k < 3; ++k) {
    loads.f[k] = s.loads[k];
    loads.tau[k] = s.loads[3 + k];
    block.f[k] = s.loads[k];
    block.tau[k] = s.loads[3 + k];
  }
  for (const LocalForceModel* force : local_) force->accumulate_block(view, loads);
  return block;
}

}  // namespace tumble::engine
