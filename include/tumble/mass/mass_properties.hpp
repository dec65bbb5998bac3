#pragma once
// Mass properties of a rigid body: the tutorial's section IV as a value type.
//
// All quantities are expressed in one frame, the body's *reference frame* (the frame its shape, mesh
// or data sheet is written in). The inertia tensor is about the centre of mass c, with axes parallel
// to the reference frame — the tutorial's ^sI when the reference frame is aligned with {w}:
//
//   I = ∫ ρ ((r·r) I₃ − r rᵀ) dV,   r = x − c.
#include <string>

#include "tumble/math/types.hpp"

namespace tumble {

/// m((b·b)I₃ − b bᵀ): what translating the reference point by b adds to the inertia tensor
/// (tutorial, "Inertia Tensor Under Translation": ^tI = ^sI + m((b·b)I₃ − bbᵀ)).
Mat3 parallel_axis_term(double m, const Vec3& b);

/// The spectral decomposition I = U Λ Uᵀ (tutorial, "Principal Axes").
struct PrincipalAxes {
  Vec3 Lambda;  ///< principal moments λ₁ ≤ λ₂ ≤ λ₃ (kg·m²)
  Mat3 U;       ///< proper rotation (det U = +1) whose columns are the principal axes
};

/// Options for principal_axes().
struct PrincipalAxesOptions {
  /// Moments closer than this, relative to the largest, count as equal; the axes of such a group are
  /// then chosen canonically (see principal_axes) and their moments are set to the group's mean.
  double repeated_tolerance = 1e-10;
};

/// Principal axes of a symmetric tensor: Λ ascending, U a proper rotation, deterministic.
///
/// Canonical choice: each axis that is determined up to sign points so that its largest-magnitude
/// component is positive (ties go to the lower coordinate index); the last axis is the cross product of
/// the other two, which makes det U = +1. Where moments repeat, the eigenvectors of that group are not
/// determined by I; tumble then takes the coordinate axis of the reference frame most perpendicular to
/// the unique axis, projected onto the degenerate plane, as the first axis of the group; for a sphere
/// (all three equal) U = I₃. The same tensor always yields the same U.
[[nodiscard]] PrincipalAxes principal_axes(const Mat3& I, const PrincipalAxesOptions& options = {});

/// Options for MassProperties::validate().
struct ValidityOptions {
  /// Relative slack for symmetry, positivity and the triangle inequality, as a fraction of the largest
  /// principal moment. Flat bodies (thin plates) sit exactly on λ₃ = λ₁ + λ₂, so the default allows
  /// rounding in tensors computed from meshes.
  double tolerance = 1e-9;
};

/// Mass m, centre of mass c and inertia tensor about c, in the body's reference frame.
struct MassProperties {
  double mass = 0.0;                   ///< m (kg)
  Vec3 center_of_mass = Vec3::Zero();  ///< c (m), in the reference frame
  Mat3 inertia = Mat3::Zero();         ///< I about c, reference-frame axes (kg·m²)
  double volume = 0.0;                 ///< volume of material (m³); 0 where not known (explicit data)

  /// A body given by its mass, centre and inertia about its centre (e.g. from a data sheet).
  static MassProperties from_inertia(double mass, const Vec3& center_of_mass, const Mat3& inertia,
                                     double volume = 0.0);

  /// A body given by its inertia about some `point` instead of about its centre of mass:
  /// I_c = I_point − m((b·b)I₃ − bbᵀ), b = point − c ("back to the centre of mass").
  static MassProperties from_inertia_about(double mass, const Vec3& center_of_mass,
                                           const Mat3& inertia_about_point, const Vec3& point,
                                           double volume = 0.0);

  /// Inertia about `point` (axes parallel to the reference frame): ^tI = I + m((b·b)I₃ − bbᵀ).
  Mat3 inertia_about(const Vec3& point) const;

  /// The same body described in a frame {q} rotated from the reference frame by R (columns of R are
  /// {q}'s axes in reference coordinates): ^qI = Rᵀ I R and ^q c = Rᵀ c.
  MassProperties expressed_in(const Mat3& R) const;

  /// The body placed in a parent frame by the pose (R, t), x_parent = R x + t: c' = R c + t,
  /// I' = R I Rᵀ. Use it to put a part where it belongs before combining.
  MassProperties transformed(const Mat3& R, const Vec3& t) const;

  /// Moment of inertia about the axis through `point` with direction `axis` (need not be unit):
  /// I_l = l̂ᵀ I l̂ + m |(point − c) × l̂|² (tutorial "Moment of Inertia" plus the parallel-axis term).
  double moment_about_axis(const Vec3& axis, const Vec3& point) const;
  /// Moment about the axis through the centre of mass: I_l = l̂ᵀ I l̂.
  double moment_about_axis(const Vec3& axis) const { return moment_about_axis(axis, center_of_mass); }

  /// Radius of gyration about an axis: k = √(I_l / m).
  double radius_of_gyration(const Vec3& axis, const Vec3& point) const;
  double radius_of_gyration(const Vec3& axis) const { return radius_of_gyration(axis, center_of_mass); }

  /// Principal moments (ascending) and axes of the inertia tensor about the centre of mass.
  PrincipalAxes principal_axes(const PrincipalAxesOptions& options = {}) const {
    return tumble::principal_axes(inertia, options);
  }

  /// Throws InvalidMassProperties unless: mass and every entry finite, m > 0, I symmetric, I positive
  /// definite, and λ₃ ≤ λ₁ + λ₂ (each principal moment at most the sum of the other two). The
  /// message names the condition and gives the numbers; `what` (e.g. a body name) prefixes it.
  void validate(const ValidityOptions& options = {}, const std::string& what = "") const;
  /// validate() and principal_axes() for the price of one eigen-decomposition (validity is a
  /// condition on the principal moments).
  PrincipalAxes validated_principal_axes(const ValidityOptions& options = {},
                                         const std::string& what = "") const;

  /// Combine two parts into one body: masses add, centres are mass-weighted, tensors are moved to the
  /// common centre with the parallel-axis term. Both must be in the same reference frame.
  MassProperties& operator+=(const MassProperties& part);
  /// Remove a part (a hole): the same as adding a part of negative mass. The result must keep a
  /// positive mass; it is not validated here (call validate() on the finished body).
  MassProperties& operator-=(const MassProperties& part);
};

MassProperties operator+(MassProperties a, const MassProperties& b);
MassProperties operator-(MassProperties a, const MassProperties& b);

}  // namespace tumble
