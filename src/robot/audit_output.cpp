// The audit as JSON (for tools and CI) and as a table (for a person at a terminal).
#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tumble/robot/audit.hpp"

namespace tumble::robot {

namespace {

using json = nlohmann::ordered_json;  // keys in the order written: model, format, links, ...

json vec(const Vec3& v) { return json::array({v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}); }

/// A tensor as its six numbers, by the names the files use.
json tensor(const Mat3& I) {
  return {{"ixx", I(0, 0) + 0.0}, {"iyy", I(1, 1) + 0.0}, {"izz", I(2, 2) + 0.0},
          {"ixy", I(0, 1) + 0.0}, {"ixz", I(0, 2) + 0.0}, {"iyz", I(1, 2) + 0.0}};
}

const char* severity_name(Severity s) { return s == Severity::error ? "error" : "warning"; }

std::size_t count(const ModelAudit& audit, Severity s) {
  std::size_t n = 0;
  for (const LinkAudit& l : audit.links)
    n += static_cast<std::size_t>(std::count_if(l.findings.begin(), l.findings.end(),
                                                [s](const Finding& f) { return f.severity == s; }));
  return n;
}

}  // namespace

std::string audit_json(const ModelAudit& audit) {
  json links = json::array();
  for (const LinkAudit& l : audit.links) {
    json link = {{"name", l.name}, {"line", l.line}};
    if (!l.parts.empty()) link["lumped"] = l.parts;
    link["skipped"] = l.skipped;
    if (l.authored) {
      // The COM in the link's frame, the tensor about it in the link's axes (the inertial's rotation
      // applied), and as written.
      link["authored"] = {{"mass", l.authored->mass},
                          {"com", vec(l.authored->frame.p)},
                          {"inertia", tensor(l.authored->inertia_link())},
                          {"inertia_written", tensor(l.authored->inertia_written)},
                          {"rotated", l.authored->rotated}};
    } else {
      link["authored"] = nullptr;
    }
    if (l.computed) {
      const MassProperties& c = l.computed->properties;
      link["computed"] = {{"volume", c.volume},
                          {"mass", c.mass},
                          {"com", vec(c.center_of_mass)},
                          {"inertia", tensor(c.inertia)},
                          {"geometry", l.computed->geometry},
                          {"mass_from", l.computed->basis}};
    } else {
      link["computed"] = nullptr;
    }
    json findings = json::array();
    for (const Finding& f : l.findings)
      findings.push_back({{"code", f.code}, {"severity", severity_name(f.severity)}, {"message", f.message}});
    link["findings"] = std::move(findings);
    links.push_back(std::move(link));
  }
  const json out = {{"model", audit.model.name},
                    {"format", format_name(audit.model.format)},
                    {"path", audit.model.path.string()},
                    {"links", std::move(links)},
                    {"notes", audit.notes},
                    {"errors", count(audit, Severity::error)},
                    {"warnings", count(audit, Severity::warning)}};
  return out.dump(2) + "\n";
}

std::string audit_table(const ModelAudit& audit) {
  std::string out = fmt::format("{} '{}' ({}): {} link{}\n", audit.model.path.string(), audit.model.name,
                                format_name(audit.model.format), audit.model.links.size(),
                                audit.model.links.size() == 1 ? "" : "s");
  std::size_t width = 4;
  for (const LinkAudit& l : audit.links) width = std::max(width, l.name.size());
  // The authored mass as written; the computed one as the geometry gives it (MJCF: MuJoCo's inference).
  out += fmt::format("  {:<{}}  {:>12}  {:>12}  {:>12}  {:>10}  {:<28}  {}\n", "link", width, "mass kg",
                     "computed kg", "volume m³", "ρ kg/m³", "computed from", "findings");
  for (const LinkAudit& l : audit.links) {
    const std::string mass = l.authored ? l.authored->mass_text : "—";
    std::string computed = "—", volume = "—", density = "—", from = "no geometry";
    if (l.computed) {
      computed = fmt::format("{:.6g}", l.computed->properties.mass);
      volume = fmt::format("{:.4g}", l.computed->properties.volume);
      from = l.computed->geometry;
      if (l.authored && l.authored->mass > 0 && l.computed->properties.volume > 0)
        density = fmt::format("{:.4g}", l.authored->mass / l.computed->properties.volume);
    }
    std::size_t errors = 0, warnings = 0;
    for (const Finding& f : l.findings) (f.severity == Severity::error ? errors : warnings)++;
    std::string findings = errors + warnings == 0 ? "ok" : "";
    if (errors) findings += fmt::format("{} error{}", errors, errors == 1 ? "" : "s");
    if (warnings)
      findings += fmt::format("{}{} warning{}", errors ? ", " : "", warnings, warnings == 1 ? "" : "s");
    out += fmt::format("  {:<{}}  {:>12}  {:>12}  {:>12}  {:>10}  {:<28}  {}\n", l.name, width, mass,
                       computed, volume, density, from, findings);
  }
  for (const LinkAudit& l : audit.links)
    for (const Finding& f : l.findings)
      out += fmt::format("{} [{}] {}\n", severity_name(f.severity), f.code, f.message);
  for (const LinkAudit& l : audit.links)
    for (const std::string& s : l.skipped) out += fmt::format("note: link '{}': {}\n", l.name, s);
  for (const std::string& n : audit.notes) out += fmt::format("note: {}\n", n);
  const std::size_t errors = count(audit, Severity::error), warnings = count(audit, Severity::warning);
  out += fmt::format("{} error{}, {} warning{}\n", errors, errors == 1 ? "" : "s", warnings,
                     warnings == 1 ? "" : "s");
  return out;
}

}  // namespace tumble::robot
