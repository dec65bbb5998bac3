// Gyro telemetry from a CSV file: a header naming the columns, then one sample per line. Every error
// names file:line (and the column where one field is at fault), since a telemetry file is long and
// the user must find the line.
#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/fit/gyro_fit.hpp"
#include "tumble/mass/input_file.hpp"

namespace tumble::fit {
namespace {

/// What each known column holds: group 0 the time, 1 ω, 2 τ, 3 h; component 0…2.
struct ColumnName {
  std::string_view name;
  int group;
  int component;
};
constexpr std::array<ColumnName, 10> kColumns{{{"t", 0, 0},
                                               {"wx", 1, 0},
                                               {"wy", 1, 1},
                                               {"wz", 1, 2},
                                               {"tau_x", 2, 0},
                                               {"tau_y", 2, 1},
                                               {"tau_z", 2, 2},
                                               {"h_x", 3, 0},
                                               {"h_y", 3, 1},
                                               {"h_z", 3, 2}}};
constexpr std::string_view kColumnsHelp =
    "the columns are t (s), wx, wy, wz (the gyro's angular velocity, rad/s) and optionally tau_x, tau_y, "
    "tau_z (a known applied torque, N m) and h_x, h_y, h_z (a known wheel angular momentum, N m s), "
    "all in sensor axes";

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

/// A line's fields, each with its 1-based column in the line.
struct Field {
  std::string_view text;
  std::size_t column;
};
std::vector<Field> split(std::string_view line) {
  std::vector<Field> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view raw =
        line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    const std::size_t lead = raw.find_first_not_of(" \t");
    fields.push_back({trim(raw), start + (lead == std::string_view::npos ? 0 : lead) + 1});
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

bool skipped(std::string_view line) {
  const std::string_view s = trim(line);
  return s.empty() || s.front() == '#';
}

}  // namespace

Telemetry parse_telemetry(std::string_view text, const std::string& source) {
  Telemetry out;
  out.source = source;
  const auto fail = [&](long line, std::size_t column, const std::string& what) {
    throw FileError(column > 0 ? fmt::format("{}:{}:{}: {}", source, line, column, what)
                               : fmt::format("{}:{}: {}", source, line, what));
  };

  // Which column of a line feeds which quantity (index into kColumns), from the header.
  std::vector<int> slot;
  std::array<int, 4> group_count{};
  long header_line = 0;
  long line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (skipped(line)) {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<Field> fields = split(line);
    if (header_line == 0) {
      header_line = line_number;
      for (const Field& f : fields) {
        int found = -1;
        for (std::size_t c = 0; c < kColumns.size(); ++c) {
          if (kColumns[c].name == f.text) found = static_cast<int>(c);
        }
        if (found < 0) {
          fail(line_number, f.column,
               f.text.empty()
                   ? std::string("an empty column name in the header; ") + std::string(kColumnsHelp)
               : !f.text.empty() && (std::isdigit(static_cast<unsigned char>(f.text.front())) != 0 ||
                                     f.text.front() == '-' || f.text.front() == '.')
                   ? fmt::format("'{}' looks like a number, but the first line must be the header naming the "
                                 "columns, e.g. t,wx,wy,wz; {}",
                                 f.text, kColumnsHelp)
                   : fmt::format("unknown column '{}' in the header; {}", f.text, kColumnsHelp));
        }
        for (const int s : slot) {
          if (s == found)
            fail(line_number, f.column, fmt::format("column '{}' appears twice in the header", f.text));
        }
        slot.push_back(found);
        ++group_count[static_cast<std::size_t>(kColumns[static_cast<std::size_t>(found)].group)];
      }
      for (const ColumnName& c : kColumns) {
        const bool required = c.group <= 1;
        const bool partial = group_count[static_cast<std::size_t>(c.group)] > 0;
        bool present = false;
        for (const int s : slot) present = present || kColumns[static_cast<std::size_t>(s)].name == c.name;
        if (!present && (required || partial)) {
          fail(line_number, 0,
               required
                   ? fmt::format("the header has no column '{}'; {}", c.name, kColumnsHelp)
                   : fmt::format("the header has no column '{}' beside the other {} columns: a {} needs all "
                                 "three components",
                                 c.name, c.group == 2 ? "tau" : "h",
                                 c.group == 2 ? "torque" : "wheel momentum"));
        }
      }
      continue;
    }

    if (fields.size() != slot.size()) {
      fail(line_number, 0,
           fmt::format("{} field{} where the header (line {}) names {} columns", fields.size(),
                       fields.size() == 1 ? "" : "s", header_line, slot.size()));
    }
    double t = 0.0;
    Vec3 omega = Vec3::Zero(), tau = Vec3::Zero(), h = Vec3::Zero();
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const ColumnName& c = kColumns[static_cast<std::size_t>(slot[i])];
      std::string_view s = fields[i].text;
      if (!s.empty() && s.front() == '+') s.remove_prefix(1);
      double value = 0.0;
      const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
      if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) {
        fail(line_number, fields[i].column,
             fields[i].text.empty()
                 ? fmt::format("column '{}' is empty: every sample needs a value", c.name)
                 : fmt::format("'{}' in column '{}' is not a number", fields[i].text, c.name));
      }
      if (!std::isfinite(value)) {
        fail(line_number, fields[i].column,
             fmt::format("'{}' in column '{}' is not finite: every value must be a finite number (drop the "
                         "sample instead)",
                         fields[i].text, c.name));
      }
      if (c.group == 0) t = value;
      if (c.group == 1) omega[c.component] = value;
      if (c.group == 2) tau[c.component] = value;
      if (c.group == 3) h[c.component] = value;
    }
    out.t.push_back(t);
    out.omega.push_back(omega);
    if (group_count[2] > 0) out.tau.push_back(tau);
    if (group_count[3] > 0) out.h.push_back(h);
    out.line.push_back(line_number);
    if (end == text.size()) break;
  }
  if (header_line == 0) {
    throw FileError(
        fmt::format("{}: no header line: the first line must name the columns, e.g. t,wx,wy,wz; {}", source,
                    kColumnsHelp));
  }
  if (out.t.empty()) {
    throw FileError(fmt::format("{}:{}: no samples after the header: the fit needs at least {}", source,
                                header_line, kMinSamples));
  }
  check_telemetry(out);
  return out;
}

Telemetry read_telemetry(const std::filesystem::path& path) {
  return parse_telemetry(read_input_file(path, "telemetry file"), path.string());
}

}  // namespace tumble::fit
