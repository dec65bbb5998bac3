// `tumble run` never destroys a user's file: outputs that are the run's inputs are refused (by file
// identity), devices, FIFOs and symlinks are written through and never replaced, "-" is standard
// output, killed runs' temporaries are cleaned up, a trajectory and its diagnostics appear together,
// write errors (a full disk) end with one line and a non-zero status, and outputs are byte-identical
// run to run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"
#include "tumble/error.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/io/trajectory_writer.hpp"

extern char** environ;

namespace tumble {
namespace {

namespace fs = std::filesystem;
using test::run_tumble;

std::string example(const std::string& name) { return std::string(TUMBLE_SOURCE_DIR) + "/examples/" + name; }

/// A shell command line; its stdout (and stderr, unless the command redirects it) captured.
test::CommandResult run_shell(const std::string& command, bool merge_stderr = true) {
  return test::run_shell_command(command + (merge_stderr ? " 2>&1" : ""));
}

size_t line_count(const std::string& text) {
  size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

bool has_temporaries(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos) return true;
  }
  return false;
}

/// A copy of the T-handle scene and its mesh in `dir`: s.toml reading meshes/t_handle.stl.
fs::path copy_t_handle(const test::TempDir& dir) {
  fs::create_directories(dir / "meshes");
  fs::copy_file(example("meshes/t_handle.stl"), dir / "meshes/t_handle.stl");
  fs::copy_file(example("t_handle.toml"), dir / "s.toml");
  return dir / "s.toml";
}

/// A short run of the scene: 0.1 s, samples every 0.01 s.
const std::string kShort = " --duration 0.1 --quiet";

TEST(RunOutputs, SceneRecordsItsInputFiles) {
  test::TempDir dir("outputs_inputs");
  const fs::path scene = copy_t_handle(dir);
  const Scene s = load_scene(scene);
  ASSERT_EQ(s.input_files.size(), 2u);
  EXPECT_EQ(s.input_files[0], scene);
  EXPECT_TRUE(fs::equivalent(s.input_files[1], dir / "meshes/t_handle.stl"));
}

TEST(RunOutputs, AnInputIsNeverAnOutput) {
  test::TempDir dir("outputs_refused");
  const fs::path scene = copy_t_handle(dir);
  const std::string original = test::read_text(scene);
  const std::string mesh = test::read_text(dir / "meshes/t_handle.stl");
  fs::create_directories(dir / "x");
  fs::create_hard_link(scene, dir / "hard.csv");
  fs::create_symlink(scene, dir / "soft.csv");
  const std::string s = scene.string(), d = dir.path().string();
  auto refused = [&](const std::string& args, const std::string& expected) {
    const auto r = run_tumble("run " + s + " " + args + kShort);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    EXPECT_EQ(line_count(r.output), 1u) << r.output;
    EXPECT_NE(r.output.find("tumble: error: " + expected), std::string::npos) << args << "\n" << r.output;
  };
  const std::string scene_is = " is the scene file " + s + ": writing it would destroy the run's input; ";
  refused("-o " + s, "-o " + s + scene_is + "give another output name, e.g. -o s.csv");
  // Any spelling of the same file: "x/../", a hard link, a symlink; and HDF5 too.
  refused("-o " + d + "/x/../s.toml", "-o " + d + "/x/../s.toml" + scene_is);
  refused("-o " + d + "/hard.csv", "-o " + d + "/hard.csv" + scene_is);
  refused("-o " + d + "/soft.csv", "-o " + d + "/soft.csv" + scene_is);
  refused("-o " + s + " --format hdf5", "-o " + s + scene_is + "give another output name, e.g. -o s.h5");
  refused("-o " + d + "/out.csv --diagnostics " + s,
          "--diagnostics " + s + scene_is + "give another file, e.g. --diagnostics s.diagnostics.csv");
  // A mesh the scene reads.
  const std::string m = d + "/meshes/t_handle.stl";
  refused("-o " + d + "/meshes/../meshes/t_handle.stl",
          "-o " + d + "/meshes/../meshes/t_handle.stl is the file " + m +
              " that the scene reads (a mesh or a body table): writing it would destroy the run's input; "
              "give another output name, e.g. "
              "-o s.csv");
  // The trajectory and the diagnostics in one file.
  refused("-o " + d + "/a.csv --diagnostics " + d + "/x/../a.csv",
          "the trajectory " + d + "/a.csv and the diagnostics " + d +
              "/x/../a.csv are the same file: give different files");
  EXPECT_EQ(test::read_text(scene), original);
  EXPECT_EQ(test::read_text(dir / "meshes/t_handle.stl"), mesh);
  EXPECT_TRUE(fs::is_symlink(dir / "soft.csv"));
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunOutputs, ASymlinkIsFollowedAndKept) {
  test::TempDir dir("outputs_symlink");
  const auto target = dir.write("data/target.csv", "old\n");
  fs::create_symlink("data/target.csv", dir / "link.csv");
  const auto r =
      run_tumble("run " + example("t_handle.toml") + " -o " + (dir / "link.csv").string() + kShort);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  EXPECT_EQ(fs::read_symlink(dir / "link.csv"), "data/target.csv");
  EXPECT_EQ(test::read_text(target).substr(0, 7), "t,body,");
  EXPECT_EQ(line_count(test::read_text(target)), 12u);  // header + 11 samples
  EXPECT_TRUE(fs::exists(dir / "link.diagnostics.csv"));
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunOutputs, DevicesAndFifosAreWrittenThroughNeverReplaced) {
  test::TempDir dir("outputs_devices");
  // /dev/null discards the trajectory; no diagnostics file is made beside a device.
  const auto r = run_tumble("run " + example("t_handle.toml") + " -o /dev/null" + kShort);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_FALSE(fs::exists("/dev/null.diagnostics.csv"));
  // A FIFO: its reader gets the CSV, and it is still a FIFO afterwards.
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = test::read_text(fifo); });
  const auto f = run_tumble("run " + example("t_handle.toml") + " -o " + fifo.string() + " --diagnostics " +
                            (dir / "d.csv").string() + kShort);
  reader.join();
  ASSERT_EQ(f.status, 0) << f.output;
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(received.substr(0, 7), "t,body,");
  EXPECT_EQ(line_count(received), 12u);
  EXPECT_EQ(line_count(test::read_text(dir / "d.csv")), 12u);
  // HDF5 seeks: a device or "-" is refused, with the way out.
  const auto h = run_tumble("run " + example("t_handle.toml") + " -o /dev/null --format hdf5" + kShort);
  EXPECT_EQ(h.status, 1);
  EXPECT_NE(h.output.find("tumble: error: /dev/null is a character device: HDF5 needs a regular file (the "
                          "library seeks in it): give a file name, or write CSV"),
            std::string::npos)
      << h.output;
  const auto hs = run_tumble("run " + example("t_handle.toml") + " -o - --format hdf5" + kShort);
  EXPECT_EQ(hs.status, 1);
  EXPECT_NE(hs.output.find("tumble: error: HDF5 cannot be written to standard output"), std::string::npos)
      << hs.output;
  // A socket is no output at all.
  const fs::path socket_path = dir / "sock";
  const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::snprintf(address.sun_path, sizeof(address.sun_path), "%s", socket_path.c_str());
  ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  const auto s = run_tumble("run " + example("t_handle.toml") + " -o " + socket_path.string() + kShort);
  ::close(sock);
  EXPECT_EQ(s.status, 1);
  EXPECT_NE(s.output.find("tumble: error: " + socket_path.string() +
                          " is a socket: tumble writes to regular files, character devices (e.g. /dev/null), "
                          "FIFOs or standard output (-): give a file name"),
            std::string::npos)
      << s.output;
  EXPECT_TRUE(fs::is_socket(socket_path));
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunOutputs, DashIsStandardOutputAndMessagesGoToStderr) {
  test::TempDir dir("outputs_stdout");
  const std::string run = std::string(TUMBLE_CLI) + " run " + example("t_handle.toml") +
                          " --duration 0.1 -o -";
  // Standard output holds the CSV and nothing else; the summary went to stderr.
  const auto csv = run_shell(run + " 2>" + (dir / "err.txt").string(), false);
  ASSERT_EQ(csv.status, 0) << csv.output;
  EXPECT_EQ(csv.output.substr(0, 7), "t,body,");
  EXPECT_EQ(line_count(csv.output), 12u);
  const std::string err = test::read_text(dir / "err.txt");
  EXPECT_NE(err.find("ran " + example("t_handle.toml") + " for 0.1 s"), std::string::npos) << err;
  EXPECT_NE(err.find("trajectory:  standard output\ndiagnostics: none (give --diagnostics FILE)"),
            std::string::npos)
      << err;
  // --diagnostics still writes its file.
  const auto both =
      run_shell(run + " --quiet --diagnostics " + (dir / "d.csv").string() + " 2>/dev/null", false);
  ASSERT_EQ(both.status, 0) << both.output;
  EXPECT_EQ(both.output, csv.output);
  EXPECT_EQ(line_count(test::read_text(dir / "d.csv")), 12u);
}

