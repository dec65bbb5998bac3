#pragma once
// Mass properties of a body whose density varies from point to point, ρ = ρ(x) (tutorial section IV:
// "the density ρ is a function of ^s r"):
//
//   m = ∫ρ dV,   c = (1/m) ∫ρ x dV,   I = ∫ρ ((r·r)I₃ − r rᵀ) dV,   r = x − c,
//
// integrated numerically with rules of a selectable polynomial degree d: a rule of degree d integrates
// every polynomial of total degree ≤ d exactly. The inertia integrand is ρ times a quadratic, so all of
// m, c and I are exact (to rounding) when ρ is a polynomial of degree ≤ d − 2.
//
// Rules (src/mass/tet_quadrature.cpp, src/mass/line_quadrature.cpp):
//  - Tetrahedra: Grundmann–Möller simplex rules (Grundmann & Möller, SIAM J. Numer. Anal. 15, 1978),
//    odd degree 2s+1 in closed form, C(s+4, 4) points. Some weights are negative: fine for smooth ρ,
//    but they amplify rounding by Σ|w| = 2.6, 5.6, 12, 25, 54, 116, 251, 545 (in units of the volume)
//    for degrees 3, 5, ..., 17 — the cap on the degree keeps it near 1e-13 relative (tests measure
//    ≤ 6e-14 at the top degree). Positive-weight alternatives (conical products of Gauss–Jacobi rules)
//    need ~2–4× the points for the same degree. No Debian library provides simplex rules (Boost.Math
//    has only 1-D rules, Eigen none), so tumble writes this one.
//  - Primitives: tensor products of 1-D Gauss–Legendre rules (nodes from Boost.Math
//    legendre_p_zeros) and, in periodic angles, the trapezoid rule.
//
// Degrees: the requested `degree` must lie in [kMinDensityDegree, kMaxDensityDegree] = [2, 15]; the
// rules come in odd degrees, so an even request is raised to the next odd one, d. Every call integrates
// with d and with the next rule, d + 2, and RETURNS THE DEGREE d + 2 RESULT (DensityResult::degree
// says d + 2). Why the higher one: for smooth ρ the error falls by a large factor from one rule to the
// next, so |Q(d) − Q(d+2)| ≈ error of Q(d) ≫ error of Q(d+2): the estimate is then a conservative bound
// on the error of what is returned (the argument of Gauss–Kronrod and of local extrapolation). Returning
// Q(d) instead would make the estimate slightly *smaller* than its own error whenever successive errors
// share a sign (they do for ρ = exp(k·x), whose derivatives are all positive). The result is exact for
// polynomial ρ of degree ≤ d − 2 (both rules are then exact and the estimate is rounding).
#include <functional>
#include <string>
#include <vector>

#include "tumble/mass/mass_properties.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// Density in kg/m³ at a point given in the body reference frame.
using DensityField = std::function<double(const Vec3&)>;

/// Smallest and largest degree integrate_density() accepts (see the top of this header).
inline constexpr int kMinDensityDegree = 2;
inline constexpr int kMaxDensityDegree = 15;

struct DensityResult {
  /// Mass, centre of mass, inertia about it (reference-frame axes) and the geometric volume — from the
  /// rule of degree `degree`.
  MassProperties properties;
  /// Relative difference between the requested rule d and the returned rule d + 2: the largest of
  /// |Δm| / m, max |ΔI_ij| / max |I_ij| and |Δc| / k with k = √(tr I / 2m) the body's radius of
  /// gyration (a length scale of the body). An error estimate for degree d; for smooth ρ a
  /// conservative bound on the error of the returned (degree d + 2) numbers.
  double estimated_error = 0.0;
  /// Polynomial degree the returned rule integrates exactly: the requested degree raised to odd, + 2.
  int degree = 0;
  /// From the mesh checks, one line each (e.g. an inside-out mesh was integrated flipped); empty for
  /// primitives.
  std::vector<std::string> warnings;
};

/// Solid bounded by a closed mesh with density ρ(x).
///
/// The mesh is first checked and oriented by solid_mass_properties(mesh, MassSpec::density(1.0), name)
/// (throws MeshError naming the defect; an inside-out mesh is integrated flipped). The solid is then
/// decomposed into the signed fan of tetrahedra (c₀, a, b, c), one per triangle (a, b, c), from the
/// mesh's unit-density centroid c₀; each is integrated with the Grundmann–Möller rule. The signed fan
/// sums to the winding number of the closed mesh, so the decomposition is exact for any closed,
/// consistently oriented mesh, convex or not.
///
/// Where ρ is evaluated: in the fan tetrahedra, i.e. inside the convex hull of the mesh (c₀ lies in
/// it). For a convex mesh — or one star-shaped about c₀ — every point is inside the solid; for a
/// non-convex mesh some points lie outside the solid, where outside contributions cancel exactly in the
/// signed sum for polynomial ρ. So ρ must be defined, finite and smooth on the convex hull of the mesh.
///
/// Throws InvalidArgument for a degree outside [2, 15], an empty `rho`, a non-finite ρ at a quadrature
/// point (the message gives the point), or a total mass ≤ 0; MeshError for a mesh that bounds no solid.
/// `name` (e.g. the file name) prefixes messages.
DensityResult integrate_density(const TriangleMesh& mesh, const DensityField& rho, int degree,
                                const std::string& name = "mesh");

/// The same for a primitive shape in its own frame (shapes.hpp: centred at the origin, axis z; the
/// cone's base at z = 0 and apex at +z). Each shape is the image of a parameter box:
///   box       x, y, z                                  Gauss–Legendre in each
///   sphere    r, u = cos θ, φ: x = r(√(1−u²)cos φ, √(1−u²)sin φ, u), dV = r² dr du dφ
///   ellipsoid the sphere map scaled by (a, b, c), dV = abc r² dr du dφ
///   cylinder  s, φ, z: x = (s cos φ, s sin φ, z), dV = s ds dφ dz
///   capsule   the cylinder plus two hemispheres (the sphere map with u ∈ [0, 1], resp. [−1, 0])
///   cone      t, s, φ: x = (R(1−t)s cos φ, R(1−t)s sin φ, h t), dV = R²h (1−t)² s ds dt dφ
///   torus     s, θ, φ: x = ((R + s cos θ)cos φ, (R + s cos θ)sin φ, s sin θ), dV = s(R + s cos θ)
/// with Gauss–Legendre in s, r, u, t, z and the trapezoid rule in the periodic angles θ, φ.
///
/// Exact: a polynomial in x of degree ≤ d becomes, after the exact trapezoid sum over φ (exact for
/// trigonometric polynomials of degree < the number of points), a polynomial in the other parameters
/// (odd powers of √(1−u²) cancel in the φ sum), and the point counts are chosen for its degree. So every
/// primitive is exact for polynomial ρ of degree ≤ d − 2. For ρ analytic on the body the maps are
/// analytic and the error falls exponentially with d (spectral convergence of the trapezoid rule in
/// periodic angles, of Gauss–Legendre elsewhere); a kink or singularity in ρ gives only algebraic
/// convergence, and estimated_error says so. ρ is evaluated only inside the shape.
///
/// Throws InvalidArgument for an invalid shape (validate_shape), and as for meshes.
DensityResult integrate_density(const Shape& shape, const DensityField& rho, int degree);

}  // namespace tumble
