// tumble — the command-line front end. Errors become one readable line and a non-zero exit status.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <system_error>
#include <vector>

#include "commands.hpp"
#include "tumble/error.hpp"

namespace {

/// One line on stderr; never throws (stderr may be gone: a closed terminal, a full disk).
void say(const std::string& line) { std::fputs((line + "\n").c_str(), stderr); }

/// Standard output flushed and closed after a command: a write that failed there (a full disk, a
/// closed pipe) must not pass for success. Returns the exit status.
int finish_stdout(int status) {
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0 && !std::ferror(stdout);
  int error = flushed ? 0 : errno;
  errno = 0;
  if (std::fclose(stdout) != 0 && flushed) error = errno;
  if (flushed && error == 0) return status;
  say(fmt::format("tumble: error: writing to standard output failed: {}; what was printed is incomplete",
                  std::strerror(error != 0 ? error : EIO)));
  return status != 0 ? status : 1;
}

/// Exit status of a command line that cannot be parsed (as most Unix tools do), apart from the 1 of
/// an input that cannot be used.
constexpr int kExitUsage = 2;

/// A command line that cannot be parsed: one line saying what, and where the help is.
int usage_error(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  // The command given, if it is one; otherwise the first word is an unknown command.
  std::string command;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (argc > 1 && sub->get_name() == argv[1]) command = sub->get_name();
  }
  if (command.empty() && argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    say(fmt::format("tumble: error: unknown command '{}': the commands are {}; see tumble --help", argv[1],
                    fmt::join(names, ", ")));
    return kExitUsage;
  }
  say(fmt::format("tumble: error: {}; see tumble {}--help", e.what(), command.empty() ? "" : command + " "));
  return kExitUsage;
}

/// An empty argument ('' or --name=) is never a value tumble can use, and CLI11 takes it for "not
/// given": --density '' would silently mean the default. Returns the message for the first one, or "".
std::string empty_argument(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 2 && arg.rfind("--", 0) == 0 && arg.back() == '=') {
      return fmt::format("{} was given an empty value: give one after the '=', or leave the option out",
                         arg.substr(0, arg.size() - 1));
    }
    if (!arg.empty()) continue;
    const std::string before = i > 1 ? argv[i - 1] : "";
    return before.size() > 1 && before[0] == '-'
               ? fmt::format("{} was given an empty value (''): give one, or leave the option out", before)
               : fmt::format("argument {} is empty (''): give a value or a file name", i);
  }
  return {};
}

/// Address space held back for the way out of an allocation failure, for `tumble report`, which reads
/// run.json into a nlohmann::json tree: that tree's destructor allocates (it flattens the tree into a
/// vector) and is noexcept, so out of memory while reading ended in std::terminate. The first
/// allocation that fails releases the reserve and throws std::bad_alloc, and the unwinding has room.
/// Untouched, it costs no memory, only address space (which is why the other commands, which build no
/// such tree, do not hold it: under ulimit -v it would shrink what they may use).
constexpr std::size_t kReserveBytes = std::size_t{32} << 20;
void* g_reserve = nullptr;

void release_reserve_and_throw() {
  std::free(g_reserve);
  g_reserve = nullptr;
  std::set_new_handler(nullptr);
  throw std::bad_alloc();
}

void hold_reserve() {
  g_reserve = std::malloc(kReserveBytes);
  if (g_reserve != nullptr) std::set_new_handler(release_reserve_and_throw);
}

/// Where the documentation is: beside an installed program, share/doc/tumble of its prefix (found from
/// the program's own path, so a moved or relocated install still names it); for a program in a build
/// tree, the source tree's docs/ and examples/.
std::string where_the_docs_are() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::canonical("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path docs = (self.parent_path() / TUMBLE_DOC_DIR_FROM_BIN).lexically_normal();
    if (std::filesystem::is_regular_file(docs / "README.md", error))
      return "installed in " + docs.string() + ".";
  }
  return "in docs/ and examples/ of the source tree (installed: share/doc/tumble of the prefix).";
}

}  // namespace

int main(int argc, char** argv) {
  // A file size limit (ulimit -f) must end in a write error that tumble reports and cleans up after
  // (one line, exit 1, no temporaries), not in SIGXFSZ's silent death. Children (the mesh reader)
  // inherit the disposition.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "tumble: rigid-body dynamics after Jia's Tutorial on Rigid Body Dynamics.\n"
      "Run 'tumble COMMAND --help' for the options and an example of each command. The documentation "
      "(README.md; scene-format.md: every scene key and output field; NOTATION.md: frames and symbols) "
      "and the examples are " +
          where_the_docs_are(),
      "tumble"};
  app.set_version_flag("--version", std::string("tumble ") + TUMBLE_VERSION);
  app.require_subcommand(1);
  const tumble::cli::Runner run = tumble::cli::add_run_command(app);
  const tumble::cli::Runner resume = tumble::cli::add_resume_command(app);
  const tumble::cli::Runner check = tumble::cli::add_check_command(app);
  const tumble::cli::Runner inertia = tumble::cli::add_inertia_command(app);
  const tumble::cli::Runner report = tumble::cli::add_report_command(app);
  const tumble::cli::Runner ensemble = tumble::cli::add_ensemble_command(app);
  const tumble::cli::Runner model = tumble::cli::add_model_command(app);
  const tumble::cli::Runner fit = tumble::cli::add_fit_command(app);

  try {
    if (const std::string empty = empty_argument(argc, argv); !empty.empty()) {
      say("tumble: error: " + empty + "; see tumble " +
          (argc > 1 && argv[1][0] != '-' ? std::string(argv[1]) + " " : std::string()) + "--help");
      return kExitUsage;
    }
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return usage_error(app, e, argc, argv);
  }
  try {
    if (app.got_subcommand("run")) return finish_stdout(run());
    if (app.got_subcommand("resume")) return finish_stdout(resume());
    if (app.got_subcommand("check")) return finish_stdout(check());
    if (app.got_subcommand("inertia")) return finish_stdout(inertia());
    if (app.got_subcommand("report")) {
      hold_reserve();
      return finish_stdout(report());
    }
    if (app.got_subcommand("ensemble")) return finish_stdout(ensemble());
    if (app.got_subcommand("model")) return finish_stdout(model());
    if (app.got_subcommand("fit")) return finish_stdout(fit());
  } catch (const std::bad_alloc&) {
    // No allocation here: the message is a literal (building a string could throw again and end the
    // process by std::terminate).
    std::fputs(
        "tumble: error: out of memory: the command needs more memory than this process may use "
        "(the machine's, or a limit such as ulimit -v); nothing was kept under the output names: "
        "free memory, raise the limit, or give a smaller problem\n",
        stderr);
    return 1;
  } catch (const tumble::Error& e) {
    say(std::string("tumble: error: ") + e.what());
    return 1;
  } catch (const std::system_error& e) {  // the system refused: a full disk, a closed terminal
    say(std::string("tumble: error: ") + e.what());
    return 1;
  } catch (const std::exception& e) {
    say(std::string("tumble: internal error: ") + e.what());
    return 2;
  }
  return finish_stdout(0);
}
