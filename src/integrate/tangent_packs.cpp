#include "tangent_packs.hpp"

#include <algorithm>
#include <array>
#include <tuple>
#include <vector>

#include "rk4_steps.hpp"

namespace tumble::tangent_packs {
namespace {

using engine::Pack;
constexpr size_t W = engine::kWidth;
using TS = TangentScalar;

/// The numbers of one body a lane carries: its variables, mass, principal moments, and the force it
/// bears (constant: uniform fields), on double dual numbers or on packs.
template <class T>
struct Body {
  Coordinates<T> x;
  T m;
  Vec3T<T> Lambda;
  Vec3T<T> f;
};

/// A body's 13 variables in one order (o, q's coefficients, v, ω), for moving them between layouts.
template <class C>  // Coordinates<T>, const or not
auto variables(C& x) {
  auto& q = x.q.coeffs();
  return std::array{&x.o(0), &x.o(1), &x.o(2), &q(0),       &q(1),       &q(2),      &q(3),
                    &x.v(0), &x.v(1), &x.v(2), &x.omega(0), &x.omega(1), &x.omega(2)};
}
/// All 20 numbers of a Body: its variables, then m, Λ and f.
template <class T>
std::array<T*, 20> numbers(Body<T>& b) {
  std::array<T*, 20> all;
  const auto x = variables(b.x);
  std::copy(x.begin(), x.end(), all.begin());
  const std::array<T*, 7> rest = {&b.m, &b.Lambda(0), &b.Lambda(1), &b.Lambda(2), &b.f(0), &b.f(1), &b.f(2)};
  std::copy(rest.begin(), rest.end(), all.begin() + 13);
  return all;
}

/// Which body and slots each lane holds: lane ℓ, body ℓ / groups, slots from (ℓ mod groups)·directions;
/// lanes past the last (the last pack's padding) repeat it.
struct Layout {
  int directions = 4;  ///< slots per lane
  int slots = 0;       ///< slots per body
  size_t groups = 1, lanes = 0;
  Layout(int k, int slots_in_use, size_t bodies)
      : directions(k),
        slots(slots_in_use),
        groups(static_cast<size_t>((slots_in_use + k - 1) / k)),
        lanes(bodies * groups) {}
  size_t packs() const { return (lanes + W - 1) / W; }
  size_t clamped(size_t lane) const { return std::min(lane, lanes - 1); }
  size_t body(size_t lane) const { return clamped(lane) / groups; }
  int first_slot(size_t lane) const { return static_cast<int>(clamped(lane) % groups) * directions; }
};

/// The uniform field's force on body i, f = Σ m g over the models, as TangentRates::loads sums it
/// (zero, then += m g in model order; g seeded where x carries the models' parameters).
Vec3T<TS> uniform_force(const Model& model, const TangentCoordinates& x, size_t i) {
  Vec3T<TS> f = Vec3T<TS>::Zero();
  for (size_t k = 0; k < model.forces.size(); ++k) {
    const Vec3 g = *model.forces[k]->uniform_acceleration();
    const bool seeded = k < x.force_parameters.size();
    const Vec3T<TS> gk =
        seeded ? Vec3T<TS>(x.force_parameters[k][0], x.force_parameters[k][1], x.force_parameters[k][2])
               : g.cast<TS>();
    f += x.m[i] * gk;
  }
  return f;
}

/// Pack p's numbers from the bodies' (each lane its body's value and its group's slots).
template <class DP>
void gather(const Layout& layout, size_t p, std::vector<Body<TS>>& bodies, Body<DP>& out) {
  std::array<std::array<TS*, 20>, W> from;
  std::array<int, W> first;
  for (size_t l = 0; l < W; ++l) {
    from[l] = numbers(bodies[layout.body(p * W + l)]);
    first[l] = layout.first_slot(p * W + l);
  }
  const std::array<DP*, 20> to = numbers(out);
  alignas(64) double lane[W];
  for (size_t n = 0; n < 20; ++n) {
    for (size_t l = 0; l < W; ++l) lane[l] = from[l][n]->v;
    to[n]->v = Pack::load_aligned(lane);
    for (int j = 0; j < layout.directions; ++j) {
      for (size_t l = 0; l < W; ++l) {
        const int slot = first[l] + j;
        lane[l] = slot < layout.slots ? from[l][n]->d[static_cast<size_t>(slot)] : 0.0;
      }
      to[n]->d[static_cast<size_t>(j)] = Pack::load_aligned(lane);
    }
  }
}

/// The inverse of gather for the variables (the only numbers a step changes); padding lanes are dropped.
template <class DP>
void scatter(const Layout& layout, size_t p, const Coordinates<DP>& in,
             std::vector<Coordinates<TS>>& bodies) {
  constexpr int K = std::tuple_size_v<decltype(DP::d)>;
  const auto from = variables(in);
  alignas(64) double lane[K + 1][W];
  for (size_t n = 0; n < from.size(); ++n) {
    from[n]->v.store_aligned(lane[0]);
    for (int j = 0; j < K; ++j) from[n]->d[static_cast<size_t>(j)].store_aligned(lane[j + 1]);
    for (size_t l = 0; l < W && p * W + l < layout.lanes; ++l) {
      TS& to = *variables(bodies[layout.body(p * W + l)])[n];
      const int first = layout.first_slot(p * W + l);
      to.v = lane[0][l];
      for (int j = 0; j < K && first + j < layout.slots; ++j) {
        to.d[static_cast<size_t>(first + j)] = lane[j + 1][l];
      }
    }
  }
}

/// One pack through the steps: step_tangent's loop on DP = Dual<Pack, K>.
template <Method M, class DP>
void step_pack(Formulation F, Body<DP>& b, std::span<const double> lengths) {
  const MassConstants<DP> c = mass_constants<DP>(b.m, b.Lambda);
  const Vec3T<DP> tau = Vec3T<DP>::Zero();
  Coordinates<DP> x = b.x;
  for (const double h : lengths) {
    if constexpr (M == Method::euler) {
      x = advanced<DP>(x, DP(h), newton_euler<DP>(F, c, x, b.f, tau));
    } else if constexpr (M == Method::semi_implicit_euler) {
      x = semi_implicit_euler_update<DP>(F, x, DP(h), newton_euler<DP>(F, c, x, b.f, tau));
    } else {
      Coordinates<DP> y = x;
      CoordinateRates<DP> A;
      for (int s = 0; s < 4; ++s) {
        const CoordinateRates<DP> k = newton_euler<DP>(F, c, y, b.f, tau);
        const Coordinates<DP> next = rk4::stage<DP>(s, DP(rk4::stage_length(s, h)), x, k, A);
        (s < 3 ? y : x) = next;
      }
    }
  }
  b.x = x;
}

/// Every pack of `layout` through the steps on Dual<Pack, K>.
template <int K>
void steps_on(const Layout& layout, Method method, Formulation F, std::vector<Body<TS>>& bodies,
              TangentCoordinates& x, std::span<const double> lengths) {
  using DP = Dual<Pack, K>;
  Body<DP> pack;
  for (size_t p = 0; p < layout.packs(); ++p) {
    gather(layout, p, bodies, pack);
    switch (method) {
      case Method::euler:
        step_pack<Method::euler>(F, pack, lengths);
        break;
      case Method::semi_implicit_euler:
        step_pack<Method::semi_implicit_euler>(F, pack, lengths);
        break;
      case Method::rk4:
        step_pack<Method::rk4>(F, pack, lengths);
        break;
    }
    scatter(layout, p, pack.x, x.bodies);
  }
}

}  // namespace

bool applies(const Model& model) {
  return std::all_of(model.forces.begin(), model.forces.end(), [](const auto& f) {
    return f->uniform_acceleration().has_value() && f->parameters().size() == 3;
  });
}

bool steps(Method method, const Model& model, Formulation formulation, TangentCoordinates& x,
           std::span<const double> lengths, int slots) {
  if (!applies(model)) return false;
  const size_t n = x.bodies.size();
  if (n == 0 || lengths.empty()) return true;
  std::vector<Body<TS>> bodies(n);
  for (size_t i = 0; i < n; ++i) bodies[i] = {x.bodies[i], x.m[i], x.Lambda[i], uniform_force(model, x, i)};
  // Slots per lane: 8 and more spill registers (tangent_pack_bench: 3–4.5 state steps a direction);
  // a pack-step of Dual<Pack, 2> costs 0.53 of one of Dual<Pack, 4> (sensitivity_bench, N = 1000, 15
  // slots, AVX-512: 0.59 against 1.12 µs), so 2 where it fills fewer packs than that (one body: 8 lanes
  // of 2 in one pack, against 4 of 4 in half a pack), else 4.
  slots = std::clamp(slots, 1, kTangentDirections);
  const Layout two(2, slots, n), four(4, slots, n);
  if (0.53 * static_cast<double>(two.packs()) < static_cast<double>(four.packs())) {
    steps_on<2>(two, method, formulation, bodies, x, lengths);
  } else {
    steps_on<4>(four, method, formulation, bodies, x, lengths);
  }
  return true;
}

}  // namespace tumble::tangent_packs
