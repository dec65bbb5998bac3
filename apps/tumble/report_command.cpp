// `tumble report TRAJECTORY`: the interactive 3D report of a run that `tumble run` wrote (io/report.hpp).
#include <fmt/format.h>

#include <filesystem>

#include "commands.hpp"
#include "tumble/error.hpp"
#include "tumble/io/report.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble::cli {
namespace {

struct ReportOptions {
  std::string trajectory;
  std::string output;
  std::string scene;
  bool quiet = false;
};

int report(const ReportOptions& o) {
  std::filesystem::path out = o.output;
  if (out.empty()) {
    out = o.trajectory;
    out.replace_extension(".html");
  }
  // Never write over what the report is read from: the trajectory, its companions, the scene.
  const std::filesystem::path t = o.trajectory;
  const std::pair<std::filesystem::path, const char*> inputs[] = {{t, "the trajectory itself"},
                                                                  {diagnostics_path(t),
                                                                   "the trajectory's diagnostics"},
                                                                  {events_path(t), "its events file"},
                                                                  {run_facts_path(t), "its run file"},
                                                                  {o.scene, "the scene given with --scene"}};
  for (const auto& [input, what] : inputs) {
    if (!input.empty() && same_file(out, input)) {
      throw InvalidArgument(fmt::format("-o {} is {}: give another file, e.g. -o {}", out.string(), what,
                                        t.stem().string() + ".html"));
    }
  }
  if (report_template().empty()) report_html(Report{});  // says how to get the viewer
  std::optional<Scene> scene;
  if (!o.scene.empty()) scene = load_scene(o.scene);
  Report r = read_report(o.trajectory, scene ? &*scene : nullptr);
  write_report(out, r);
  if (!o.quiet) {
    fmt::print("report of {} ({} of {} samples shown, {} events): {}\n", o.trajectory, r.t.size(),
               r.samples_total, r.events.size(), out.string());
  }
  return 0;
}

}  // namespace

Runner add_report_command(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write the interactive 3D report of a run that `tumble run` wrote: ONE self-contained HTML file (opens "
      "from disk in any browser, no network, no server) with every body drawn as its shape or mesh, its "
      "principal axes, ω and the angular momentum L, playback with a time scrubber and speeds, linked plots "
      "of the energies, |L|, their drifts and ω in world and principal axes, the events marked, and the "
      "run's "
      "facts. The geometry comes from the trajectory file (HDF5: its geometry group; CSV: OUT.run.json "
      "beside it), so moved or changed meshes do not matter. Long runs are down-sampled for display "
      "(the true sample count is shown). `tumble run --report FILE` writes the same during a run.\n\n"
      "Examples:\n"
      "  tumble run examples/t_handle.toml -o out/t_handle.h5\n"
      "  tumble report out/t_handle.h5                 (writes out/t_handle.html)\n"
      "  tumble report out/t_handle.csv -o out/flip.html\n"
      "Open a shared link at a moment: file:///.../flip.html#t=4.6 (paused there), #t=4.6&play=1 (playing)");
  cmd->add_option("trajectory", o->trajectory, "a trajectory file tumble run wrote (.csv or .h5)")
      ->required();
  cmd->add_option("-o,--output", o->output, "the HTML file (default: the trajectory's name with .html)");
  cmd->add_option("--scene", o->scene,
                  "take the bodies' geometry and the scene text from this scene file instead of the "
                  "trajectory's (for files written before reports existed); its bodies must be the run's");
  cmd->add_flag("--quiet,-q", o->quiet, "print nothing but errors");
  return [o] { return report(*o); };
}

}  // namespace tumble::cli
