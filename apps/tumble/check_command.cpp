// `tumble check`: read and validate a scene, print what it contains, simulate nothing.
#include <fmt/format.h>

#include <cstdio>
#include <optional>

#include "commands.hpp"
#include "run_plan_report.hpp"
#include "scene_summary.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/io/ensemble.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble::cli {

Runner add_check_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto strict = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Validate a scene file without simulating: report the first problem as file:line:column, or "
      "print a summary (each body's mass, centre of mass, principal moments and axes and initial "
      "centre-of-mass velocity; the forces; the "
      "initial energy and momenta; which of them the forces conserve; the run's steps, samples, output size "
      "and an estimate of its time, from timing its first few steps; an [ensemble] table's runs, varied "
      "values and output columns).\n\nExample:\n"
      "  tumble check examples/t_handle.toml");
  cmd->add_option("scene", *file, "scene file (TOML; see docs/scene-format.md)")->required();
  cmd->add_flag("--strict", *strict,
                "warnings are errors: exit with status 1 if the scene has any (a density or a mesh size that "
                "looks like another unit, angles that look like degrees, ...)");
  return [file, strict] {
    const Scene scene = load_scene(*file);
    // What `tumble run` would refuse (e.g. integrator exact with a torque, a step too small to advance
    // the clock) is refused here too, with the same message.
    validate(scene.settings);
    if (!is_adaptive(scene.settings.integrator))
      make_integrator(scene.settings.integrator)->check(scene.model);
    print_scene_warnings(scene, *strict);
    print_scene_summary(stdout, scene);
    const RunPlan plan = plan_of(scene, scene.settings, {});
    const std::optional<double> seconds = estimate_seconds(scene, scene.settings, plan);
    fmt::print("  plan         {}\n",
               describe(plan, seconds, scene.model.bodies.size() + scene.model.particles.size()));
    // What run refuses without --force (more than a day, more than 100 GB) or warns of, said as run says
    // it (CSV; HDF5 is smaller): valid, so a warning here.
    std::optional<std::string> warning;
    try {
      warning = enforce(plan, seconds, false, false);
    } catch (const InvalidArgument& e) {
      warning = fmt::format("tumble run would refuse it: {}", e.what());
    }
    if (warning) std::fprintf(stderr, "tumble: warning: %s\n", warning->c_str());
    // An [ensemble] table is checked as `tumble ensemble` reads it, with its first run's scene.
    if (scene.text.find("[ensemble") != std::string::npos) {
      const EnsembleStudy study = EnsembleStudy::load(*file);
      (void)study.scene_of_run(0);
      require_table_fits_in_memory(study);
      fmt::print("ensemble: {} runs, seed {}; the table about {:.3g} MB in memory\n", study.runs(),
                 study.seed(), ensemble_table_bytes(study) / 1e6);
      for (const Variation& v : study.variations()) fmt::print("  varies       {}\n", v.path);
      fmt::print("  columns      {}\n", fmt::join(study.columns(), ", "));
    }
    return 0;
  };
}

}  // namespace tumble::cli
