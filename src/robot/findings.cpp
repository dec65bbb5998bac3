#include "findings.hpp"

#include <array>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <fmt/ranges.h>

namespace tumble::robot {

namespace {

std::string where(const RobotModel& model, int line) {
  return fmt::format("{}:{}", model.path.string(), line);
}

/// Eigenvalues of a symmetric matrix, ascending.
Vec3 eigenvalues(const Mat3& I) {
  return Eigen::SelfAdjointEigenSolver<Mat3>(I, Eigen::EigenvaluesOnly).eigenvalues();
}

/// ‖A − B‖₂ (the largest |eigenvalue| of the symmetric difference) over the largest eigenvalue of B.
double relative_difference(const Mat3& A, const Mat3& B) {
  const Mat3 D = (A - B + (A - B).transpose()) / 2;
  return eigenvalues(D).cwiseAbs().maxCoeff() / eigenvalues(B).maxCoeff();
}

std::string tensor_text(const Mat3& I) {
  return fmt::format("ixx {:.6g}, iyy {:.6g}, izz {:.6g}, ixy {:.6g}, ixz {:.6g}, iyz {:.6g}", I(0, 0),
                     I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
}

/// The authored inertial alone: a mass and a tensor some body could have.
bool judge_alone(const std::string& who, const Inertial& in, std::vector<Finding>& findings) {
  if (in.mass < 0) {
    findings.push_back(
        {"not_positive_definite", Severity::error,
         fmt::format("{}: the mass is {} kg: a mass is positive; fix <mass>", who, in.mass_text)});
    return false;
  }
  if (in.mass == 0 && in.inertia_written.isZero(0.0)) return false;  // a massless frame: nothing to judge
  const Vec3 lambda = eigenvalues(in.inertia_written);
  if (!(lambda(0) > 0)) {
    findings.push_back(
        {"not_positive_definite", Severity::error,
         fmt::format("{}: the inertia tensor ({}) is not positive definite: its principal moments are "
                     "{:.6g}, "
                     "{:.6g}, {:.6g}, and every body's are positive. Recompute it (tumble model fix)",
                     who, tensor_text(in.inertia_written), lambda(0), lambda(1), lambda(2))});
    return false;
  }
  // λ₃ ≤ λ₁ + λ₂ holds for every body, with equality for a flat one; 1e-6 of λ₃ allows for values
  // written with six or seven significant digits.
  if (lambda(2) > (lambda(0) + lambda(1)) + 1e-6 * lambda(2)) {
    findings.push_back(
        {"triangle_inequality", Severity::error,
         fmt::format("{}: the principal moments {:.6g}, {:.6g}, {:.6g} break the triangle inequality "
                     "(the largest exceeds the sum of the others by {:.3g}): no body has them. Recompute the "
                     "tensor (tumble model fix)",
                     who, lambda(0), lambda(1), lambda(2), lambda(2) - lambda(0) - lambda(1))});
    return false;
  }
  return true;
}

/// The scale a mesh's coordinates were probably meant to have, if its implied density says one:
/// millimetres read as metres make the volume 1e9 times too large and the density as much too small.
std::optional<std::pair<double, const char*>> implied_scale(double rho) {
  const auto plausible = [](double x) { return x >= kDensityPlausibleLow && x <= kDensityPlausibleHigh; };
  if (plausible(rho * 1e9)) return std::make_pair(0.001, "millimetres");
  if (plausible(rho * 1e6)) return std::make_pair(0.01, "centimetres");
  if (plausible(rho * 1e-9)) return std::make_pair(1000.0, "kilometres");
  return std::nullopt;
}

/// How the format says a mesh's scale: the words to fix it with.
std::string scale_text(Format format, double s) {
  const std::string v = fmt::format("{} {} {}", s, s, s);
  switch (format) {
    case Format::urdf:
      return fmt::format("scale=\"{}\" (<mesh filename=... scale=\"{}\"/>)", v, v);
    case Format::mjcf:
      return fmt::format("scale=\"{}\" (on its <asset><mesh>)", v);
    case Format::sdf:
      return fmt::format("<scale>{}</scale> (in its <mesh>)", v);
  }
  return v;
}

/// The explanation of a tensor that differs from the computed one, if one of the usual mistakes
/// accounts for it: its text, or empty.
std::string explain(const Inertial& in, const Mat3& I_authored, const Mat3& I_computed, const Vec3& com,
                    double mass, std::string& code) {
  const auto matches = [&](const Mat3& candidate) {
    return relative_difference(candidate, I_computed) <= kTensorExplained;
  };
  const Mat3 about_origin = I_computed + mass * (com.dot(com) * Mat3::Identity() - com * com.transpose());
  if (relative_difference(I_authored, about_origin) <= kTensorExplained) {
    code = "tensor_about_origin";
    return "it is the tensor about the link's origin, not about the centre of mass (the parallel-axis term "
           "m((c·c)I − c cᵀ) was not taken off)";
  }
  const Mat3& R = in.frame.R;
  if (in.rotated) {
    if (matches(in.inertia_written)) {
      code = "inertial_rotation";
      return "it is right in the link's own axes: the inertial's rotation should be none, or the "
             "tensor "
             "was rotated before it was written and the rotation applied again";
    }
    if (matches(R * R * in.inertia_written * R.transpose() * R.transpose())) {
      code = "inertial_rotation";
      return "it is right only with the inertial's rotation applied twice";
    }
    if (matches(R.transpose() * in.inertia_written * R)) {
      code = "inertial_rotation";
      return "it is right with the inertial's rotation inverted (its angles of the wrong sign or order)";
    }
  }
  // A permuted diagonal: the moments written for the wrong axes.
  static constexpr std::array<std::array<int, 3>, 5> kPermutations{
      {{1, 0, 2}, {2, 1, 0}, {0, 2, 1}, {1, 2, 0}, {2, 0, 1}}};
  static constexpr std::array<const char*, 3> kAxis{"x", "y", "z"};
  for (const auto& p : kPermutations) {
    Mat3 P = Mat3::Zero();
    for (int i = 0; i < 3; ++i) P(i, p[static_cast<std::size_t>(i)]) = 1;
    if (matches(P * I_authored * P.transpose())) {
      code = "tensor_mismatch";
      return fmt::format(
          "its moments are those of the axes permuted: ixx, iyy, izz belong to i{0}{0}, i{1}{1}, "
          "i{2}{2}",
          kAxis[static_cast<std::size_t>(p[0])], kAxis[static_cast<std::size_t>(p[1])],
          kAxis[static_cast<std::size_t>(p[2])]);
    }
  }
  // A product of inertia of the wrong sign (the two conventions: I_xy = −∫xy dm, or +).
  static constexpr std::array<std::array<int, 2>, 3> kProducts{{{0, 1}, {0, 2}, {1, 2}}};
  for (int mask = 1; mask < 8; ++mask) {
    Mat3 F = I_authored;
    std::string names;
    for (int k = 0; k < 3; ++k) {
      if (!(mask & (1 << k))) continue;
      const auto [i, j] = kProducts[static_cast<std::size_t>(k)];
      F(i, j) = F(j, i) = -F(i, j);
      names += fmt::format("{}i{}{}", names.empty() ? "" : ", ", kAxis[static_cast<std::size_t>(i)],
                           kAxis[static_cast<std::size_t>(j)]);
    }
    if (matches(F)) {
      code = "tensor_mismatch";
      return fmt::format(
          "its product{} of inertia {} ha{} the wrong sign (URDF, SDF and MJCF take I_xy = −∫xy dm)",
          mask == 1 || mask == 2 || mask == 4 ? "" : "s", names,
          mask == 1 || mask == 2 || mask == 4 ? "s" : "ve");
    }
  }
  return {};
}

/// Authored against computed tensors, at the authored mass, each about its own centre of mass.
void compare_tensors(const std::string& who, const Inertial& in, const ComputedMass& computed,
                     std::vector<Finding>& findings) {
  const MassProperties& c = computed.properties;
  const Mat3 I_authored = in.inertia_link();
  const Mat3 I_computed = c.inertia * (in.mass / c.mass);
  const double d = relative_difference(I_authored, I_computed);
  std::string code;
  const std::string why = explain(in, I_authored, I_computed, c.center_of_mass, in.mass, code);
  if (!why.empty() && d > kTensorExplained) {
    findings.push_back({code, Severity::error,
                        fmt::format("{}: the inertia tensor differs from the geometry's by {:.0f} % and {}. "
                                    "Written: {}; from the geometry: {}. Fix it with tumble model fix",
                                    who, 100 * d, why, tensor_text(I_authored), tensor_text(I_computed))});
    return;
  }
  if (d <= kTensorWarning) return;
  findings.push_back(
      {"tensor_mismatch", d > kTensorError ? Severity::error : Severity::warning,
       fmt::format(
           "{}: the inertia tensor differs from the geometry's ({}) at the same mass by {:.0f} % of its "
           "largest moment (a warning past {:.0f} %, an error past {:.0f} %). Written: {}; from the "
           "geometry: {}. If the link is not uniform (motors, hollow castings) this may be right; else "
           "tumble model fix recomputes it",
           who, computed.geometry, 100 * d, 100 * kTensorWarning, 100 * kTensorError, tensor_text(I_authored),
           tensor_text(I_computed))});
}

}  // namespace

void judge(const RobotModel& model, const Link& link, const LinkAudit& audit, const LinkSolids* solids,
           std::vector<Finding>& findings) {
  if (!audit.authored) return;
  const Inertial& in = *audit.authored;
  const std::string who = fmt::format("link '{}' (<inertial> at {})", link.name, where(model, in.span.line));
  const bool valid = judge_alone(who, in, findings);
  if (!audit.computed || !solids) return;
  const ComputedMass& computed = *audit.computed;
  const double V = computed.properties.volume;
  if (in.mass == 0) {
    if (in.inertia_written.isZero(0.0)) {
      findings.push_back(
          {"zero_mass_with_geometry", Severity::warning,
           fmt::format("{}: the mass is 0 but the link has {} of {:.4g} m³: a simulator takes it "
                       "for a massless frame. If it is a real part, give it its mass (tumble model "
                       "fix --keep none --density RHO computes one)",
                       who, computed.geometry, V)});
    }
    return;
  }
  if (in.mass < 0) return;
  // The density the authored mass implies, and what it says about the mesh's units.
  const double rho = in.mass / V;
  const auto scale = computed.from_meshes ? implied_scale(rho) : std::nullopt;
  if (scale && !(rho >= kDensityPlausibleLow && rho <= kDensityPlausibleHigh)) {
    findings.push_back(
        {"mesh_scale", Severity::error,
         fmt::format("{}: the mass {} kg over the geometry's {:.4g} m³ is {:.3g} kg/m³: the mesh is probably "
                     "in {} and read as metres. Give the mesh {}",
                     who, in.mass_text, V, rho, scale->second, scale_text(model.format, scale->first))});
    return;  // the tensors of a geometry 1000 times too large say nothing more
  }
  if (!(rho >= kDensityPlausibleLow && rho <= kDensityPlausibleHigh)) {
    const bool impossible = rho < kDensityPossibleLow || rho > kDensityPossibleHigh;
    findings.push_back(
        {"implied_density", impossible ? Severity::error : Severity::warning,
         fmt::format(
             "{}: the mass {} kg over the geometry's {:.4g} m³ ({}) is {:.3g} kg/m³, {} ({:.0f}–{:.0f} kg/m³ "
             "is plausible). Check the mass, and that the {} geometry is the part's own",
             who, in.mass_text, V, computed.geometry, rho,
             impossible ? "which no solid material has" : "unusual for a solid part", kDensityPlausibleLow,
             kDensityPlausibleHigh, computed.geometry.substr(0, computed.geometry.find(' ')))});
  }
  // Where the authored centre of mass is: in the geometry, in its convex hull, or outside both.
  const Vec3 com = in.frame.p;
  double size = 0;
  Eigen::AlignedBox3d box;
  for (const Vec3& p : solids->points) box.extend(p);
  if (!box.isEmpty()) size = box.diagonal().norm();
  bool com_judged = false;
  // A COM where the geometry's own is (to 1 % of the link's size) is right for a uniform link whatever
  // its shape, inside the solid or not (a U-shaped link's is between its arms): only another is tested.
  const bool at_geometry_com = (com - computed.properties.center_of_mass).norm() <= 0.01 * size;
  if (size > 0 && !at_geometry_com && !solids->contains(com, 1e-9 * size)) {
    // Tessellated primitives fall inside their surfaces by < 0.9 % of a radius (audit.cpp): 1 % of the
    // size keeps a COM on a cylinder's wall from counting as outside its hull.
    const double d = distance_to_hull(solids->points, com);
    const bool outside_hull = d > 0.01 * size;
    findings.push_back(
        {"com_outside_geometry", outside_hull ? Severity::error : Severity::warning,
         fmt::format("{}: the centre of mass ({:.6g}, {:.6g}, {:.6g}) is outside the link's {}{}; the "
                     "geometry's is "
                     "at ({:.6g}, {:.6g}, {:.6g}). {}",
                     who, com.x(), com.y(), com.z(), computed.geometry,
                     outside_hull ? fmt::format(", {:.3g} m beyond its convex hull", d)
                                  : " but inside its convex hull",
                     computed.properties.center_of_mass.x(), computed.properties.center_of_mass.y(),
                     computed.properties.center_of_mass.z(),
                     outside_hull ? "No body's centre of mass is outside its convex hull: fix the inertial's "
                                    "position (tumble "
                                    "model fix)"
                                  : "A hollow or U-shaped link can have it so; check it")});
    com_judged = true;
  }
  if (!com_judged && size > 0 && (com - computed.properties.center_of_mass).norm() > kComWarning * size) {
    const Vec3& c = computed.properties.center_of_mass;
    findings.push_back(
        {"com_mismatch", Severity::warning,
         fmt::format("{}: the centre of mass ({:.6g}, {:.6g}, {:.6g}) is {:.3g} m from the geometry's "
                     "({:.6g}, {:.6g}, {:.6g}), {:.0f} % of the link's size. Right for a link whose "
                     "mass is not uniform; else tumble model fix moves it",
                     who, com.x(), com.y(), com.z(), (com - c).norm(), c.x(), c.y(), c.z(),
                     100 * (com - c).norm() / size)});
  }
  if (valid) compare_tensors(who, in, computed, findings);
}

void judge_lumped(const RobotModel& model, const LinkAudit& lumped, std::vector<Finding>& findings) {
  if (!lumped.authored || !lumped.computed) return;
  const std::string who = fmt::format("'{}' (links {} welded by fixed joints, from {})", lumped.name,
                                      fmt::join(lumped.parts, ", "), where(model, lumped.line));
  if (judge_alone(who, *lumped.authored, findings))
    compare_tensors(who, *lumped.authored, *lumped.computed, findings);
}

}  // namespace tumble::robot
