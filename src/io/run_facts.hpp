#pragma once
// OUT.run.json beside a CSV trajectory: the facts an HDF5 file keeps as attributes and in its geometry
// group (scene text, settings, version, warnings, each body's surface and mass properties, the
// springs), so that `tumble report OUT.csv` needs nothing else. No wall time: two runs of a scene write
// the same bytes (only `tumble run --report` shows it). Private to tumble_io.
#include <nlohmann/json.hpp>

#include <functional>
#include <string_view>

#include "tumble/io/report.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble::io {

/// The run.json text, handed to `write` in pieces of about a megabyte: run_facts_head() all of it but
/// the warnings, run_facts_tail() those and the end. The head is written while the run goes on (it
/// holds nothing the run finds), the tail when it has ended. Format version 2: the distinct display
/// meshes once, in "kinds", each body naming its own by index, so 10⁵ identical boxes hold one mesh;
/// written straight to text, numbers shortest round trip (std::to_chars), with no document tree (which
/// cost a quarter of a 10⁵-body run and most of its memory).
void run_facts_head(const TrajectoryInfo& info, const std::vector<std::string>& names,
                    const std::function<void(std::string_view)>& write);
void run_facts_tail(const std::vector<std::string>& warnings,
                    const std::function<void(std::string_view)>& write);

/// Fills the facts, names and geometry of `report` from a run.json (format version 1, each body with its
/// mesh, or 2); InvalidArgument naming `file` and what is missing or malformed.
void read_run_facts(const nlohmann::json& facts, const std::string& file, Report& report);

}  // namespace tumble::io
