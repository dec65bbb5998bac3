#pragma once
// The exact torque-free motion of one body on dual numbers (issue 25): the drift of splitting and
// splitting4, and exact's whole rotation, differentiated. Values are EulerPoinsot's (the flow the
// integrators evaluate on double, bit for bit); derivatives come from
//  - the closed form on dual numbers wherever it is differentiable — a triaxial body off the separatrix
//    and not spinning about a principal axis: the set-up (triaxial_setup.hpp) and the evaluation
//    (euler_poinsot_flows.hpp's triaxial_state) instantiated on TangentScalar, sn, cn, dn and Π
//    differentiated with respect to their argument and parameter through the Landen recursion, Carlson's
//    R_J and Bulirsch's Π(n | m); O(1) at any τ;
//  - elsewhere (equal moments, where a moment's derivative breaks the symmetry the closed form assumes;
//    the separatrix and spins about a principal axis, where the closed form's parametrisation is
//    singular though the flow is smooth) the flow's Taylor series in time (free_body_taylor.hpp) on dual
//    numbers, summed in steps short enough that it converges to rounding; its cost grows with |ω|τ.
// Both are the same flow's derivatives, to rounding (tests/integrate/free_flow_tangent_test.cpp).
#include <optional>

#include "euler_poinsot_flows.hpp"
#include "tumble/dynamics/tangent.hpp"

namespace tumble {

class FreeFlowTangent {
 public:
  using T = TangentScalar;
  /// How the derivatives are computed: the closed form where it is differentiable (what the integrators
  /// use), or the Taylor series always (the tests' second method).
  enum class Method { closed_form_where_differentiable, taylor_series };
  /// The motion from q0 (body → world, unit) and omega_b0 of a body with principal moments Lambda, all
  /// carrying their derivatives. Throws InvalidArgument as EulerPoinsot does for bad values.
  FreeFlowTangent(const Vec3T<T>& Lambda, const QuatT<T>& q0, const Vec3T<T>& omega_b0,
                  Method method = Method::closed_form_where_differentiable);

  /// Whether at(τ) evaluates the closed form (the same cost for every τ); otherwise it sums the Taylor
  /// series from the start, at a cost proportional to |ω|τ.
  bool closed_form() const { return k_.has_value(); }
  /// q(τ) and ω_b(τ) with their derivatives.
  detail::FlowState<T> at(double tau) const;
  /// The values alone (EulerPoinsot).
  const EulerPoinsot& values() const { return values_; }

 private:
  EulerPoinsot values_;
  Vec3T<T> Lambda_, omega_b0_;
  QuatT<T> q0_;
  std::optional<detail::TriaxialConstants<T>> k_;
};

/// The values of s set to v's (the derivatives kept).
void set_values(detail::FlowState<TangentScalar>& s, const EulerPoinsot::State& v);

}  // namespace tumble
