#pragma once
// The findings about one link: its authored inertial judged alone (is it a body at all?) and against
// what its geometry gives. Every code, its trigger and its threshold are here and in
// docs/robot-models.md; keep the two the same.
#include <vector>

#include "link_mass.hpp"
#include "tumble/robot/audit.hpp"

namespace tumble::robot {

/// Implied densities (kg/m³) outside this range are warned about: lighter than any wood or foam a robot
/// is built of, denser than osmium.
constexpr double kDensityPlausibleLow = 50.0, kDensityPlausibleHigh = 25000.0;
/// Outside this range no solid material has the density: an error.
constexpr double kDensityPossibleLow = 5.0, kDensityPossibleHigh = 50000.0;
/// The tensors differ by this fraction of the largest computed principal moment (spectral norm of the
/// difference): a warning; by kTensorError, an error.
constexpr double kTensorWarning = 0.1, kTensorError = 0.5;
/// An explanation (a tensor about the origin, a rotation applied twice, a permuted diagonal, a product's
/// sign) is named when it brings the difference within this fraction.
constexpr double kTensorExplained = 0.02;
/// The authored COM farther than this fraction of the link's size from the computed one: a warning.
constexpr double kComWarning = 0.1;

/// Appends the findings about `link` (its audit's authored and computed values; `solids` its geometry,
/// null when none could be used) to `findings`.
void judge(const RobotModel& model, const Link& link, const LinkAudit& audit, const LinkSolids* solids,
           std::vector<Finding>& findings);
/// The same for a body welded from several links: the authored tensor and the comparison of tensors.
void judge_lumped(const RobotModel& model, const LinkAudit& lumped, std::vector<Finding>& findings);

}  // namespace tumble::robot
