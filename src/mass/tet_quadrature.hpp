#pragma once
// Grundmann–Möller quadrature on a tetrahedron (private to the mass layer; see tet_quadrature.cpp).
#include <Eigen/Core>
#include <vector>

namespace tumble::detail {

/// A rule on any tetrahedron T = (v0, v1, v2, v3):  ∫_T f dV ≈ |T| Σ_k w_k f(Σ_j λ_kj v_j).
/// The weights sum to 1 (they are fractions of the volume); some are negative.
struct TetRule {
  int degree = 0;                            ///< every polynomial of total degree ≤ degree is exact
  std::vector<Eigen::Vector4d> barycentric;  ///< λ_k, one row per point, Σ_j λ_kj = 1
  std::vector<double> weights;               ///< w_k
};

/// The Grundmann–Möller rule of odd degree 2s+1 (s = 0, 1, ...), C(s+4, 4) points. Throws
/// InvalidArgument for an even or non-positive degree.
TetRule grundmann_moller_tet(int degree);

}  // namespace tumble::detail
