// tumble through its public API only: a Model of RigidBody::from_principal_moments bodies under
// UniformGravity, run by simulate(). Nothing here reaches behind simulate(), so the harness keeps
// measuring whatever engine implements it.
#include <cmath>
#include <string>

#include "scenario.hpp"
#include "tumble/dynamics/state.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/sim/simulate.hpp"

namespace peers {
namespace {

using tumble::Quat;
using tumble::Vec3;

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> arr(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

class TumbleRunner final : public Runner {
 public:
  explicit TumbleRunner(std::string integrator) : integrator_(std::move(integrator)) {}
  std::string engine() const override { return "tumble"; }
  std::string variant() const override { return integrator_; }
  std::string describe() const override {
    return "tumble " PEERS_TUMBLE_VERSION " (double), simulate() with formulation = mixed, integrator = " +
           integrator_ + ", output_interval = duration (one sample at the end of each timed run)";
  }

  std::string notes() const override {
    if (runs_with_extra_ == 0) return {};
    return "simulate() took a different number of steps than duration / h in " +
           std::to_string(runs_with_extra_) + " of " + std::to_string(runs_) + " calls (e.g. " +
           extra_example_ + "); rates count the steps taken";
  }

  void setup(const std::vector<BoxState>& boxes) override {
    model_ = tumble::Model{};
    model_.bodies.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      // Principal moments along the box's own x, y, z: the reference frame is the principal frame
      // (up to the order tumble sorts the moments into), with the centre of mass at its origin.
      model_.add_body(tumble::RigidBody::from_principal_moments(kMass, vec(kMoments), "box"));
    }
    model_.add_force<tumble::UniformGravity>(vec(kGravity));
    state_ = tumble::SystemState{};
    state_.bodies.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const BoxState& b = boxes[i];
      // state_from_reference: the pose of the box frame (which tumble calls the reference frame) and
      // ω in world axes; tumble places its own principal frame from it.
      state_.bodies.push_back(tumble::state_from_reference(
          model_.bodies[i], vec(b.position), Quat(b.q[0], b.q[1], b.q[2], b.q[3]), vec(b.velocity),
          vec(b.omega), tumble::Frame::world));
    }
  }

  long advance(long steps) override {
    // One simulate() call per timed run, as a user would make it: the step count is fixed by the
    // duration; output_interval = duration means no intermediate samples.
    const tumble::RunSettings rs = settings(steps, static_cast<double>(steps) * kTimestep);
    tumble::IntegratorStats stats;
    state_ = tumble::simulate(model_, std::move(state_), rs, {}, &stats);
    count_steps(stats, steps);
    return stats.steps;
  }

  void read(std::vector<BoxState>& out) const override {
    out.resize(state_.bodies.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = box_state(i, state_.bodies[i]);
  }

  void teardown() override {
    state_ = tumble::SystemState{};
    model_ = tumble::Model{};
  }

  void run_sampled(long steps, long every, const SampleSink& sink) override {
    // One run with samples every `every` steps, rather than a new simulate() per sample: each call
    // converts the world state into the formulation's variables, which would add a rounding per call
    // that a long run does not have.
    const tumble::RunSettings rs = settings(steps, static_cast<double>(every) * kTimestep);
    std::vector<BoxState> boxes(state_.bodies.size());
    const double t0 = state_.t;
    bool first = true;
    tumble::IntegratorStats stats;
    state_ = tumble::simulate(
        model_, std::move(state_), rs,
        [&](const tumble::SystemState& s) {
          if (first) {  // the initial state
            first = false;
            return true;
          }
          for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = box_state(i, s.bodies[i]);
          sink(std::lround((s.t - t0) / kTimestep), boxes);
          return true;
        },
        &stats);
    count_steps(stats, steps);
  }

 private:
  tumble::RunSettings settings(long steps, double output_interval) const {
    tumble::RunSettings rs;
    rs.duration = static_cast<double>(steps) * kTimestep;
    rs.timestep = kTimestep;
    rs.output_interval = output_interval;
    rs.formulation = tumble::Formulation::mixed;
    rs.integrator = integrator_;
    return rs;
  }

  // The pose of the box frame from tumble's state of its principal frame.
  BoxState box_state(std::size_t i, const tumble::BodyState& s) const {
    const tumble::ReferenceFrameState r = tumble::reference_state(model_.bodies[i], s);
    BoxState b;
    b.position = arr(r.position);
    b.q = {r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z()};
    b.velocity = arr(r.velocity);
    b.omega = arr(r.omega_w);
    return b;
  }

  // With duration = steps·h the time loop should take exactly `steps` steps. It accumulates t by
  // adding h, so after many steps t can fall short of the end by more than its rounding allowance and
  // one more (sliver) step is taken; it costs a whole step, so rates count the steps taken.
  void count_steps(const tumble::IntegratorStats& stats, long steps) {
    ++runs_;
    if (stats.steps != steps) {
      ++runs_with_extra_;
      extra_example_ = std::to_string(stats.steps) + " steps for duration = " + std::to_string(steps) + " h";
    }
  }

  std::string integrator_;
  long runs_ = 0, runs_with_extra_ = 0;
  std::string extra_example_;
  tumble::Model model_;
  tumble::SystemState state_;
};

}  // namespace

std::vector<std::unique_ptr<Runner>> make_tumble_runners() {
  std::vector<std::unique_ptr<Runner>> runners;
  for (const char* name : {"rk4", "splitting", "semi_implicit_euler"}) {
    runners.push_back(std::make_unique<TumbleRunner>(name));
  }
  return runners;
}

}  // namespace peers
