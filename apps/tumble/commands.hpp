#pragma once
// The subcommands of the tumble program. Each registers its options on the CLI11 app and returns the
// function that runs it after parsing.
#include <CLI/CLI.hpp>
#include <functional>

namespace tumble::cli {

using Runner = std::function<int()>;

/// `tumble inertia`: mass properties of a mesh file or a primitive shape.
Runner add_inertia_command(CLI::App& app);
/// `tumble run`: simulate a scene file, write the trajectory and diagnostics (run_command.cpp).
Runner add_run_command(CLI::App& app);
/// `tumble resume`: continue a run from its checkpoint (run_command.cpp).
Runner add_resume_command(CLI::App& app);
/// `tumble report`: the interactive 3D report of a trajectory file (report_command.cpp).
Runner add_report_command(CLI::App& app);
/// `tumble ensemble`: a Monte Carlo study on every core and across MPI ranks (ensemble_command.cpp).
Runner add_ensemble_command(CLI::App& app);
/// `tumble check`: validate a scene file and summarise it (check_command.cpp).
Runner add_check_command(CLI::App& app);
/// `tumble model check|fix`: robot descriptions' inertials against their geometry (model_command.cpp).
Runner add_model_command(CLI::App& app);
/// `tumble fit`: a rigid body's inertia identified from gyro telemetry (fit_command.cpp).
Runner add_fit_command(CLI::App& app);

}  // namespace tumble::cli
