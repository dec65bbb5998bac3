// tumble — the command-line front end. Errors become one readable line and a non-zero exit status.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "tumble/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "tumble: rigid-body dynamics after Jia's Tutorial on Rigid Body Dynamics.\n"
      "Run 'tumble COMMAND --help' for the options and an example of each command. The documentation "
      "(README.md; scene-format.md: every scene key and output field; NOTATION.md: frames and symbols) "
      "and the examples are installed in " TUMBLE_DOC_DIR " (docs/ and examples/ in the source tree).",
      "tumble"};
  app.set_version_flag("--version", std::string("tumble ") + TUMBLE_VERSION);
  app.require_subcommand(1);
  const tumble::cli::Runner run = tumble::cli::add_run_command(app);
  const tumble::cli::Runner check = tumble::cli::add_check_command(app);
  const tumble::cli::Runner inertia = tumble::cli::add_inertia_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("run")) return run();
    if (app.got_subcommand("check")) return check();
    if (app.got_subcommand("inertia")) return inertia();
  } catch (const tumble::Error& e) {
    fmt::print(stderr, "tumble: error: {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "tumble: internal error: {}\n", e.what());
    return 2;
  }
  return 0;
}
