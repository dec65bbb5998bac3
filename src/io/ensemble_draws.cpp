// The draws of an ensemble: Philox4x64-10 (Random123) keyed by the seed, counting (run, variation, k),
// so that run i's values depend on nothing but (seed, i). Each block of four 64-bit words gives up to
// four uniforms in (0, 1): the top 53 bits, offset by half a step, so that neither 0 nor 1 occurs (the
// logarithm of Box–Muller and the inverse normal CDF need an open interval).
#include <Random123/philox.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <numbers>

#include "ensemble_impl.hpp"

namespace tumble::ensemble {
namespace {

struct Uniforms {
  double u[4];
};

Uniforms uniforms(std::uint64_t seed, long run, size_t variation, std::uint64_t block) {
  r123::Philox4x64 philox;
  const r123::Philox4x64::ctr_type counter = {{static_cast<std::uint64_t>(run), variation, block, 0}};
  const r123::Philox4x64::key_type key = {{seed, 0x74756d626c65ull /* "tumble" */}};
  const auto r = philox(counter, key);
  Uniforms out{};
  for (int k = 0; k < 4; ++k) out.u[k] = (static_cast<double>(r.v[k] >> 11) + 0.5) * 0x1p-53;
  return out;
}

/// A standard normal from two uniforms (Box–Muller).
double standard_normal(double u1, double u2) {
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace

std::vector<double> draw(const Study& study, size_t v, long i) {
  const Variation& x = study.variations[v];
  const Uniforms r = uniforms(study.seed, i, v, 0);
  using K = Variation::Kind;
  switch (x.kind) {
    case K::uniform:
      return {x.low + (x.high - x.low) * r.u[0]};
    case K::normal:
      return {x.mean + x.std * standard_normal(r.u[0], r.u[1])};
    case K::lognormal:
      return {std::exp(x.mu + x.sigma * standard_normal(r.u[0], r.u[1]))};
    case K::truncated_normal: {
      // Inverse CDF between the bounds' probabilities: exact truncation, one draw, no rejection.
      const double alpha = (x.low - x.mean) / x.std, beta = (x.high - x.mean) / x.std;
      if (alpha <= 0.0 && beta >= 0.0) {  // the interval holds the mean: Φ is accurate at both ends
        const boost::math::normal_distribution<double> n(x.mean, x.std);
        const double a = boost::math::cdf(n, x.low), b = boost::math::cdf(n, x.high);
        const double p = a + (b - a) * r.u[0];
        return {std::clamp(boost::math::quantile(n, std::clamp(p, 1e-300, 1.0 - 0x1p-53)), x.low, x.high)};
      }
      // A tail: Φ(α) and Φ(β) both round to 1 (mean 1000, std 1, [1010, 1020]: every draw was `low`).
      // Drawn by the upper tail's probability Q(z) = 1 − Φ(z), which keeps its relative accuracy, in long
      // double (Q(40) ≈ 4e-350 is below double's range; the spec refuses intervals past 150σ). A lower
      // tail is the upper one mirrored.
      const bool upper = alpha > 0.0;
      const auto from = static_cast<long double>(upper ? alpha : -beta);  // from < to, from > 0
      const auto to = static_cast<long double>(upper ? beta : -alpha);
      const boost::math::normal_distribution<long double> unit;
      const long double q_from = boost::math::cdf(boost::math::complement(unit, from));
      const long double q_to = boost::math::cdf(boost::math::complement(unit, to));
      const long double q = q_from -
                            (q_from - q_to) * static_cast<long double>(r.u[0]);  // in (Q(to), Q(from)]
      const long double z = boost::math::quantile(boost::math::complement(unit, q));
      const double value = x.mean + x.std * static_cast<double>(upper ? z : -z);
      return {std::clamp(value, x.low, x.high)};
    }
    case K::rotation: {
      // Uniform on SO(3) (Shoemake 1992): a uniform point on the unit 3-sphere.
      const double a = std::sqrt(1.0 - r.u[0]), b = std::sqrt(r.u[0]);
      const double t1 = 2.0 * std::numbers::pi * r.u[1], t2 = 2.0 * std::numbers::pi * r.u[2];
      return {b * std::cos(t2), a * std::sin(t1), a * std::cos(t1), b * std::sin(t2)};  // w, x, y, z
    }
    case K::direction: {
      // Uniform on the sphere (Archimedes: z is uniform on [−1, 1]).
      const double z = 2.0 * r.u[0] - 1.0, phi = 2.0 * std::numbers::pi * r.u[1];
      const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
      return {x.magnitude * s * std::cos(phi), x.magnitude * s * std::sin(phi), x.magnitude * z};
    }
    case K::list:
      return {x.values[static_cast<size_t>(i) % x.values.size()]};
    case K::grid: {
      // Mixed radix over the grid variations in file order, the first fastest; runs beyond the grid repeat it.
      long place = i % study.grid_points;
      for (size_t g = 0; g < v; ++g) {
        if (study.variations[g].kind == K::grid)
          place /= static_cast<long>(study.variations[g].values.size());
      }
      return {x.values[static_cast<size_t>(place) % x.values.size()]};
    }
  }
  return {};
}

}  // namespace tumble::ensemble
