// `tumble run --checkpoint` and `tumble resume`: a run stopped by SIGTERM (or killed) and resumed writes
// the same files, byte for byte, as a run that was never stopped.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"
#include "tumble/io/checkpoint.hpp"

extern char** environ;

namespace tumble {
namespace {

namespace fs = std::filesystem;

/// A T-handle (a mesh: its stamp is checked on resume) tumbling for long enough that a signal lands
/// mid-way; a damped box beside it feels torques, so splitting sets up new flows as well. Two events
/// watch them, so that the events file is continued too.
std::string scene_text(const std::string& integrator) {
  return "[simulation]\nduration = 2.0\ntimestep = 1e-4\noutput_interval = 0.01\nintegrator = \"" +
         integrator +
         "\"\n"
         "[[bodies]]\nname = \"handle\"\nmesh = \"t_handle.stl\"\ndensity = 2700.0\n"
         "angular_velocity = [0.1, 0.0, 20.0]\n"
         "[[bodies]]\nname = \"box\"\nshape = { type = \"box\", size = [0.1, 0.2, 0.3] }\nmass = 1.0\n"
         "position = [1.0, 0.0, 0.0]\nangular_velocity = [1.0, 2.0, 3.0]\n"
         "[[forces]]\ntype = \"damping\"\nbody = \"box\"\nlinear = 0.1\nangular = 0.02\n"
         "[[events]]\nname = \"slowing\"\nbody = \"handle\"\ncolumn = \"w2\"\nvalue = 19.99\n"
         "[[events]]\nname = \"tilt\"\nbody = \"box\"\naxis = [0, 1, 0]\ntoward = [0, 1, 0]\nangle_deg = 30\n"
         "[[events]]\nname = \"turning\"\nbody = \"handle\"\ncolumn = \"w2\"\nvalue = 15\n";
}

pid_t spawn(std::vector<std::string> args, const fs::path& stderr_file) {
  args.insert(args.begin(), TUMBLE_CLI);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, TUMBLE_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return spawned == 0 ? pid : -1;
}

bool wait_for(const std::function<bool()>& condition) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

size_t lines_of_temporary(const fs::path& dir, const std::string& name) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.rfind(name + ".tmp-", 0) == 0) {
      const std::string text = test::read_text(e.path());
      return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
    }
  }
  return 0;
}

/// The closing summary's lines about events ("event NAME (BODY): N crossings, the first at t = ...").
std::string event_lines(const std::string& output) {
  std::string lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("event ", 0) == 0) lines += line + "\n";
  }
  return lines;
}

struct Dir {
  explicit Dir(const std::string& name) : dir(name) {  // NOLINT
    fs::copy_file(fs::path(TUMBLE_SOURCE_DIR) / "examples/meshes/t_handle.stl", dir / "t_handle.stl");
  }
  test::TempDir dir;
};

