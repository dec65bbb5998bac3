#pragma once
// Sensitivities of a run (issue 25; docs/sensitivities.md): the state transition matrix
// ∂x(t_k)/∂x(0) and the derivatives ∂x(t_k)/∂p with respect to the bodies' principal moments,
// masses or the force models' parameters, at every sample, by forward-mode differentiation of the steps the integrator takes
// (Integrator::step_tangent): the derivatives of the discrete map that is run.
//
// Conventions (docs/NOTATION.md, "Tangent space"): per body 12 numbers δp, δθ, δv, δω in world axes
// (its reference frame's origin, attitude R ← exp([δθ]×) R, origin velocity, angular velocity); rows
// and columns body-major (body b owns rows and columns 12b … 12b + 11, and parameter columns
// P·b … P·b + P − 1). Column j perturbs x(0) along j with the other world-frame components held fixed;
// a parameter column holds x(0) (ω(0) in world axes included), the principal axes, the centre of mass
// and every other parameter fixed. The force models' parameters are columns every body shares (after
// the state's, in model order). Sample 0 is the identity and zeros.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tumble/sim/simulate.hpp"

namespace tumble {

/// Which parameters parameter_sensitivity differentiates with respect to.
enum class SensitivityParameters {
  inertia,  ///< each body's principal moments I₁ ≤ I₂ ≤ I₃ (3 columns per body)
  mass,     ///< each body's mass (1 column per body)
  forces,   ///< every force model's parameters() in model order (columns every body shares)
};
/// "inertia" or "mass" ↔ SensitivityParameters; throws InvalidArgument naming the choices.
SensitivityParameters parse_sensitivity_parameters(const std::string& name);
std::string sensitivity_parameters_name(SensitivityParameters parameters);
/// Columns per body: 3 (inertia), 1 (mass) or 0 (forces: their columns are shared by every body).
int parameters_per_body(SensitivityParameters parameters);
/// The parameter columns' names: "box: I1", "box: m", "force 0 (uniform gravity …): g_z".
std::vector<std::string> parameter_names(const Model& model, SensitivityParameters parameters);

/// The sensitivities at one sample. For bodies that do not interact (every force model local) the
/// derivatives of one body's state with respect to another's vanish: only each body's own 12 × 12
/// block (and 12 × P parameter block) is computed and kept, at a cost per body; bodies coupled by a
/// spring give dense matrices.
struct Sensitivities {
  bool coupled = false;
  int parameters_per_body = 3;  ///< 0: the parameters are the force models', shared by every body
  SensitivityParameters of = SensitivityParameters::inertia;
  std::vector<std::string> parameter_names;  ///< one per column of the dense parameter matrix
  /// coupled: ∂x/∂x(0), 12B × 12B. Otherwise 12B × 12: rows 12b … 12b + 11 are body b's own block.
  Eigen::MatrixXd stm;
  /// coupled: ∂x/∂p, 12B × PB. Otherwise 12B × P: rows 12b … are ∂x_b/∂p_b. The force models'
  /// parameters (shared): 12B × (their count), coupled or not.
  Eigen::MatrixXd parameters;

  /// The 12B × 12B matrix (zero off the diagonal blocks when not coupled).
  [[nodiscard]] Eigen::MatrixXd dense_stm() const;
  /// The 12B × PB matrix.
  [[nodiscard]] Eigen::MatrixXd dense_parameters() const;
};

/// Called with every sample's state and sensitivities (the initial state first); false stops the run.
using SensitivitySink = std::function<bool(const SystemState&, const Sensitivities&)>;

/// Runs the model from `state` as simulate() does — the same fixed steps landing on the same sample
/// times (output_interval or sample_times) — on dual numbers, and hands every sample's state and
/// sensitivities to `on_sample`. The states are the values of the dual numbers: the same arithmetic as
/// the integrator's, on one body at a time (they agree with simulate()'s to rounding). Returns the final
/// state. Throws InvalidArgument for settings simulate() refuses, an integrator that does not
/// differentiate its steps (differentiating_integrators()), a system with particles, or a force model
/// tumble cannot differentiate (a user callback); tumble::Error naming the body and time if a value or
/// a derivative becomes non-finite.
SystemState simulate_sensitivities(const Model& model, const SystemState& state, const RunSettings& settings,
                                   SensitivityParameters parameters, const SensitivitySink& on_sample);

}  // namespace tumble
