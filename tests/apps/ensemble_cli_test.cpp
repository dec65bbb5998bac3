// `tumble ensemble` as users run it: the same table from 1 thread, 2 threads and 2 MPI ranks, and a study
// killed mid-way resumes to the same table without recomputing what it finished.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <sstream>
#include <thread>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"

extern char** environ;

namespace tumble {
namespace {

namespace fs = std::filesystem;

/// A study of a free box near its intermediate axis: `runs` runs of `duration` s.
std::string study(long runs, double duration) {
  return test::racket_scene(duration) + fmt::format(R"([ensemble]
runs = {}
seed = 5
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "lognormal"
mu = -3.0
sigma = 0.5
[ensemble.outputs]
extrema = ["w2"]
final = ["orientation"]
)",
                                                    runs);
}

/// `tumble ensemble SCENE -o OUT --threads 1 --quiet`, started and not waited for (to be killed): its
/// pid, or -1 if it could not start.
pid_t start_study(const fs::path& scene, const fs::path& out) {
  std::vector<std::string> args = {TUMBLE_CLI,  "ensemble", scene.string(), "-o", out.string(),
                                   "--threads", "1",        "--quiet"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  return posix_spawn(&pid, TUMBLE_CLI, nullptr, nullptr, argv.data(), environ) == 0 ? pid : -1;
}

TEST(EnsembleCli, OneThreadTwoThreadsAndTwoMpiRanksWriteTheSameTable) {
  const test::TempDir dir("ensemble_ranks");
  const fs::path scene = dir.write("s.toml", study(60, 2.0));
  for (const char* threads : {"1", "2"}) {
    const auto r = test::run_tumble(fmt::format("ensemble {} -o {} --threads {} --quiet", scene.string(),
                                                (dir / fmt::format("t{}.csv", threads)).string(), threads));
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const std::string one = test::read_text(dir / "t1.csv");
  EXPECT_EQ(std::count(one.begin(), one.end(), '\n'), 61) << "a header and a row per run";
  EXPECT_TRUE(one == test::read_text(dir / "t2.csv")) << "1 and 2 threads";
  EXPECT_TRUE(test::read_text(dir / "t1.summary.csv") == test::read_text(dir / "t2.summary.csv"));
  EXPECT_FALSE(fs::exists(dir / "t1.csv.partial-0")) << "a finished study keeps no partial rows";
  if (test::run_shell_command("command -v mpirun").status != 0) GTEST_SKIP() << "no mpirun (openmpi-bin)";
  // OpenMPI refuses to run as root unless told; --oversubscribe: more ranks than cores is fine here.
  // Under the sanitize preset, leak detection is off for the ranks only: OpenMPI's components, loaded
  // with dlopen and unloaded at exit, keep their allocations, and LeakSanitizer cannot even name their
  // module to suppress them. Memory errors are still caught; the runs above check tumble's own leaks.
  const auto mpi = test::run_shell_command(
      fmt::format("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader "
                  "OMPI_MCA_btl_vader_single_copy_mechanism=none "
                  "ASAN_OPTIONS=${{ASAN_OPTIONS:+$ASAN_OPTIONS:}}detect_leaks=0 "
                  "mpirun -np 2 --oversubscribe {} ensemble {} -o {} --threads 1 --quiet 2>&1",
                  TUMBLE_CLI, scene.string(), (dir / "mpi.csv").string()));
  ASSERT_EQ(mpi.status, 0) << mpi.output;
  EXPECT_TRUE(one == test::read_text(dir / "mpi.csv")) << "2 MPI ranks";
  EXPECT_TRUE(test::read_text(dir / "t1.summary.csv") == test::read_text(dir / "mpi.summary.csv"));

  // Ranks that read different copies of the scene (here by mpirun's MPMD form: one scene per rank) would
  // write one table of two studies: refused by the rank that differs, and no table is written.
  std::string other = study(60, 2.0);
  other.replace(other.find("sigma = 0.5"), 11, "sigma = 0.6");
  const fs::path copy = dir.write("copy/s.toml", other);
  const auto mixed = test::run_shell_command(
      fmt::format("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader "
                  "OMPI_MCA_btl_vader_single_copy_mechanism=none "
                  "ASAN_OPTIONS=${{ASAN_OPTIONS:+$ASAN_OPTIONS:}}detect_leaks=0 "
                  "mpirun --oversubscribe -np 1 {0} ensemble {1} -o {3} --threads 1 --quiet : -np 1 {0} "
                  "ensemble {2} -o {3} "
                  "--threads 1 --quiet 2>&1",
                  TUMBLE_CLI, scene.string(), copy.string(), (dir / "mixed.csv").string()));
  EXPECT_NE(mixed.status, 0) << mixed.output;
  EXPECT_NE(mixed.output.find("tumble: error (rank 1): rank 1 read another study than rank 0"),
            std::string::npos)
      << mixed.output;
  EXPECT_FALSE(fs::exists(dir / "mixed.csv"));
}

TEST(EnsembleCli, AKilledStudyResumesToTheSameTable) {
  const test::TempDir dir("ensemble_resume");
  const fs::path scene = dir.write("s.toml", study(1200, 4.0));  // about 2 s on one thread: time to kill it
  const auto whole = test::run_tumble(
      fmt::format("ensemble {} -o {} --quiet", scene.string(), (dir / "whole.csv").string()));
  ASSERT_EQ(whole.status, 0) << whole.output;

  // The same study, killed (SIGKILL: no chance to tidy up) once some rows are kept.
  const pid_t pid = start_study(scene, dir / "part.csv");
  ASSERT_GT(pid, 0);
  const fs::path partial = dir / "part.csv.partial-0";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  // Rows are flushed every half second: wait for some (a header of 24 bytes, then rows).
  while (std::chrono::steady_clock::now() < deadline &&
         (!fs::exists(partial) || fs::file_size(partial) < 2000)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(fs::exists(partial));
  ASSERT_FALSE(fs::exists(dir / "part.csv")) << "killed before it finished";

  const auto resumed =
      test::run_tumble(fmt::format("ensemble {} -o {}", scene.string(), (dir / "part.csv").string()));
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming:"), std::string::npos) << resumed.output;
  EXPECT_TRUE(test::read_text(dir / "part.csv") == test::read_text(dir / "whole.csv"));
  EXPECT_FALSE(fs::exists(partial));

  // HDF5: one dataset per column, the same numbers.
  const auto h5 =
      test::run_tumble(fmt::format("ensemble {} -o {} --quiet", scene.string(), (dir / "t.h5").string()));
  ASSERT_EQ(h5.status, 0) << h5.output;
  EXPECT_TRUE(fs::exists(dir / "t.h5"));
}

TEST(EnsembleCli, FiftyKillsAtRandomPointsStillGiveTheUninterruptedTable) {
  // SIGKILL lands anywhere: in a run, between two of stdio's buffer flushes (which cut records, not
  // rows), in the set-up of a resumed study. Each kill here waits until the partial file has grown by a
  // random number of bytes (so it lands at a random point of the writing, whatever the machine's
  // speed), and the next start resumes from what the last left. The table at the end must be the
  // uninterrupted one, byte for byte: a torn record appended to (the old fault) reads as garbage rows.
  const test::TempDir dir("ensemble_kills");
  const fs::path scene = dir.write("s.toml", study(30000, 0.1));
  const auto whole = test::run_tumble(
      fmt::format("ensemble {} -o {} --quiet", scene.string(), (dir / "whole.csv").string()));
  ASSERT_EQ(whole.status, 0) << whole.output;

  const fs::path partial = dir / "part.csv.partial-0";
  const auto size_of = [&] {
    std::error_code ec;
    const auto size = fs::file_size(partial, ec);
    return ec ? std::uintmax_t{0} : size;
  };
  std::mt19937_64 rng(2026);
  std::uniform_int_distribution<std::uintmax_t> growth(1, 12000);  // bytes: about half a batch of rows
  int kills = 0, torn = 0;
  // A record is the run, its values and a checksum: 8 bytes for each column of the table and one more.
  const std::string table = test::read_text(dir / "whole.csv");
  const auto columns = std::count(table.begin(), table.begin() + static_cast<long>(table.find('\n')), ',') +
                       1;
  const auto record = static_cast<std::uintmax_t>(8 * (columns + 1));
  for (; kills < 50; ++kills) {
    const std::uintmax_t target = size_of() + growth(rng);
    const pid_t pid = start_study(scene, dir / "part.csv");
    ASSERT_GT(pid, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    int status = 0;
    bool exited = false;
    while (std::chrono::steady_clock::now() < deadline && size_of() < target) {
      if (waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    ASSERT_FALSE(exited) << "the study finished after " << kills << " kills: give it more runs; status "
                         << status;
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    const std::uintmax_t size = size_of();
    if (size > 24 && (size - 24) % record != 0) ++torn;
  }
  std::printf("[ measured ] %d kills, %d left a torn record, %ju rows kept\n", kills, torn,
              (size_of() - 24) / record);
  EXPECT_GE(torn, 10) << "most kills land between two flushes, which cut records";
  ASSERT_FALSE(fs::exists(dir / "part.csv"));

  const auto resumed =
      test::run_tumble(fmt::format("ensemble {} -o {}", scene.string(), (dir / "part.csv").string()));
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming:"), std::string::npos) << resumed.output;
  EXPECT_TRUE(test::read_text(dir / "part.csv") == test::read_text(dir / "whole.csv"));
  EXPECT_TRUE(test::read_text(dir / "part.summary.csv") == test::read_text(dir / "whole.summary.csv"));
}

TEST(EnsembleCli, ChosenRunsGetTheirTrajectoriesAndBadStudiesOneLine) {
  const test::TempDir dir("ensemble_files");
  std::string text = study(10, 4.0);
  text += "trajectories = { every = 5, worst = 1, by = \"energy_drift_max\" }\n";
  const fs::path scene = dir.write("s.toml", text);
  // Into a directory that does not exist yet, as `tumble run` allows.
  const auto r =
      test::run_tumble(fmt::format("ensemble {} -o {}", scene.string(), (dir / "new/t.csv").string()));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "new/t.run-0.csv"));
  EXPECT_TRUE(fs::exists(dir / "new/t.run-5.csv"));
  EXPECT_NE(r.output.find("flip.count"), std::string::npos) << "the summary on the terminal: " << r.output;
  // A chosen run's file has its crossings (OUT.run-I.events.csv, as `tumble run` writes them): as many
  // flips as its row counts, so that `tumble report` shows them.
  std::vector<std::vector<std::string>> table;
  for (std::istringstream lines(test::read_text(dir / "new/t.csv")); !lines.eof();) {
    std::string line;
    std::getline(lines, line);
    if (line.empty()) continue;
    std::vector<std::string>& row = table.emplace_back();
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(cell);
  }
  const size_t count_column = std::find(table[0].begin(), table[0].end(), "flip.count") - table[0].begin();
  ASSERT_LT(count_column, table[0].size());
  long flips = 0;
  for (const int run : {0, 5}) {
    const std::string events = test::read_text(dir / fmt::format("new/t.run-{}.events.csv", run));
    long crossings = 0;
    for (size_t at = events.find(",flip,"); at != std::string::npos; at = events.find(",flip,", at + 1))
      ++crossings;
    EXPECT_EQ(std::to_string(crossings), table[static_cast<size_t>(run) + 1][count_column]) << events;
    flips += crossings;
  }
  EXPECT_GT(flips, 0) << "4 s holds a flip of these rackets";

  const fs::path bad = dir.write("bad.toml", study(10, 1.0) +
                                                 "[[ensemble.vary]]\npath = \"bodies.racket.mass\"\n"
                                                 "distribution = \"uniform\"\nlow = 2\nhigh = 1\n");
  const auto e = test::run_tumble(fmt::format("ensemble {} -o {}", bad.string(), (dir / "b.csv").string()));
  EXPECT_EQ(e.status, 1);
  EXPECT_NE(e.output.find("high (1) must be above low (2)"), std::string::npos) << e.output;
}

}  // namespace
}  // namespace tumble
