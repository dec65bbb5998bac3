#include "tumble/forces/stack.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "tumble/forces/rotors.hpp"

namespace tumble {
namespace {

/// A local model of one run acting on each of the stacked runs' copies of its bodies: the bodies of a
/// block are handed to it run by run, as a sub-block whose indices are those inside the run, so that
/// the model computes for each copy exactly what it computes in the run alone.
class OnEveryRun final : public LocalForceModel {
 public:
  OnEveryRun(std::shared_ptr<const LocalForceModel> model, size_t n) : model_(std::move(model)), n_(n) {}

  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override {
    const size_t end = block.begin + block.count;
    for (size_t i = block.begin; i < end;) {
      const size_t run_start = i / n_ * n_, stop = std::min(end, run_start + n_), j = i - block.begin;
      BodyBlock part = block;
      part.begin = i - run_start;
      part.count = stop - i;
      part.bodies = block.bodies + j;
      part.m = block.m + j;
      BlockLoads part_loads;
      for (size_t k = 0; k < 3; ++k) {
        part.Lambda[k] = block.Lambda[k] + j;
        part.o[k] = block.o[k] + j;
        if (block.v[k]) part.v[k] = block.v[k] + j;
        if (block.omega_w[k]) part.omega_w[k] = block.omega_w[k] + j;
        part_loads.f[k] = loads.f[k] + j;
        part_loads.tau[k] = loads.tau[k] + j;
      }
      for (size_t k = 0; k < 4; ++k) part.q[k] = block.q[k] + j;
      model_->accumulate_block(part, part_loads);
      i = stop;
    }
  }
  bool needs_velocity() const override { return model_->needs_velocity(); }
  std::optional<Vec3> uniform_acceleration() const override { return model_->uniform_acceleration(); }
  std::optional<CentralBody> central_body() const override { return model_->central_body(); }
  std::string describe(std::span<const RigidBody> bodies) const override {
    return model_->describe(bodies) + " (in every stacked run)";
  }
  std::optional<double> potential_energy(const SystemView& view) const override {
    // Σ over the runs of each run's potential, on its own bodies.
    double V = 0;
    for (size_t first = 0; first < view.bodies.size(); first += n_) {
      const SystemView run{
          view.t, view.bodies.subspan(first, n_), view.body_states.subspan(first, n_), {}, {}};
      const std::optional<double> v = model_->potential_energy(run);
      if (!v) return std::nullopt;
      V += *v;
    }
    return V;
  }
  Vec3 internal_angular_momentum(const SystemView& view) const override {
    // Σ over the runs of each run's (its rotors' R h), on its own bodies, as the potential.
    Vec3 L = Vec3::Zero();
    for (size_t first = 0; first < view.bodies.size(); first += n_) {
      const SystemView run{
          view.t, view.bodies.subspan(first, n_), view.body_states.subspan(first, n_), {}, {}};
      L += model_->internal_angular_momentum(run);
    }
    return L;
  }
  void check(size_t n_bodies, size_t n_particles) const override {
    model_->check(n_, n_particles);
    if (n_bodies % n_ != 0) model_->check(n_bodies % n_, n_particles);
  }

 private:
  std::shared_ptr<const LocalForceModel> model_;
  size_t n_;
};

}  // namespace

std::optional<Model> stack_runs(std::span<const Model* const> runs) {
  if (runs.empty()) return std::nullopt;
  const Model& first = *runs[0];
  const size_t n = first.bodies.size();
  if (n == 0) return std::nullopt;
  Model stacked;
  // Rotors become one Rotors of every run's copies (built once the bodies are stacked): the splittings
  // find them there (rotors_of) and carry them in their flows, as in the run alone.
  std::vector<std::pair<size_t, const Rotors*>> rotors;
  for (const auto& f : first.forces) {
    if (const auto* r = dynamic_cast<const Rotors*>(f.get())) {
      rotors.emplace_back(stacked.forces.size(), r);
      stacked.forces.push_back(nullptr);
    } else if (f->acts_alike_on_every_body()) {
      stacked.forces.push_back(f);
    } else if (auto local = std::dynamic_pointer_cast<const LocalForceModel>(f)) {
      stacked.forces.push_back(std::make_shared<const OnEveryRun>(std::move(local), n));
    } else {
      return std::nullopt;  // a system model may couple any bodies: each run keeps its own system
    }
  }
  stacked.bodies.reserve(n * runs.size());
  for (const Model* run : runs) {
    if (run->bodies.size() != n || !run->particles.empty() || run->forces.size() != first.forces.size())
      return std::nullopt;
    stacked.bodies.insert(stacked.bodies.end(), run->bodies.begin(), run->bodies.end());
  }
  for (const auto& [slot, r] : rotors) {
    if (r->input_interval() > 0.0) return std::nullopt;  // a controller's state is its run's own
    std::vector<Rotor> every;
    for (size_t k = 0; k < runs.size(); ++k) {
      for (Rotor rotor : r->rotors()) {
        rotor.body += k * n;
        every.push_back(std::move(rotor));
      }
    }
    stacked.forces[slot] = std::make_shared<const Rotors>(std::move(every), stacked.bodies);
  }
  return stacked;
}

}  // namespace tumble
