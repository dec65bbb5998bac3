// What telemetry must be before it is fitted, from a file or from arrays: one check, messages naming
// the sample's file:line when it came from a file, its index and time otherwise.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "tumble/error.hpp"
#include "tumble/fit/gyro_fit.hpp"

namespace tumble::fit {

void check_telemetry(const Telemetry& d) {
  const bool from_file = d.line.size() == d.t.size() && !d.line.empty();
  const auto where = [&](std::size_t k) {
    return from_file ? fmt::format("{}:{}", d.source, d.line[k]) : fmt::format("{}: sample {}", d.source, k);
  };
  const auto fail = [&](const std::string& what) {
    if (from_file) throw FileError(what);
    throw InvalidArgument(what);
  };
  const std::size_t n = d.t.size();
  if (d.omega.size() != n)
    fail(fmt::format("{}: {} times but {} angular velocities", d.source, n, d.omega.size()));
  if (!d.tau.empty() && d.tau.size() != n)
    fail(
        fmt::format("{}: {} times but {} torques (give one per sample, or none)", d.source, n, d.tau.size()));
  if (!d.h.empty() && d.h.size() != n)
    fail(fmt::format("{}: {} times but {} wheel momenta (give one per sample, or none)", d.source, n,
                     d.h.size()));
  for (std::size_t k = 0; k < n; ++k) {
    const auto finite = [](const Vec3& v) { return v.allFinite(); };
    if (!std::isfinite(d.t[k]) || !finite(d.omega[k]) || (!d.tau.empty() && !finite(d.tau[k])) ||
        (!d.h.empty() && !finite(d.h[k]))) {
      fail(fmt::format("{}: a value is not finite (NaN or infinite): every value must be a finite number",
                       where(k)));
    }
    if (k > 0 && !(d.t[k] > d.t[k - 1])) {
      fail(fmt::format(
          "{}: t = {} {} the previous sample's t = {} ({}): the samples must be in time order, "
          "without repeated times",
          where(k), d.t[k], d.t[k] == d.t[k - 1] ? "repeats" : "is before", d.t[k - 1], where(k - 1)));
    }
  }
  if (n < kMinSamples) {
    const std::string lines = from_file ? fmt::format(":{}: {} sample{} (lines {} to {})", d.line.back(), n,
                                                      n == 1 ? "" : "s", d.line.front(), d.line.back())
                                        : fmt::format(": {} sample{}", n, n == 1 ? "" : "s");
    fail(
        fmt::format("{}{}: the fit needs at least {} (3 components each, against up to 12 unknowns, with "
                    "residuals to spare)",
                    d.source, lines, kMinSamples));
  }
}

}  // namespace tumble::fit
