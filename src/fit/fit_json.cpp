// The fit as JSON, the one writer behind `tumble fit` and tumble.fit() in Python. Keys in the order
// docs/fit.md lists them; a number that is not finite (a quantity the data do not determine) is
// written as null, never as NaN.
#include <nlohmann/json.hpp>

#include <cmath>

#include "tumble/fit/gyro_fit.hpp"

namespace tumble::fit {
namespace {

using json = nlohmann::ordered_json;

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
json vec(const Vec3& v) { return json::array({number(v.x()), number(v.y()), number(v.z())}); }
json matrix(const Mat3& M) { return json::array({vec(M.row(0)), vec(M.row(1)), vec(M.row(2))}); }

/// JSON indented by two spaces as dump(2) does, but an array of numbers (a vector, a matrix's row) or of
/// names on one line, so that a 3×3 matrix reads as three rows.
void write(const json& j, int indent, std::string& out) {
  const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
  if (j.is_object()) {
    if (j.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
      if (!first) out += ",\n";
      out += pad;
      out += json(it.key()).dump();
      out += ": ";
      write(it.value(), indent + 2, out);
      first = false;
    }
    out += '\n';
    out.append(static_cast<std::size_t>(indent), ' ');
    out += '}';
  } else if (j.is_array()) {
    bool flat = true;
    for (const json& e : j)
      flat = flat && !e.is_structured() && (!e.is_string() || e.get_ref<const std::string&>().size() < 16);
    if (flat) {
      out += "[";
      for (std::size_t i = 0; i < j.size(); ++i) {
        if (i > 0) out += ", ";
        out += j[i].dump();
      }
      out += "]";
      return;
    }
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      if (i > 0) out += ",\n";
      out += pad;
      write(j[i], indent + 2, out);
    }
    out += '\n';
    out.append(static_cast<std::size_t>(indent), ' ');
    out += ']';
  } else {
    out += j.dump();
  }
}

}  // namespace

std::string fit_json(const FitResult& f) {
  json out;
  out["verdict"] = f.determined ? "determined" : "not determined";
  out["reason"] = f.reason;
  out["samples"] = f.samples;
  out["t0"] = f.t0;
  out["duration"] = f.duration;
  out["sigma"] = f.sigma;
  out["scale"] = f.absolute ? "absolute" : "trace";
  out["unit"] = f.absolute ? "kg m^2" : "trace(J) = 1";

  json inertia;
  inertia["J"] = matrix(f.J);
  inertia["J_sigma"] = matrix(f.J_sigma);
  inertia["principal_moments"] = vec(f.principal_moments.value);
  inertia["principal_moments_sigma"] = vec(f.principal_moments.sigma);
  // Each principal axis as a row: axes[i] is the axis of principal_moments[i], in sensor axes.
  inertia["principal_axes"] = matrix(f.principal_axes.transpose());
  inertia["principal_axes_sigma_rad"] = vec(f.axis_sigma);
  inertia["ratios"] = json::array({number(f.ratios[0]), number(f.ratios[1])});
  inertia["ratios_sigma"] = json::array({number(f.ratios_sigma[0]), number(f.ratios_sigma[1])});
  inertia["positive_definite"] = f.positive_definite;
  inertia["triangle_inequality"] = f.triangle_inequality;
  out["inertia"] = inertia;

  out["omega0"] = vec(f.omega0.value);
  out["omega0_sigma"] = vec(f.omega0.sigma);
  if (f.bias_estimated) {
    out["bias"] = vec(f.bias.value);
    out["bias_sigma"] = vec(f.bias.sigma);
  } else {
    out["bias"] = nullptr;
    out["bias_sigma"] = nullptr;
  }

  json residuals;
  residuals["count"] = f.residuals;
  residuals["rms_sigma"] = number(f.rms_sigma);
  residuals["rms"] = number(f.rms);
  residuals["chi2"] = number(f.chi2);
  residuals["dof"] = static_cast<long>(f.residuals) - static_cast<long>(f.parameters.size());
  out["residuals"] = residuals;

  json covariance;
  covariance["parameters"] = f.parameter_names;
  covariance["values"] = json::array();
  for (Eigen::Index i = 0; i < f.parameters.size(); ++i)
    covariance["values"].push_back(number(f.parameters[i]));
  covariance["matrix"] = json::array();
  for (Eigen::Index i = 0; i < f.covariance.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < f.covariance.cols(); ++j) row.push_back(number(f.covariance(i, j)));
    covariance["matrix"].push_back(row);
  }
  covariance["condition_number"] = number(f.condition_number);
  out["covariance"] = covariance;

  json solver;
  solver["iterations"] = f.iterations;
  solver["starts"] = f.starts;
  solver["termination"] = f.termination;
  solver["substep"] = f.substep;
  solver["integration_error"] = number(f.integration_error);
  out["solver"] = solver;
  out["notes"] = f.notes;
  std::string text;
  write(out, 0, text);
  return text + "\n";
}

}  // namespace tumble::fit
