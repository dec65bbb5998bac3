#include "tumble/sim/drift_monitor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tumble/integrate/integrator.hpp"

namespace tumble {
namespace {

/// E when every force has a potential, else nullopt.
std::optional<double> energy(const Invariants& inv) { return inv.total_energy(); }

/// What to change, for this scene: only integrators that remove the error here, never the one in use.
std::string advice(const Model& model, const RunSettings& s) {
  const bool torque_free = std::all_of(model.forces.begin(), model.forces.end(),
                                       [](const auto& f) { return f->uniform_acceleration().has_value(); });
  auto others = [&](std::vector<std::string> names) {
    std::erase(names, s.integrator);
    return names;
  };
  const std::string smaller = is_adaptive(s.integrator)
                                  ? fmt::format("tighten the tolerances (now rtol {:g}, atol {:g})",
                                                s.tolerances.relative, s.tolerances.absolute)
                                  : fmt::format("reduce the timestep (now {:g} s)", s.timestep);
  if (torque_free) {
    const auto better = others({"exact", "splitting"});
    if (better.empty()) return smaller;
    return fmt::format("no torque acts in this scene, so '{}' {}; or {}", fmt::join(better, "' or '"),
                       better.size() == 2
                           ? "(the analytic motion, or exact at any step here) removes the error"
                           : "removes the error",
                       smaller);
  }
  const auto better = others({"splitting4", "dopri45"});
  return better.empty() ? smaller : fmt::format("{}, or use '{}'", smaller, fmt::join(better, "' or '"));
}

}  // namespace

DriftMonitor::DriftMonitor(const Model& model, const SystemState& initial, Conservation conserved,
                           double threshold, const RunSettings& settings)
    : DriftMonitor(model, invariants(model, initial), conserved, threshold, settings) {}

DriftMonitor::DriftMonitor(const Model& model, const Invariants& initial, Conservation conserved,
                           double threshold, const RunSettings& settings)
    : model_(model),
      rotors_(rotors_of(model)),
      initial_(initial),
      conserved_(conserved),
      threshold_(threshold),
      settings_(settings) {
  // The energy is relative to max(|E₀|, T₀): |E₀| alone can be ~0 by the choice of the potential's
  // zero (a thrown body, a bound orbit near escape), which would make any drift look infinite.
  if (const auto E0 = energy(initial_)) energy_scale_ = std::max(std::abs(*E0), initial_.kinetic_energy);
  // What every sample is compared with, formed once (a study observes millions of samples).
  E0_ = energy(initial_);
  p0_ = initial_.linear_momentum.norm();
  L0_ = initial_.angular_momentum.norm();
}

DriftSample DriftMonitor::observe(const SystemCoordinates& x, size_t first) {
  return judge(invariants(model_, settings_.formulation, x, first, scratch_), x.t);
}

DriftSample DriftMonitor::observe(const SystemState& state) {
  DriftSample d = judge(invariants(model_, state), state.t);
  if (rotors_) {
    for (size_t j = 0; j < rotors_->rotors().size(); ++j) {
      d.rotor_speed.push_back(rotors_->speed(j, state.t));
      d.rotor_torque.push_back(rotors_->motor_torque(j, state.t));
    }
  }
  return d;
}

DriftSample DriftMonitor::judge(const Invariants& at, double t) {
  DriftSample d;
  d.invariants = at;
  const auto E = energy(d.invariants);
  if (E0_ && E && energy_scale_ > 0) d.energy_drift = (*E - *E0_) / energy_scale_;
  if (p0_ > 0)
    d.linear_momentum_drift = (d.invariants.linear_momentum - initial_.linear_momentum).norm() / p0_;
  if (L0_ > 0) {
    d.angular_momentum_drift = (d.invariants.angular_momentum - initial_.angular_momentum).norm() / L0_;
  }

  if (warned_ || !(threshold_ > 0)) return d;
  auto passes = [&](const std::optional<double>& drift) {
    return drift && !(std::abs(*drift) <= threshold_);  // NaN counts as past the threshold
  };
  const char* quantity = nullptr;
  double value = 0.0;
  if (conserved_.energy && passes(d.energy_drift)) {
    quantity = "energy";
    value = *d.energy_drift;
  } else if (conserved_.angular_momentum && passes(d.angular_momentum_drift)) {
    quantity = "angular momentum";
    value = *d.angular_momentum_drift;
  }
  if (quantity != nullptr) {
    warned_ = true;
    pending_ = fmt::format(
        "{} drifted by {:.3g} (relative to t = 0) at t = {} s, past the drift threshold {:g}; the "
        "forces conserve it, so this is integration error of '{}': {}; or raise drift_threshold in "
        "[simulation] (--drift-threshold)",
        quantity, value, t, threshold_, settings_.integrator, advice(model_, settings_));
    first_warning_ = pending_;
  }
  return d;
}

std::optional<std::string> DriftMonitor::take_warning() {
  std::optional<std::string> w;
  w.swap(pending_);
  return w;
}

}  // namespace tumble