/// The pid of a process that has ended (and been reaped).
pid_t dead_pid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  int status = 0;
  waitpid(pid, &status, 0);
  return pid;
}

TEST(RunOutputs, StaleTemporariesOfDeadRunsAreRemoved) {
  test::TempDir dir("outputs_stale");
  const std::string dead = std::to_string(dead_pid()), alive = std::to_string(::getpid());
  for (const std::string& name :
       std::vector<std::string>{"out.csv.tmp-" + dead, "out.diagnostics.csv.tmp-" + dead,
                                "out.csv.old-" + dead, "out.csv.tmp-" + alive, "out.csv.tmp-" + dead + "x",
                                "out.csv.tmp-abc", "other.csv.tmp-" + dead, "out.csv.tmp-0" + dead}) {
    dir.write(name, "left by a killed run\n");
  }
  fs::create_directories(dir / ("out.csv.tmp-" + std::to_string(dead_pid())));  // not a regular file
  const auto r = run_tumble("run " + example("t_handle.toml") + " -o " + (dir / "out.csv").string() + kShort);
  ASSERT_EQ(r.status, 0) << r.output;
  // Only regular files named exactly FINAL.tmp-PID / FINAL.old-PID of a dead PID are removed.
  EXPECT_FALSE(fs::exists(dir / ("out.csv.tmp-" + dead)));
  EXPECT_FALSE(fs::exists(dir / ("out.diagnostics.csv.tmp-" + dead)));
  EXPECT_FALSE(fs::exists(dir / ("out.csv.old-" + dead)));
  for (const std::string& kept : std::vector<std::string>{"out.csv.tmp-" + alive, "out.csv.tmp-" + dead + "x",
                                                          std::string("out.csv.tmp-abc"),
                                                          "other.csv.tmp-" + dead, "out.csv.tmp-0" + dead}) {
    EXPECT_TRUE(fs::exists(dir / kept)) << kept;
  }
  size_t directories = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) directories += e.is_directory();
  EXPECT_EQ(directories, 1u);
}

