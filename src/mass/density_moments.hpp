#pragma once
// The moments ∫ρ, ∫ρ r, ∫ρ r rᵀ summed over quadrature points, and the two-rule error estimate: the
// parts of integrate_density() shared by meshes and primitives (private to the mass layer).
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>

#include "pairwise_sum.hpp"
#include "tumble/mass/density.hpp"

namespace tumble::detail {

/// Sums, over quadrature points x with geometric weights w (volume element × rule weight),
///   V = Σ w,  M₀ = Σ w ρ(x),  M₁ = Σ w ρ(x) r,  M₂ = Σ w ρ(x) r rᵀ,   r = x − origin.
/// The origin should be near the centre of mass: M₂ − M₁M₁ᵀ/M₀ then loses little to cancellation.
/// Points are summed one after the other into a block; end_block() (once per tetrahedron or outer
/// quadrature node) hands the block to a pairwise sum, so rounding grows like log(blocks), not like the
/// number of points (10⁷ for a large mesh at high degree).
class MomentAccumulator {
 public:
  /// `where` names the body in messages ("mesh 'part.stl'", "sphere").
  MomentAccumulator(const DensityField& rho, const Vec3& origin, std::string where);

  /// Names the element (e.g. "the tetrahedron of triangle 7") in a message about a bad density value.
  void set_element(const char* kind, std::size_t index) {
    element_kind_ = kind;
    element_ = index;
  }

  /// Adds one point; throws InvalidArgument naming the point if ρ(x) is not finite.
  void add(const Vec3& x, double weight) {
    const double rho = rho_(x);
    if (!std::isfinite(rho)) bad_density(x, rho);
    const Vec3 r = x - origin_;
    const double wr = weight * rho;
    const Vec3 wrr = wr * r;
    block_[0] += weight;
    block_[1] += wr;
    block_[2] += wrr.x();
    block_[3] += wrr.y();
    block_[4] += wrr.z();
    block_[5] += wrr.x() * r.x();
    block_[6] += wrr.y() * r.y();
    block_[7] += wrr.z() * r.z();
    block_[8] += wrr.x() * r.y();
    block_[9] += wrr.x() * r.z();
    block_[10] += wrr.y() * r.z();
  }

  /// Ends the current block of points (see the class comment).
  void end_block() {
    sum_.add(block_);
    block_ = {};
  }

  /// m = M₀, c = origin + M₁/m, I = tr(S)I₃ − S with S = M₂ − M₁M₁ᵀ/m (the second moment about c).
  /// Ends the last block. Throws InvalidArgument if m ≤ 0.
  MassProperties finish();

 private:
  [[noreturn]] void bad_density(const Vec3& x, double rho) const;

  const DensityField& rho_;
  Vec3 origin_;
  std::string where_;
  const char* element_kind_ = nullptr;
  std::size_t element_ = 0;
  // V, M₀, M₁ (x, y, z), M₂ (xx, yy, zz, xy, xz, yz).
  using Terms = PairwiseSum<11>::Terms;
  Terms block_{};
  PairwiseSum<11> sum_;
};

/// Checks the requested degree and the density field; returns the odd rule degree d ≥ degree.
/// Throws InvalidArgument naming the supported range [kMinDensityDegree, kMaxDensityDegree].
int density_rule_degree(int degree, const DensityField& rho, const std::string& where);

/// Integrates with rule degrees d and d + 2 and returns the degree d + 2 result with the relative
/// difference as estimated_error (see density.hpp for why the higher one).
DensityResult integrate_with_estimate(int d, const std::function<MassProperties(int)>& integrate);

/// max(|Δm|/m, max|ΔI_ij| / max|I_ij|, |Δc|/k), k = √(tr I / 2m), relative to `reference`.
double relative_difference(const MassProperties& other, const MassProperties& reference);

}  // namespace tumble::detail
