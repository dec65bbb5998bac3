// fix_model: each inertial element's bytes replaced by one written from the computed mass properties,
// in the file's own format and indentation; every other byte kept.
#include "tumble/robot/fix.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "tumble/error.hpp"
#include "xml_source.hpp"

namespace tumble::robot {

namespace {

/// The whitespace before the element on its line (empty if something else precedes it there).
std::string indent_of(const std::string& text, std::size_t begin) {
  std::size_t start = begin;
  while (start > 0 && (text[start - 1] == ' ' || text[start - 1] == '\t')) --start;
  if (start > 0 && text[start - 1] != '\n') return "";
  return text.substr(start, begin - start);
}

/// The indentation one level deeper: the element's first child's, else two spaces more.
std::string child_indent(const std::string& text, const SourceSpan& span, const std::string& indent) {
  const std::size_t newline = text.find('\n', span.begin);
  if (newline != std::string::npos && newline < span.end) {
    std::size_t i = newline + 1;
    while (i < span.end && (text[i] == ' ' || text[i] == '\t')) ++i;
    if (i > newline + 1 && text[i] == '<' && i - (newline + 1) > indent.size())
      return text.substr(newline + 1, i - (newline + 1));
  }
  return indent + "  ";
}

/// The line ending the file uses.
std::string newline_of(const std::string& text) {
  return text.find("\r\n") != std::string::npos ? "\r\n" : "\n";
}

std::string xyz(const Vec3& v) {
  return fmt::format("{} {} {}", number_text(v.x()), number_text(v.y()), number_text(v.z()));
}

/// The new element, in the format of the file.
std::string element_text(Format format, const std::string& comment, const std::string& mass, const Vec3& com,
                         const Mat3& I, const std::string& indent, const std::string& inner,
                         const std::string& nl) {
  const auto n = [](double x) { return number_text(x); };
  switch (format) {
    case Format::urdf:
      return fmt::format(
          "<inertial>{nl}{in}<!-- {c} -->{nl}{in}<origin xyz=\"{xyz}\" rpy=\"0 0 0\"/>{nl}"
          "{in}<mass value=\"{m}\"/>{nl}"
          "{in}<inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" "
          "izz=\"{}\"/>{nl}{i}</inertial>",
          n(I(0, 0)), n(I(0, 1)), n(I(0, 2)), n(I(1, 1)), n(I(1, 2)), n(I(2, 2)), fmt::arg("nl", nl),
          fmt::arg("in", inner), fmt::arg("c", comment), fmt::arg("xyz", xyz(com)), fmt::arg("m", mass),
          fmt::arg("i", indent));
    case Format::mjcf:
      // fullinertia is "ixx iyy izz ixy ixz iyz" in the body's axes (no quat: the frame is the body's).
      return fmt::format(
          "<!-- {} -->{}{}<inertial pos=\"{}\" mass=\"{}\" fullinertia=\"{} {} {} {} {} {}\"/>", comment, nl,
          indent, xyz(com), mass, n(I(0, 0)), n(I(1, 1)), n(I(2, 2)), n(I(0, 1)), n(I(0, 2)), n(I(1, 2)));
    case Format::sdf: {
      const std::string deeper = inner + inner.substr(std::min(indent.size(), inner.size()));
      return fmt::format(
          "<inertial>{nl}{in}<!-- {c} -->{nl}{in}<pose>{xyz} 0 0 0</pose>{nl}{in}<mass>{m}</mass>{nl}"
          "{in}<inertia>{nl}{d}<ixx>{}</ixx>{nl}{d}<ixy>{}</ixy>{nl}{d}<ixz>{}</ixz>{nl}{d}<iyy>{}</iyy>{nl}"
          "{d}<iyz>{}</iyz>{nl}{d}<izz>{}</izz>{nl}{in}</inertia>{nl}{i}</inertial>",
          n(I(0, 0)), n(I(0, 1)), n(I(0, 2)), n(I(1, 1)), n(I(1, 2)), n(I(2, 2)), fmt::arg("nl", nl),
          fmt::arg("in", inner), fmt::arg("c", comment), fmt::arg("xyz", xyz(com)), fmt::arg("m", mass),
          fmt::arg("d", deeper), fmt::arg("i", indent));
    }
  }
  return {};
}

const char* keep_words(Keep keep) {
  switch (keep) {
    case Keep::mass:
      return "mass as written";
    case Keep::mass_and_com:
      return "mass and centre of mass as written";
    case Keep::none:
      return "mass from the density";
  }
  return "";
}

}  // namespace

FixResult fix_model(const ModelAudit& audit, const FixOptions& options, const AuditOptions& audit_options) {
  const RobotModel& model = audit.model;
  std::set<std::string> names;
  for (const Link& l : model.links) names.insert(l.name);
  for (const std::string& n : options.only) {
    if (!names.count(n)) {
      throw InvalidArgument(fmt::format("--only {}: {} has no link of that name; its links are {}", n,
                                        model.path.string(), fmt::join(names, ", ")));
    }
  }
  if (options.keep == Keep::none && !audit_options.density && model.format != Format::mjcf) {
    throw InvalidArgument("--keep none computes each mass from a density: give --density RHO (kg/m³)");
  }
  const std::string nl = newline_of(model.text);
  FixResult result;
  // Spans in file order, replaced back to front would do as well; front to back keeps one pass.
  struct Edit {
    SourceSpan span;
    std::string text;
  };
  std::vector<Edit> edits;
  // What a recomputed inertial answers: its tensor and COM always; its mass only when not kept.
  const auto answered = [&](const Finding& f) {
    if (f.code == "implied_density" || f.code == "zero_mass_with_geometry") return options.keep == Keep::none;
    return f.code != "missing_mesh" && f.code != "open_mesh" && f.code != "mesh_scale" &&
           f.code != "bad_geometry";
  };
  for (const LinkAudit& l : audit.links) {
    if (!l.parts.empty()) continue;  // a lumped body is a view, not an element of the file
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), l.name) == options.only.end())
      continue;
    LinkFix fix{l.name, l.line, false, {}, {}, {}};
    if (!l.authored) {
      fix.reason = "it has no inertial, and the fix adds none";
    } else if (!l.computed) {
      fix.reason = "its geometry could not be used (see the findings)";
    } else if (std::any_of(l.findings.begin(), l.findings.end(),
                           [](const Finding& f) { return f.code == "mesh_scale"; })) {
      fix.reason =
          "its mesh is in other units than metres (finding mesh_scale): give the mesh its scale first";
    } else if (l.authored->mass <= 0 && options.keep != Keep::none) {
      fix.reason =
          "its mass is 0 (a massless frame?); --keep none --density RHO gives it one from its geometry";
    } else if (!options.all && options.only.empty() &&
               std::none_of(l.findings.begin(), l.findings.end(), answered)) {
      fix.reason = l.findings.empty()
                       ? "no finding (--all recomputes it anyway)"
                       : "its findings are about its mass, which is kept (--keep none recomputes it)";
    } else {
      const Inertial& in = *l.authored;
      const MassProperties& c = l.computed->properties;
      std::string mass = in.mass_text;  // kept as written: never routed through arithmetic
      MassProperties at = c;
      if (options.keep == Keep::none) {
        mass = number_text(c.mass);
      } else {
        at = MassProperties::from_inertia(in.mass, c.center_of_mass, c.inertia * (in.mass / c.mass));
      }
      Vec3 com = at.center_of_mass;
      Mat3 I = at.inertia;
      if (options.keep == Keep::mass_and_com) {
        com = in.frame.p;
        I = at.inertia_about(com);
      }
      const std::string comment = fmt::format(
          "inertial computed by tumble from the link's {} ({}; COM in the link "
          "frame, tensor about it in the link's axes)",
          l.computed->geometry, keep_words(options.keep));
      const std::string indent = indent_of(model.text, in.span.begin);
      const std::string inner = child_indent(model.text, in.span, indent);
      fix.before = model.text.substr(in.span.begin, in.span.end - in.span.begin);
      fix.after = element_text(model.format, comment, mass, com, I, indent, inner, nl);
      fix.changed = true;
      edits.push_back({in.span, fix.after});
    }
    result.links.push_back(std::move(fix));
  }
  std::sort(edits.begin(), edits.end(),
            [](const Edit& a, const Edit& b) { return a.span.begin < b.span.begin; });
  std::size_t at = 0;
  for (const Edit& e : edits) {
    result.text.append(model.text, at, e.span.begin - at);
    result.text += e.text;
    at = e.span.end;
  }
  result.text.append(model.text, at, std::string::npos);
  return result;
}

}  // namespace tumble::robot
