// MuJoCo (2.2.2 from Debian's libmujoco-dev): one body with a free joint per box.
//
// - Each body has an explicit <inertial> (mass, diaginertia along the body axes, at the body origin)
//   and no geoms: with no geom there is nothing to collide, and with inertiafromgeom="false" the
//   compiler takes the inertia as written. The body frame is then the box frame (principal axes, centre
//   of mass at the origin), so qpos holds the box's pose directly.
// - <flag contact="disable"/>: collision detection and the contact solver are skipped entirely.
// - Integrators: RK4 and Euler (MuJoCo's semi-implicit Euler), set per run on the compiled model.
// - Free-joint conventions: qpos = (position, quaternion w, x, y, z), world; qvel = (linear velocity in
//   world axes, angular velocity in the body's local axes).
//
// MuJoCo 2.2.2's XML compiler takes O(N²) time for N free bodies (17 s at N = 1e4 on a 2-vCPU EPYC),
// so the compiled model is built once per N and kept (in memory) for both variants and every
// repetition; each set-up only makes a fresh mjData. Sizes whose compile would exceed the harness's
// budget are skipped by main.cpp from the measured growth.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>

#include "scenario.hpp"

namespace peers {
namespace {

/// The compiled model of the last N asked for, shared by the two MuJoCo runners.
class ModelCache {
 public:
  ~ModelCache() { release(); }
  mjModel* get(std::size_t n) {
    if (model_ && n_ == n) return model_;
    release();
    const auto t0 = std::chrono::steady_clock::now();
    model_ = compile(n);
    compile_seconds[n] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    n_ = n;
    return model_;
  }
  /// Seconds taken by mj_loadXML, by N (for the report).
  std::map<std::size_t, double> compile_seconds;
  void release() {
    if (model_) mj_deleteModel(model_);
    model_ = nullptr;
  }

 private:
  static std::string xml(std::size_t n) {
    std::ostringstream s;
    s.precision(17);
    s << "<mujoco model=\"peers\">\n"
      // Inertia exactly as given (no geoms to derive it from anyway).
      << "  <compiler inertiafromgeom=\"false\"/>\n"
      // mjData's stack: MuJoCo 2.2.2's default grows as nv² (1.7 GB at N = 1000, and past the range of
      // an int near N = 2700), while mj_step here uses ~17 nv (measured with d->maxuse_stack). Sized
      // explicitly with a wide margin; it only affects memory and set-up, not the step.
      << "  <size nstack=\"" << 10'000 + 100 * 6 * n << "\"/>\n"
      << "  <option timestep=\"" << kTimestep << "\" gravity=\"" << kGravity[0] << ' ' << kGravity[1] << ' '
      << kGravity[2] << "\" integrator=\"RK4\">\n"
      << "    <flag contact=\"disable\"/>\n"
      << "  </option>\n"
      << "  <worldbody>\n";
    for (std::size_t i = 0; i < n; ++i) {
      // The pose is written into qpos at set-up; the body starts at the origin here.
      s << "    <body><freejoint/><inertial pos=\"0 0 0\" mass=\"" << kMass << "\" diaginertia=\""
        << kMoments[0] << ' ' << kMoments[1] << ' ' << kMoments[2] << "\"/></body>\n";
    }
    s << "  </worldbody>\n</mujoco>\n";
    return s.str();
  }

  static mjModel* compile(std::size_t n) {
    // Through MuJoCo's virtual file system: nothing is written to disk.
    const std::string text = xml(n);
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    if (mj_makeEmptyFileVFS(vfs.get(), "peers.xml", static_cast<int>(text.size())) != 0) {
      throw std::runtime_error("MuJoCo: cannot make the in-memory XML file");
    }
    const int f = mj_findFileVFS(vfs.get(), "peers.xml");
    std::memcpy(vfs->filedata[f], text.data(), text.size());
    char error[1000] = "";
    mjModel* m = mj_loadXML("peers.xml", vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (!m) throw std::runtime_error(std::string("MuJoCo: ") + error);
    if (static_cast<std::size_t>(m->nbody) != n + 1 || static_cast<std::size_t>(m->nv) != 6 * n) {
      mj_deleteModel(m);
      throw std::runtime_error("MuJoCo: the compiled model does not have the bodies asked for");
    }
    return m;
  }

  mjModel* model_ = nullptr;
  std::size_t n_ = 0;
};

class MujocoRunner final : public Runner {
 public:
  MujocoRunner(std::shared_ptr<ModelCache> cache, int integrator, std::string name)
      : cache_(std::move(cache)), integrator_(integrator), name_(std::move(name)) {}
  ~MujocoRunner() override { teardown(); }