/// Runs the scene with a checkpoint and stops it with `signal` once `rows` rows are in the trajectory.
int stopped_run(const Dir& d, const std::string& integrator, int signal, size_t rows) {
  const fs::path scene = d.dir.write("s.toml", scene_text(integrator));
  const pid_t pid = spawn({"run", scene.string(), "-o", (d.dir / "out.csv").string(), "--checkpoint",
                           (d.dir / "run.ckpt").string(), "--checkpoint-every", "0", "--quiet"},
                          d.dir / "stderr.txt");
  EXPECT_GT(pid, 0);
  EXPECT_TRUE(wait_for([&] { return lines_of_temporary(d.dir.path(), "out.csv") >= rows; }));
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(ResumeCli, StoppedBySigtermAndResumedTheFilesAreThoseOfAnUninterruptedRun) {
  for (const std::string integrator : {"splitting", "dopri45", "rk4", "midpoint"}) {
    Dir whole("resume_whole_" + integrator);
    const fs::path scene = whole.dir.write("s.toml", scene_text(integrator));
    const auto full = test::run_tumble("run " + scene.string() + " -o " + (whole.dir / "out.csv").string());
    ASSERT_EQ(full.status, 0) << full.output;

    Dir part("resume_part_" + integrator);
    const int status = stopped_run(part, integrator, SIGTERM, 300);
    ASSERT_TRUE(WIFEXITED(status)) << integrator;
    EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << integrator;
    const std::string err = test::read_text(part.dir / "stderr.txt");
    EXPECT_NE(err.find("tumble resume"), std::string::npos) << err;
    ASSERT_TRUE(fs::exists(part.dir / "run.ckpt")) << err;
    ASSERT_LT(test::read_text(part.dir / "out.csv").size(), test::read_text(whole.dir / "out.csv").size())
        << integrator << ": the run was stopped mid-way";

    const auto resumed = test::run_tumble("resume " + (part.dir / "run.ckpt").string());
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    // The closing summary counts every crossing of the run, those before the stop too.
    EXPECT_EQ(event_lines(resumed.output), event_lines(full.output)) << integrator;
    long summed = 0;  // over the summary's "N crossing(s)": the events file's 3 rows
    std::istringstream lines(event_lines(resumed.output));
    for (std::string line; std::getline(lines, line);) summed += std::stol(line.substr(line.find("): ") + 3));
    EXPECT_EQ(summed, 3) << resumed.output;
    EXPECT_TRUE(test::read_text(part.dir / "out.csv") == test::read_text(whole.dir / "out.csv"))
        << integrator;
    EXPECT_TRUE(test::read_text(part.dir / "out.diagnostics.csv") ==
                test::read_text(whole.dir / "out.diagnostics.csv"))
        << integrator;
    const std::string events = test::read_text(whole.dir / "out.events.csv");
    // Crossings at 0.27, 0.88 and 1.97 s; the stop comes near 1.5 s (300 rows of 2 bodies).
    EXPECT_EQ(std::count(events.begin(), events.end(), '\n'), 4) << events;
    EXPECT_TRUE(test::read_text(part.dir / "out.events.csv") == events) << integrator;
    EXPECT_FALSE(fs::exists(part.dir / "run.ckpt")) << "removed when the run completes";
  }
}

TEST(ResumeCli, KilledBeforeItsFilesWereCommittedIsResumedFromTheTemporaries) {
  Dir whole("resume_kill_whole");
  const fs::path scene = whole.dir.write("s.toml", scene_text("splitting"));
  ASSERT_EQ(
      test::run_tumble("run " + scene.string() + " -o " + (whole.dir / "out.csv").string() + " -q").status,
      0);
  Dir part("resume_kill_part");
  const int status = stopped_run(part, "splitting", SIGKILL, 300);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_FALSE(fs::exists(part.dir / "out.csv"));
  const auto resumed = test::run_tumble("resume " + (part.dir / "run.ckpt").string() + " -q");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_TRUE(test::read_text(part.dir / "out.csv") == test::read_text(whole.dir / "out.csv"));
  EXPECT_TRUE(test::read_text(part.dir / "out.diagnostics.csv") ==
              test::read_text(whole.dir / "out.diagnostics.csv"));
}

TEST(ResumeCli, ARunOfThousandsOfBodiesWrittenOnASecondThreadResumesToTheSameFiles) {
  // 1200 boxes from a body table: enough rows that `tumble run` formats its CSV samples on a thread of
  // their own (run_command.cpp). SIGKILL lands while a sample is in flight; every checkpoint must count
  // only rows that were in the temporary files when it was written, and the resumed files equal an
  // uninterrupted run's.
  std::string table = "mass,I1,I2,I3,px,py,pz,wx,wy,wz\n";
  for (int i = 0; i < 1200; ++i) {
    table += fmt::format("6,0.065,0.05,0.025,{},0,0,{},-3,{}\n", i, 1 + i % 7, i % 5);
  }
  const std::string scene =
      "[simulation]\nduration = 4.0\ntimestep = 1e-3\noutput_interval = 0.02\nintegrator = \"rk4\"\n"
      "[world]\ngravity = [0, 0, -9.81]\n[[body_tables]]\nfile = \"boxes.csv\"\n";
  test::TempDir whole("resume_big_whole"), part("resume_big_part");
  for (const test::TempDir* d : {&whole, &part}) {
    d->write("boxes.csv", table);
    d->write("s.toml", scene);
  }
  const auto full =
      test::run_tumble("run " + (whole / "s.toml").string() + " -o " + (whole / "out.csv").string() + " -q");
  ASSERT_EQ(full.status, 0) << full.output;

  const pid_t pid =
      spawn({"run", (part / "s.toml").string(), "-o", (part / "out.csv").string(), "--checkpoint",
             (part / "run.ckpt").string(), "--checkpoint-every", "0", "--quiet"},
            part / "stderr.txt");
  ASSERT_GT(pid, 0);
  EXPECT_TRUE(wait_for([&] { return lines_of_temporary(part.path(), "out.csv") >= 30 * 1200; }));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << test::read_text(part / "stderr.txt");
  ASSERT_FALSE(fs::exists(part / "out.csv")) << "killed mid-way, before its files were committed";
  const auto resumed = test::run_tumble("resume " + (part / "run.ckpt").string() + " -q");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_TRUE(test::read_text(part / "out.csv") == test::read_text(whole / "out.csv"));
  EXPECT_TRUE(test::read_text(part / "out.diagnostics.csv") ==
              test::read_text(whole / "out.diagnostics.csv"));
}

TEST(ResumeCli, AStaleCheckpointIsRefusedAndAWriterIsAskedOnlyWhereItRan) {
  Dir whole("resume_stale_whole");
  const fs::path whole_scene = whole.dir.write("s.toml", scene_text("rk4"));
  ASSERT_EQ(test::run_tumble("run " + whole_scene.string() + " -o " + (whole.dir / "out.csv").string() +
                             " -q")
                .status,
            0);
  const std::string complete = test::read_text(whole.dir / "out.csv");
  Dir d("resume_stale");
  stopped_run(d, "rk4", SIGTERM, 300);
  const fs::path ckpt = d.dir / "run.ckpt", out = d.dir / "out.csv";
  const Checkpoint c = read_checkpoint(ckpt);
  const std::string stopped = test::read_text(out);
  ASSERT_EQ(c.output_bytes, stopped.size()) << "the interrupted run stamped its committed trajectory";
  const auto written = fs::last_write_time(ckpt);
  const auto resume = [&](const Checkpoint& k, const std::string& name, const std::string& options = "") {
    write_checkpoint(d.dir / name, k);
    fs::last_write_time(d.dir / name, written);  // as if the run had written it
    return test::run_tumble("resume " + (d.dir / name).string() + " -q" + options);
  };
  // A temporary of a killed writer beside the trajectory, holding the rows the checkpoint counts.
  const auto killed_writer = [&](Checkpoint k, long pid) {
    k.writer_pid = pid;
    d.dir.write(out.filename().string() + ".tmp-" + std::to_string(pid), stopped);
    return k;
  };
  // This test process is called tumble_tests: a live tumble on this machine and boot is the writer.
  const long self = static_cast<long>(::getpid());
  auto r = resume(killed_writer(c, self), "live.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(fmt::format("(process {}) is still writing", self)), std::string::npos) << r.output;
  // The same PID in another boot (the machine restarted since) is not the writer, nor on another host,
  // which tumble cannot ask: refused until the user says the writer is gone.
  Checkpoint elsewhere = killed_writer(c, self);
  elsewhere.writer_host = "node-17";
  r = resume(elsewhere, "elsewhere.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("ran on host node-17 (process " + std::to_string(self) + "), and its " +
                          out.string() + ".tmp-" + std::to_string(self) +
                          " is still there: if that run no longer runs, give --writer-gone"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(test::read_text(out), stopped) << "refusals move nothing";

  // A complete rerun to the same -o since the checkpoint: its file is not cut back (it was, to the
  // checkpoint's 150 samples, and continued).
  ASSERT_EQ(test::run_tumble("run " + (d.dir / "s.toml").string() + " -o " + out.string() + " -q").status, 0);
  r = test::run_tumble("resume " + ckpt.string() + " -q");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("checkpoint " + ckpt.string() + " is stale: " + out.string() +
                          " is not the trajectory of its run (" + std::to_string(complete.size()) +
                          " bytes, where the checkpoint's run had written " + std::to_string(stopped.size()) +
                          "): another run has written it since"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(test::read_text(out) == complete);
  // ... nor does a killed writer's temporary replace it.
  r = resume(killed_writer(c, 999999), "killed.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("killed.ckpt is stale: " + out.string() + " was written after it, by another run"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(test::read_text(out) == complete);

  // The files as the checkpoint left them: the writer in another boot is gone, its temporary is taken
  // over, and the resumed run is the uninterrupted one.
  d.dir.write("out.csv", stopped);
  fs::last_write_time(out, written - std::chrono::hours(1));
  Checkpoint rebooted = killed_writer(c, self);
  rebooted.writer_boot_id = "an-earlier-boot";
  r = resume(rebooted, "rebooted.ckpt");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(test::read_text(out) == complete);
  // And from another host, once the user says its writer is gone.
  d.dir.write("out.csv", stopped);
  fs::last_write_time(out, written - std::chrono::hours(1));
  r = resume(killed_writer(elsewhere, self), "elsewhere.ckpt", " --writer-gone");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(test::read_text(out) == complete);
}

TEST(ResumeCli, CorruptTruncatedAndForeignCheckpointsAndChangedMeshesAreRefused) {
  Dir d("resume_refused");
  stopped_run(d, "rk4", SIGTERM, 50);
  const fs::path ckpt = d.dir / "run.ckpt";
  const std::string good = test::read_text(ckpt);
  ASSERT_GT(good.size(), 100u);

  std::string flipped = good;
  flipped[flipped.size() / 2] ^= 0x10;
  d.dir.write("flipped.ckpt", flipped);
  auto r = test::run_tumble("resume " + (d.dir / "flipped.ckpt").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is truncated or corrupt"), std::string::npos) << r.output;

  d.dir.write("cut.ckpt", good.substr(0, good.size() - 100));
  r = test::run_tumble("resume " + (d.dir / "cut.ckpt").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is truncated or corrupt"), std::string::npos) << r.output;

  d.dir.write("other.ckpt", "[simulation]\nduration = 1\n");
  r = test::run_tumble("resume " + (d.dir / "other.ckpt").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is not a tumble checkpoint"), std::string::npos) << r.output;

  std::string version = good;
  version[8] = 7;
  d.dir.write("version.ckpt", version);
  r = test::run_tumble("resume " + (d.dir / "version.ckpt").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("has format version 7"), std::string::npos) << r.output;

  // The mesh changed under the checkpoint: one byte of the STL's header.
  const std::string original_mesh = test::read_text(d.dir / "t_handle.stl");
  std::string mesh = original_mesh;
  mesh[0] = mesh[0] == 'x' ? 'y' : 'x';
  d.dir.write("t_handle.stl", mesh);
  r = test::run_tumble("resume " + ckpt.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("t_handle.stl, which the scene reads, changed since the checkpoint was written"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line";

  // HDF5 and standard output cannot be continued: refused when the run starts.
  const fs::path scene = d.dir / "s.toml";
  r = test::run_tumble("run " + scene.string() + " -o " + (d.dir / "x.h5").string() + " --checkpoint " +
                       (d.dir / "x.ckpt").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("--checkpoint needs CSV output"), std::string::npos) << r.output;
  r = test::run_tumble("run " + scene.string() + " -o - --checkpoint " + (d.dir / "x.ckpt").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("--checkpoint needs the trajectory in a file"), std::string::npos) << r.output;

  // A checkpoint of another tumble version resumes, with a warning naming both versions.
  d.dir.write("t_handle.stl", original_mesh);
  Checkpoint old = read_checkpoint(ckpt);
  old.tumble_version = "0.0.1";
  write_checkpoint(d.dir / "old.ckpt", old);
  r = test::run_tumble("resume " + (d.dir / "old.ckpt").string() + " --quiet");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(
                fmt::format("tumble: warning: checkpoint {} was written by tumble 0.0.1, and this is tumble ",
                            (d.dir / "old.ckpt").string())),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace tumble