/// Spawns tumble with stderr to a file and optionally one more environment variable.
pid_t spawn_tumble(std::vector<std::string> args, const fs::path& stderr_file, const std::string& env = "") {
  args.insert(args.begin(), TUMBLE_CLI);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) env_strings.emplace_back(*e);
  if (!env.empty()) env_strings.push_back(env);
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, TUMBLE_CLI, &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  return spawned == 0 ? pid : -1;
}

bool wait_for(const std::function<bool()>& condition, std::chrono::seconds limit = std::chrono::seconds(30)) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(RunOutputs, SighupStopsLikeSigterm) {
  test::TempDir dir("outputs_sighup");
  const fs::path out = dir / "long.csv";
  const pid_t pid =
      spawn_tumble({"run", example("t_handle.toml"), "-o", out.string(), "--duration", "1e6", "--quiet"},
                   dir / "stderr.txt");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_for([&] { return has_temporaries(dir.path()); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_EQ(kill(pid, SIGHUP), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "it stopped by itself, not killed by the signal";
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGHUP);
  EXPECT_NE(test::read_text(dir / "stderr.txt").find("tumble: interrupted at t = "), std::string::npos);
  const size_t rows = line_count(test::read_text(out));
  EXPECT_GT(rows, 2u);
  EXPECT_EQ(line_count(test::read_text(dir / "long.diagnostics.csv")), rows);
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunOutputs, ASecondSignalBetweenTheTwoRenamesWaitsForBoth) {
  // The test hook holds the run for 2 s between moving the trajectory and its diagnostics into place;
  // a second Ctrl-C there ends the run only once both are in place.
  test::TempDir dir("outputs_pair");
  const fs::path out = dir / "long.csv", diagnostics = dir / "long.diagnostics.csv";
  const pid_t pid =
      spawn_tumble({"run", example("t_handle.toml"), "-o", out.string(), "--duration", "1e6", "--quiet"},
                   dir / "stderr.txt", "TUMBLE_TEST_PAUSE_BETWEEN_RENAMES_MS=2000");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_for([&] { return has_temporaries(dir.path()); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  ASSERT_TRUE(wait_for([&] { return fs::exists(out); })) << "the trajectory was moved into place";
  EXPECT_FALSE(fs::exists(diagnostics)) << "the hook holds the run between the two renames";
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the second signal ends the run, after the renames";
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  const size_t rows = line_count(test::read_text(out));
  EXPECT_GT(rows, 2u);
  EXPECT_EQ(line_count(test::read_text(diagnostics)), rows);
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunOutputs, TheTrajectoryIsNotReplacedIfItsDiagnosticsCannotBe) {
  test::TempDir dir("outputs_rollback");
  const Scene scene = load_scene(example("thrown_box.toml"));
  const fs::path trajectory = dir / "t.csv", diagnostics = dir / "d.csv";
  for (const bool older : {true, false}) {
    if (older) dir.write("t.csv", "older trajectory\n");
    auto writer = make_csv_writer(trajectory, diagnostics, scene.model, TrajectoryInfo{});
    writer->write(scene.model, scene.initial, DriftSample{});
    // A directory appears where the diagnostics go: their rename fails.
    dir.write("d.csv/keep", "");
    try {
      writer->commit(true);
      ADD_FAILURE() << "the commit should have failed";
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find("; " + trajectory.string() + " was not replaced either"),
                std::string::npos)
          << e.what();
    }
    if (older) {
      EXPECT_EQ(test::read_text(trajectory), "older trajectory\n") << "the older file is back";
    } else {
      EXPECT_FALSE(fs::exists(trajectory));
    }
    writer.reset();
    EXPECT_FALSE(has_temporaries(dir.path()));
    fs::remove_all(diagnostics);
    fs::remove(trajectory);
  }
}

TEST(RunOutputs, AFullDeviceIsAnErrorNeverSuccess) {
  // Standard output on /dev/full: inertia --json, and run -o -.
  const auto json =
      run_shell(std::string(TUMBLE_CLI) + " inertia --shape box --size 1,2,3 --json 2>&1 >/dev/full", false);
  EXPECT_EQ(json.status, 1) << json.output;
  EXPECT_EQ(json.output,
            "tumble: error: writing to standard output failed: No space left on device; what was printed is "
            "incomplete\n");
  const auto csv = run_shell(
      std::string(TUMBLE_CLI) + " run " + example("t_handle.toml") + " -o - 2>&1 >/dev/full", false);
  EXPECT_EQ(csv.status, 1) << csv.output;
  EXPECT_EQ(csv.output,
            "tumble: error: writing the trajectory to standard output failed: No space left on device\n");
  // -o /dev/full: written through, and the error said.
  const auto dev = run_tumble("run " + example("t_handle.toml") + " -o /dev/full --quiet");
  EXPECT_EQ(dev.status, 1) << dev.output;
  EXPECT_EQ(dev.output,
            "tumble: error: writing the trajectory to /dev/full failed: No space left on device\n");
}

TEST(RunOutputs, AFullDiskEndsWithOneLineAndNoFile) {
  // A file size limit (RLIMIT_FSIZE, SIGXFSZ ignored) makes writes past it fail with EFBIG, as a full
  // disk makes them fail with ENOSPC: CSV, and HDF5 (whose close once crashed in HDF5's exit handler)
  // failing when the file is closed (0.5 s: its chunks are written then) and during the run (100 s,
  // every step).
  test::TempDir dir("outputs_full");
  auto limited = [&](int blocks_of_512_bytes, const std::string& args) {
    return run_shell("sh -c \"trap '' XFSZ; ulimit -f " + std::to_string(blocks_of_512_bytes) + "; exec " +
                     std::string(TUMBLE_CLI) + " run " + example("t_handle.toml") + " --quiet " + args +
                     "\"");
  };
  const fs::path csv = dir / "t.csv", h5 = dir / "t.h5";
  // Within the limit: no error (64 KiB for 15 kB of CSV; 256 KiB for 0.1 MB of HDF5, its chunks
  // sized from the run's 51 samples).
  EXPECT_EQ(limited(128, "--duration 0.5 -o " + csv.string()).status, 0);
  EXPECT_EQ(limited(512, "--duration 0.5 -o " + h5.string()).status, 0);
  fs::remove(csv);
  fs::remove(dir / "t.diagnostics.csv");
  fs::remove(h5);

  const auto c = limited(128, "--duration 20 -o " + csv.string());
  EXPECT_EQ(c.status, 1) << c.output;
  EXPECT_EQ(c.output,
            "tumble: error: writing the trajectory to " + csv.string() +
                " failed: File too large; nothing was kept under that name: free some space or write "
                "elsewhere\n");
  for (const auto& [blocks, args] :
       {std::pair{64, "--duration 0.5"}, std::pair{4096, "--duration 100 --output-interval 0"}}) {
    const auto h = limited(blocks, std::string(args) + " -o " + h5.string());
    EXPECT_EQ(h.status, 1) << args << "\n" << h.output;
    EXPECT_EQ(line_count(h.output), 1u) << h.output;
    EXPECT_EQ(h.output.find("tumble: error: writing " + h5.string() + " failed: HDF5 could not "), 0u)
        << h.output;
    EXPECT_NE(h.output.find(" (File too large); nothing was kept under that name\n"), std::string::npos)
        << h.output;
  }
  EXPECT_FALSE(fs::exists(csv));
  EXPECT_FALSE(fs::exists(dir / "t.diagnostics.csv"));
  EXPECT_FALSE(fs::exists(h5));
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunOutputs, OutputsAreByteIdenticalRunToRun) {
  // Two runs of one scene, a second apart (HDF5 once stored object modification times): the same bytes.
  test::TempDir dir("outputs_identical");
  const fs::path scene = copy_t_handle(dir);
  for (const std::string ext : {".csv", ".h5"}) {
    const fs::path a = dir / ("a" + ext), b = dir / ("b" + ext);
    ASSERT_EQ(run_tumble("run " + scene.string() + " -o " + a.string() + kShort).status, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    ASSERT_EQ(run_tumble("run " + scene.string() + " -o " + b.string() + kShort).status, 0);
    EXPECT_EQ(run_shell("cmp " + a.string() + " " + b.string()).status, 0) << ext;
    if (ext == ".csv") {
      EXPECT_EQ(run_shell("cmp " + (dir / "a.diagnostics.csv").string() + " " +
                          (dir / "b.diagnostics.csv").string())
                    .status,
                0);
    }
  }
}

}  // namespace
}  // namespace tumble