  std::string engine() const override { return "mujoco"; }
  std::string variant() const override { return name_; }
  std::string describe() const override {
    return std::string("MuJoCo ") + mj_versionString() + " (mjtNum " +
           (sizeof(mjtNum) == 8 ? "double" : "float") +
           "), free joints, no geoms, contact disabled, integrator " +
           (integrator_ == mjINT_RK4 ? "RK4" : "Euler") + ", mj_step";
  }
  std::string setup_note() const override {
    return "MuJoCo 2.2.2 compiles a model of N free bodies in O(N^2) time";
  }
  std::string skip_reason(std::size_t n, double budget) const override {
    // The compile is cached, so the variant that did not compile sees only mj_makeData in its own
    // set-up times: extrapolate the compile itself from the largest size compiled below n, if that
    // compile took long enough (1 s) to be more than noise. Growth exponent from the size compiled
    // before it if that also took ≥ 1 s (at least 1), else 2, the observed behaviour.
    const auto& done = cache_->compile_seconds;
    if (done.count(n)) return {};
    auto last = done.lower_bound(n);
    if (last == done.begin()) return {};
    --last;
    if (last->second < 1.0) return {};
    double exponent = 2;
    bool measured = false;
    if (last != done.begin()) {
      const auto prev = std::prev(last);
      if (prev->second >= 1.0 && last->second > prev->second) {
        exponent =
            std::max(1.0, std::log(last->second / prev->second) /
                              std::log(static_cast<double>(last->first) / static_cast<double>(prev->first)));
        measured = true;
      }
    }
    const double predicted = last->second *
                             std::pow(static_cast<double>(n) / static_cast<double>(last->first), exponent);
    if (predicted <= budget) return {};
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "compile predicted %.0f s (> %.0f s): %.3g s at N = %zu, times (N ratio)^%.2f%s (%s)",
                  predicted, budget, last->second, last->first, exponent, measured ? "" : " assumed",
                  setup_note().c_str());
    return buf;
  }
  std::string notes() const override {
    // Where set-up time goes: the XML compile (once per N, shared by both variants) and mj_makeData
    // (every set-up).
    std::string s = "set-up: compile (mj_loadXML, once per N) / longest mj_makeData:";
    for (const auto& [n, seconds] : make_data_seconds_) {
      const auto compiled = cache_->compile_seconds.find(n);
      s += " N = " + std::to_string(n) + ": " +
           (compiled == cache_->compile_seconds.end() ? std::string("-") : seconds_text(compiled->second)) +
           " / " + seconds_text(seconds) + ";";
    }
    return s;
  }

  void setup(const std::vector<BoxState>& boxes) override {
    teardown();
    m_ = cache_->get(boxes.size());
    m_->opt.integrator = integrator_;
    const auto t0 = std::chrono::steady_clock::now();
    d_ = mj_makeData(m_);
    double& longest = make_data_seconds_[boxes.size()];
    longest = std::max(longest, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const BoxState& b = boxes[i];
      mjtNum* qpos = d_->qpos + 7 * i;
      mjtNum* qvel = d_->qvel + 6 * i;
      for (int k = 0; k < 3; ++k) qpos[k] = b.position[static_cast<std::size_t>(k)];
      for (int k = 0; k < 4; ++k) qpos[3 + k] = b.q[static_cast<std::size_t>(k)];     // w, x, y, z as MuJoCo
      for (int k = 0; k < 3; ++k) qvel[k] = b.velocity[static_cast<std::size_t>(k)];  // world axes
      // Angular velocity in the body's axes: ω_b = Rᵀ ω.
      mju_rotVecQuat(qvel + 3, b.omega.data(), conjugate(b.q).data());
    }
    d_->time = 0;
  }

  long advance(long steps) override {
    m_->opt.integrator = integrator_;  // the model is shared with the other variant
    for (long s = 0; s < steps; ++s) mj_step(m_, d_);
    // MuJoCo does not stop on a non-finite state: it warns and resets the data to the model's initial
    // state, which would hide a blow-up. Treat it as a failure.
    for (const int w : {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC}) {
      if (d_->warning[w].number > 0)
        throw std::runtime_error("MuJoCo reset the simulation after a non-finite state");
    }
    return steps;
  }

  void read(std::vector<BoxState>& out) const override {
    const std::size_t n = static_cast<std::size_t>(m_->nbody - 1);
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      BoxState& b = out[i];
      const mjtNum* qpos = d_->qpos + 7 * i;
      const mjtNum* qvel = d_->qvel + 6 * i;
      for (int k = 0; k < 3; ++k) b.position[static_cast<std::size_t>(k)] = qpos[k];
      for (int k = 0; k < 4; ++k) b.q[static_cast<std::size_t>(k)] = qpos[3 + k];
      for (int k = 0; k < 3; ++k) b.velocity[static_cast<std::size_t>(k)] = qvel[k];
      mju_rotVecQuat(b.omega.data(), qvel + 3, qpos + 3);  // ω = R ω_b
    }
  }

  void teardown() override {
    if (d_) mj_deleteData(d_);
    d_ = nullptr;
    m_ = nullptr;  // owned by the cache
  }

 private:
  static std::string seconds_text(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g s", s);
    return buf;
  }
  static std::array<double, 4> conjugate(const std::array<double, 4>& q) {
    return {q[0], -q[1], -q[2], -q[3]};
  }

  std::shared_ptr<ModelCache> cache_;
  int integrator_;
  std::string name_;
  std::map<std::size_t, double> make_data_seconds_;
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
};

}  // namespace

std::vector<std::unique_ptr<Runner>> make_mujoco_runners() {
  if (mj_version() != mjVERSION_HEADER) {
    throw std::runtime_error("MuJoCo: the library's version does not match its header's");
  }
  auto cache = std::make_shared<ModelCache>();
  std::vector<std::unique_ptr<Runner>> runners;
  runners.push_back(std::make_unique<MujocoRunner>(cache, mjINT_RK4, "rk4"));
  runners.push_back(std::make_unique<MujocoRunner>(cache, mjINT_EULER, "euler"));
  return runners;
}

}  // namespace peers
