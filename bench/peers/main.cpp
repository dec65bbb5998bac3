// tumble side by side with MuJoCo, Bullet and ODE on N free boxes (bench/peers/README.md).
//
//   peers [CSV] [--reps R] [--sizes 1,100,...] [--target SECONDS] [--budget SECONDS]
//         [--engines mujoco,tumble/rk4,...] [--no-accuracy] [--tag]
//
// 1. Accuracy: a few boxes, torque-free about their centres of mass (gravity only moves the centres),
//    run for kAccuracyDuration by every engine; the worst attitude error against tumble's exact
//    Euler–Poinsot solution and the relative change of the rotational kinetic energy.
// 2. Throughput: for each N, every engine's step count is calibrated so a run lasts about `target`
//    seconds; then `reps` rounds, each setting up every engine afresh and timing one run, the engine
//    order rotated by one per round. Rates are body-steps per second (N × steps taken / seconds of
//    stepping; set-up is timed separately).
//
// Prints the machine, compiler, library versions and settings, then tables; writes the CSV
// (default bench/results/<machine tag>/peers.csv, relative to the working directory).
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "scenario.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/math/quaternion.hpp"

namespace {

using namespace peers;
using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The accuracy case: a few boxes of the same scenario for 20 s (20 000 steps), compared every 10 ms.
constexpr std::size_t kAccuracyBodies = 8;
constexpr double kAccuracyDuration = 20.0;
constexpr long kAccuracySampleEvery = 10;
// A timed run longer than this many steps is made of segments, each from the initial states.
constexpr long kMaxSegmentSteps = 10'000;

struct Options {
  std::string csv;
  int reps = 3;
  std::vector<std::size_t> sizes{1, 100, 10'000, 100'000, 1'000'000};
  double target = 0.7;               // s per timed run
  double budget = 60.0;              // s: skip a size whose set-up or single step is predicted to take longer
  std::vector<std::string> engines;  // filters ("mujoco" or "mujoco/rk4"); empty = all
  bool accuracy = true;
  bool tag_only = false;
};

struct Accuracy {
  double attitude = kNaN;      // worst angle of R_exactᵀ R_engine over bodies and samples (rad)
  double energy_drift = kNaN;  // (E(T) − E(0)) / E(0), rotational kinetic energy summed over the bodies
  double energy_worst = kNaN;  // max |E(t) − E(0)| / E(0) over the samples
  double position = kNaN;      // worst distance of a centre from p₀ + v₀t + ½gt² (m), a sanity check
  double wall = kNaN;          // s
  std::string error;
};

struct Case {
  std::size_t n = 0;
  long steps = 0;
  std::vector<double> seconds;  // one per repetition
  std::vector<long> taken;      // steps taken in each repetition (tumble may add a sliver step)
  double setup = 0;             // the longest set-up seen (s)
  double rate_min = kNaN, rate_median = kNaN;
  std::string note;  // why skipped or failed; empty if it ran
};

struct Entry {
  std::unique_ptr<Runner> runner;
  Accuracy accuracy;
  std::vector<Case> cases;
  std::string name() const { return runner->engine() + "/" + runner->variant(); }
};

std::string cpuinfo(const std::string& key) {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0 && line.find(':') != std::string::npos) {
      const std::size_t colon = line.find(':');
      return colon + 2 <= line.size() ? line.substr(colon + 2) : "";
    }
  }
  return {};
}

bool has_avx512() { return (" " + cpuinfo("flags") + " ").find(" avx512f ") != std::string::npos; }

/// A tag for the results directory from the CPU model (never the host name): lower case, words joined
/// by '-', trademarks and clock speed dropped, "-avx512" when the CPU has it. "AMD EPYC" → amd-epyc-avx512.
std::string machine_tag() {
  std::string model = cpuinfo("model name");
  if (const std::size_t at = model.find('@'); at != std::string::npos) model.resize(at);
  for (const char* mark : {"(R)", "(r)", "(TM)", "(tm)"}) {
    for (std::size_t at; (at = model.find(mark)) != std::string::npos;)
      model.erase(at, std::string(mark).size());
  }
  for (char& c : model) {
    const auto u = static_cast<unsigned char>(c);
    c = std::isalnum(u) ? static_cast<char>(std::tolower(u)) : ' ';
  }
  std::string tag, word;
  std::istringstream words(model);
  while (words >> word) {
    if (word == "cpu" || word == "processor") continue;
    tag += (tag.empty() ? "" : "-") + word;
  }
  if (tag.empty()) tag = "unknown-cpu";
  if (has_avx512()) tag += "-avx512";
  return tag;
}

