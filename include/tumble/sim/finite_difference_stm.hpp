#pragma once
// The state transition matrix ∂x(t_end)/∂x(0) of a run by central differences: 2 runs per direction,
// 24 per body, each perturbed along one tangent direction (dynamics/tangent.hpp) by ±ε. The reference
// the sensitivities of issue 25 are compared with and measured against (cost: 2·12·B + 1 runs).
#include <Eigen/Core>

#include "tumble/sim/simulate.hpp"

namespace tumble {

/// The 12B × 12B matrix, body-major (body b owns rows and columns 12b … 12b + 11: δp, δθ, δv, δω in
/// world axes, of its reference frame). Column j is (x⁺ − x⁻)/(2ε) with x± the end of the run from x(0)
/// moved by ±ε along direction j. Throws InvalidArgument for a system with particles, or ε ≤ 0.
[[nodiscard]] Eigen::MatrixXd stm_by_central_differences(const Model& model, const SystemState& initial,
                                                         const RunSettings& settings, double epsilon);

}  // namespace tumble