std::string memory_total() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  while (in >> key >> kib) {
    if (key == "MemTotal:") {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.0f GiB", kib / (1024.0 * 1024.0));
      return buf;
    }
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return "? GiB";
}

int process_threads() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "Threads:") {
      int n = 0;
      in >> n;
      return n;
    }
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return 0;
}

std::string compiler() {
#if defined(__clang__)
  return std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

/// x as printf's "%.<precision><style>" (style 'g', 'e' or 'f'), with a '+' if `sign`; "-" for NaN.
std::string show(double x, char style = 'g', int precision = 3, bool sign = false) {
  if (std::isnan(x)) return "-";
  std::ostringstream s;
  s.precision(precision);
  if (style == 'e') s << std::scientific;
  if (style == 'f') s << std::fixed;
  if (sign) s << std::showpos;
  s << x;
  return s.str();
}

std::string size_name(std::size_t n) {
  if (n >= 1000 && n % 10 == 0) {
    int e = 0;
    std::size_t m = n;
    while (m % 10 == 0) {
      m /= 10;
      ++e;
    }
    return m == 1 ? "1e" + std::to_string(e) : std::to_string(n);
  }
  return std::to_string(n);
}

template <class F>
double seconds_of(F&& f) {
  const auto t0 = Clock::now();
  f();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool selected(const Options& o, const Runner& r) {
  if (o.engines.empty()) return true;
  const std::string full = r.engine() + "/" + r.variant();
  return std::any_of(o.engines.begin(), o.engines.end(),
                     [&](const std::string& e) { return e == r.engine() || e == full; });
}

// ---------------------------------------------------------------------------------------------------
// Accuracy

tumble::Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
tumble::Quat quat(const std::array<double, 4>& q) {
  return tumble::Quat(q[0], q[1], q[2], q[3]).normalized();
}

Accuracy measure_accuracy(Runner& runner, const std::vector<BoxState>& boxes,
                          const std::vector<tumble::Mat3>& exact_R, long steps) {
  Accuracy a;
  double e0 = 0;
  for (const BoxState& b : boxes) e0 += rotational_energy(b);
  double worst_angle = 0, worst_energy = 0, worst_position = 0, e_last = kNaN;
  bool finite = true;
  const std::size_t k = boxes.size();
  try {
    runner.setup(boxes);
    a.wall = seconds_of([&] {
      runner.run_sampled(steps, kAccuracySampleEvery, [&](long step, const std::vector<BoxState>& now) {
        const std::size_t sample = static_cast<std::size_t>(step / kAccuracySampleEvery - 1);
        const double t = static_cast<double>(step) * kTimestep;
        double e = 0;
        for (std::size_t i = 0; i < k; ++i) {
          const double angle =
              tumble::rotation_angle_between(exact_R[sample * k + i], quat(now[i].q).toRotationMatrix());
          const tumble::Vec3 p_exact = vec(boxes[i].position) + vec(boxes[i].velocity) * t +
                                       0.5 * vec(kGravity) * t * t;
          const double dp = (vec(now[i].position) - p_exact).norm();
          finite = finite && std::isfinite(angle) && std::isfinite(dp);
          worst_angle = std::max(worst_angle, angle);
          worst_position = std::max(worst_position, dp);
          e += rotational_energy(now[i]);
        }
        finite = finite && std::isfinite(e);
        worst_energy = std::max(worst_energy, std::abs(e - e0) / e0);
        e_last = e;
      });
    });
    runner.teardown();
  } catch (const std::exception& ex) {
    runner.teardown();
    a.error = ex.what();
    return a;
  }
  if (!finite) {
    a.error = "the state became non-finite";
    return a;
  }
  a.attitude = worst_angle;
  a.energy_drift = (e_last - e0) / e0;
  a.energy_worst = worst_energy;
  a.position = worst_position;
  return a;
}

void run_accuracy(std::vector<Entry>& entries) {
  const std::vector<BoxState> boxes = initial_boxes(kAccuracyBodies);
  const long steps = std::lround(kAccuracyDuration / kTimestep);
  const long samples = steps / kAccuracySampleEvery;
  // The exact attitudes, once for all engines: tumble's closed-form Euler–Poinsot solution with the
  // moments along the box axes (the box frame is principal) and ω in those axes.
  std::vector<tumble::Mat3> exact_R(static_cast<std::size_t>(samples) * boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const tumble::Quat q0 = quat(boxes[i].q);
    const tumble::EulerPoinsot flow(vec(kMoments), q0, q0.conjugate() * vec(boxes[i].omega));
    for (long s = 0; s < samples; ++s) {
      const double t = static_cast<double>((s + 1) * kAccuracySampleEvery) * kTimestep;
      exact_R[static_cast<std::size_t>(s) * boxes.size() + i] = flow.R(t);
    }
  }
  std::printf(
      "== Accuracy: %zu boxes (the first of the scenario), %.0f s = %ld steps of h = %g s, compared every "
      "%ld "
      "steps\n",
      boxes.size(), kAccuracyDuration, steps, kTimestep, kAccuracySampleEvery);
  std::printf(
      "   attitude: worst angle of R_exact^T R_engine over boxes and samples (exact: tumble::EulerPoinsot);\n"
      "   energy: rotational kinetic energy summed over the boxes, (E(T) - E(0)) / E(0) and the worst "
      "|dE|/E;\n"
      "   position: worst distance of a centre from p0 + v0 t + g t^2/2 (first-order methods: O(h)).\n\n");
  std::printf("%-28s %12s %12s %12s %12s %9s\n", "engine/variant", "attitude_rad", "energy_drift",
              "worst_|dE|/E", "position_m", "wall_s");
  for (Entry& e : entries) {
    e.accuracy = measure_accuracy(*e.runner, boxes, exact_R, steps);
    const Accuracy& a = e.accuracy;
    if (!a.error.empty()) {
      std::printf("%-28s failed: %s\n", e.name().c_str(), a.error.c_str());
    } else {
      std::printf("%-28s %12s %12s %12s %12s %9s\n", e.name().c_str(), show(a.attitude, 'e', 2).c_str(),
                  show(a.energy_drift, 'e', 2, true).c_str(), show(a.energy_worst, 'e', 2).c_str(),
                  show(a.position, 'e', 2).c_str(), show(a.wall, 'f', 2).c_str());
    }
    std::fflush(stdout);
  }
  std::printf("\n");
}

// ---------------------------------------------------------------------------------------------------
// Throughput

/// A timed run of `steps` steps, in segments of at most kMaxSegmentSteps, each from the initial states:
/// set-up (timed separately), one untimed warm-up step (first-step allocations), the timed stepping,
/// teardown. Segments keep every run physically the same (at most 10 s simulated, as in the accuracy
/// case) however many steps a fast engine takes at small N: first-order integrators blow up after a few
/// hundred seconds of this motion, and the boxes fall freely all the while. Returns the seconds
/// stepping; `taken` gets the steps taken.
double timed_run(Runner& r, const std::vector<BoxState>& boxes, long steps, double& setup, long& taken) {
  double t = 0;
  taken = 0;
  for (long done = 0; done < steps;) {
    const long segment = std::min(kMaxSegmentSteps, steps - done);
    setup = std::max(setup, seconds_of([&] { r.setup(boxes); }));
    r.advance(1);
    long n = 0;
    t += seconds_of([&] { n = r.advance(segment); });
    r.teardown();
    taken += n;
    done += segment;
  }
  return t;
}

/// A reason to skip size n from what the runner did at smaller sizes (empty: run it).
std::string skip_reason(const Entry& e, std::size_t n, double budget) {
  if (std::string engine = e.runner->skip_reason(n, budget); !engine.empty()) return engine;
  if (e.cases.empty()) return {};
  const Case& last = e.cases.back();
  if (!last.note.empty()) return "not run at N = " + size_name(last.n) + " either";
  // Set-up: the growth exponent from the last two sizes run (at least linear).
  double exponent = 1;
  if (e.cases.size() >= 2) {
    const Case& prev = e.cases[e.cases.size() - 2];
    if (prev.note.empty() && prev.setup > 1e-3 && last.setup > prev.setup) {
      exponent = std::max(1.0, std::log(last.setup / prev.setup) /
                                   std::log(static_cast<double>(last.n) / static_cast<double>(prev.n)));
    }
  }
  const double ratio = static_cast<double>(n) / static_cast<double>(last.n);
  const double setup = last.setup * std::pow(ratio, exponent);
  const double step = median(last.seconds) / static_cast<double>(last.steps) * ratio;
  char buf[400];
  if (setup > budget) {
    std::snprintf(buf, sizeof buf, "set-up predicted %.0f s (> %.0f s): %.3g s at N = %s, growing as N^%.2f",
                  setup, budget, last.setup, size_name(last.n).c_str(), exponent);
    std::string reason = buf;
    if (!e.runner->setup_note().empty() && exponent > 1.5) reason += " (" + e.runner->setup_note() + ")";
    return reason;
  }
  if (step > budget) {
    std::snprintf(buf, sizeof buf, "one step predicted %.0f s (> %.0f s)", step, budget);
    return buf;
  }
  return {};
}

/// Steps for a run of about `target` seconds, from timed runs of increasing length.
long calibrate(Runner& r, const std::vector<BoxState>& boxes, double target, double& setup) {
  long k = std::max<long>(1, static_cast<long>(1000 / boxes.size()));
  while (true) {
    long taken = 0;
    const double t = timed_run(r, boxes, k, setup, taken);
    if (t >= 0.1 * target) return std::max<long>(1, std::lround(static_cast<double>(k) * target / t));
    const double factor = t > 0 ? std::min(100.0, 0.2 * target / t) : 100.0;
    k = std::max(k + 1, static_cast<long>(static_cast<double>(k) * factor));
  }
}

void run_size(std::vector<Entry>& entries, std::size_t n, const Options& o) {
  std::printf("== N = %s: initial states...", size_name(n).c_str());
  std::fflush(stdout);
  const std::vector<BoxState> boxes = initial_boxes(n);
  std::printf(" calibrating...");
  std::fflush(stdout);
  std::vector<Entry*> active;
  for (Entry& e : entries) {
    Case c;
    c.n = n;
    c.note = skip_reason(e, n, o.budget);
    if (c.note.empty()) {
      try {
        c.steps = calibrate(*e.runner, boxes, o.target, c.setup);
        active.push_back(&e);
      } catch (const std::exception& ex) {
        e.runner->teardown();
        c.note = std::string("failed: ") + ex.what();
      }
    }
    e.cases.push_back(c);
  }
  for (int round = 0; round < o.reps; ++round) {
    std::printf(" round %d...", round + 1);
    std::fflush(stdout);
    for (std::size_t j = 0; j < active.size(); ++j) {
      Entry& e = *active[(j + static_cast<std::size_t>(round)) % active.size()];
      Case& c = e.cases.back();
      if (!c.note.empty()) continue;  // failed in an earlier round
      try {
        long taken = 0;
        c.seconds.push_back(timed_run(*e.runner, boxes, c.steps, c.setup, taken));
        c.taken.push_back(taken);
      } catch (const std::exception& ex) {
        e.runner->teardown();
        c.note = std::string("failed: ") + ex.what();
      }
    }
  }
  std::printf("\n");
  for (Entry* e : active) {
    Case& c = e->cases.back();
    if (!c.note.empty() || c.seconds.empty()) continue;
    // Rate of each repetition: N × steps taken / seconds; min and median over repetitions.
    std::vector<double> rates;
    c.rate_min = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < c.seconds.size(); ++i) {
      rates.push_back(static_cast<double>(n) * static_cast<double>(c.taken[i]) / c.seconds[i]);
      c.rate_min = std::min(c.rate_min, rates.back());
    }
    c.rate_median = median(rates);
  }

  // This size's table; ratios to MuJoCo RK4 when it ran.
  double reference = kNaN;
  for (const Entry& e : entries) {
    if (e.name() == "mujoco/rk4") reference = e.cases.back().rate_median;
  }
  std::printf("%-28s %10s %5s %11s %11s %9s %9s %s\n", "engine/variant", "steps", "reps", "rate_min",
              "rate_median", "setup_s", "run_s", "x mujoco/rk4");
  for (const Entry& e : entries) {
    const Case& c = e.cases.back();
    if (!c.note.empty()) {
      std::printf("%-28s skipped: %s\n", e.name().c_str(), c.note.c_str());
      continue;
    }
    std::printf("%-28s %10ld %5zu %11s %11s %9s %9s %s\n", e.name().c_str(), c.steps, c.seconds.size(),
                show(c.rate_min).c_str(), show(c.rate_median).c_str(), show(c.setup, 'f', 3).c_str(),
                show(median(c.seconds), 'f', 3).c_str(), show(c.rate_median / reference, 'f', 2).c_str());
  }
  std::printf("\n");
  std::fflush(stdout);
}

void write_csv(const std::vector<Entry>& entries, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream csv(path);
  csv << "engine,variant,N,threads,steps,reps,rate_min,rate_median,attitude_error,energy_drift\n";
  auto num = [](double x, char style, int precision) {
    return std::isnan(x) ? std::string() : show(x, style, precision);
  };
  for (const Entry& e : entries) {
    for (const Case& c : e.cases) {
      // A skipped or failed size keeps its row, with 0 steps and empty rates.
      const bool ran = c.note.empty();
      csv << e.runner->engine() << ',' << e.runner->variant() << ',' << c.n << ",1," << (ran ? c.steps : 0)
          << ',' << (ran ? c.seconds.size() : 0) << ',' << num(c.rate_min, 'g', 4) << ','
          << num(c.rate_median, 'g', 4) << ',' << num(e.accuracy.attitude, 'e', 3) << ','
          << num(e.accuracy.energy_drift, 'e', 3) << '\n';
    }
  }
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

[[noreturn]] void usage(int status) {
  std::printf(
      "usage: peers [CSV] [--reps R] [--sizes 1,100,10000,...] [--target SECONDS] [--budget SECONDS]\n"
      "             [--engines mujoco,bullet,ode,tumble,tumble/rk4,...] [--no-accuracy] [--tag]\n"
      "  CSV        output file (default bench/results/<machine tag>/peers.csv)\n"
      "  --reps     interleaved repetitions per size (default 3)\n"
      "  --sizes    numbers of boxes (default 1,100,10000,100000,1000000)\n"
      "  --target   seconds per timed run (default 0.7)\n"
      "  --budget   skip a size whose set-up or one step is predicted to take longer (default 60 s)\n"
      "  --tag      print the machine tag and exit\n");
  std::exit(status);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(2);
      return argv[++i];
    };
    if (a == "--help" || a == "-h")
      usage(0);
    else if (a == "--reps")
      o.reps = std::max(1, std::atoi(value().c_str()));
    else if (a == "--sizes") {
      o.sizes.clear();
      for (const std::string& s : split(value())) o.sizes.push_back(static_cast<std::size_t>(std::stod(s)));
    } else if (a == "--target")
      o.target = std::stod(value());
    else if (a == "--budget")
      o.budget = std::stod(value());
    else if (a == "--engines")
      o.engines = split(value());
    else if (a == "--no-accuracy")
      o.accuracy = false;
    else if (a == "--tag")
      o.tag_only = true;
    else if (!a.empty() && a[0] == '-')
      usage(2);
    else
      o.csv = a;
  }
  if (o.csv.empty()) o.csv = "bench/results/" + machine_tag() + "/peers.csv";
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (o.tag_only) {
    std::printf("%s\n", machine_tag().c_str());
    return 0;
  }

  std::vector<Entry> entries;
  for (auto make : {make_mujoco_runners, make_bullet_runners, make_ode_runners, make_tumble_runners}) {
    for (auto& r : make()) {
      if (selected(o, *r)) entries.push_back(Entry{std::move(r), {}, {}});
    }
  }

  std::printf(
      "peers: N free boxes %g x %g x %g m, density %g (m = %g kg, I = (%g, %g, %g) kg m^2), random\n"
      "orientations, random directions of omega with |omega| = %g rad/s (seed %llu), gravity (%g, %g, %g),\n"
      "h = %g s, no contacts or collision; one thread\n\n",
      kBoxSize[0], kBoxSize[1], kBoxSize[2], kDensity, kMass, kMoments[0], kMoments[1], kMoments[2],
      kOmegaNorm, static_cast<unsigned long long>(kSeed), kGravity[0], kGravity[1], kGravity[2], kTimestep);
  std::printf("machine:  %s (AVX-512: %s), %u logical CPUs, %s RAM; tag %s\n", cpuinfo("model name").c_str(),
              has_avx512() ? "yes" : "no", std::thread::hardware_concurrency(), memory_total().c_str(),
              machine_tag().c_str());
  std::printf("compiler: %s, build %s, flags \"%s\"\n", compiler().c_str(), PEERS_BUILD_TYPE,
              PEERS_CXX_FLAGS);
  std::printf("tumble:   %s%s%s\n", PEERS_TUMBLE_VERSION, *PEERS_GIT_COMMIT ? ", commit " : "",
              PEERS_GIT_COMMIT);
  std::printf(
      "settings: %d interleaved repetitions (engine order rotated per round), ~%g s of stepping per timed\n"
      "          run, in segments of at most %ld steps (%g s simulated) each from the initial states after "
      "a\n"
      "          fresh set-up and one untimed warm-up step; sizes skipped when set-up or one step is\n"
      "          predicted > %g s; process niceness %d\n",
      o.reps, o.target, kMaxSegmentSteps, static_cast<double>(kMaxSegmentSteps) * kTimestep, o.budget,
      getpriority(PRIO_PROCESS, 0));
  std::printf("engines:\n");
  for (const Entry& e : entries) std::printf("  %-26s %s\n", e.name().c_str(), e.runner->describe().c_str());
  std::printf("\n");
  std::fflush(stdout);

  if (o.accuracy) run_accuracy(entries);
  for (std::size_t n : o.sizes) {
    run_size(entries, n, o);
    write_csv(entries, o.csv);  // after every size, so an interrupted run keeps what it measured
  }

  // Summary: median body-steps per second by engine and size.
  std::printf("== Summary: median body-steps per second (x MuJoCo RK4 at the same N)\n%-28s",
              "engine/variant");
  for (std::size_t n : o.sizes) std::printf(" %18s", ("N = " + size_name(n)).c_str());
  std::printf("\n");
  std::map<std::size_t, double> reference;
  for (const Entry& e : entries) {
    if (e.name() != "mujoco/rk4") continue;
    for (const Case& c : e.cases) reference[c.n] = c.rate_median;
  }
  for (const Entry& e : entries) {
    std::printf("%-28s", e.name().c_str());
    for (const Case& c : e.cases) {
      std::string cell = c.note.empty() ? show(c.rate_median) : "not run";
      if (c.note.empty() && reference.count(c.n) && !std::isnan(reference[c.n])) {
        cell += " (" + show(c.rate_median / reference[c.n], 'g', 2) + ")";
      }
      std::printf(" %18s", cell.c_str());
    }
    std::printf("\n");
  }
  std::printf("\n");
  for (const Entry& e : entries) {
    if (!e.runner->notes().empty())
      std::printf("note: %s: %s\n", e.name().c_str(), e.runner->notes().c_str());
  }
  std::printf("threads in this process at the end: %d\nwrote %s\n", process_threads(), o.csv.c_str());
  return 0;
}
