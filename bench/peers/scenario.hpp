#pragma once
// The scenario every engine runs, and the interface each engine's runner implements.
//
// N free boxes 0.1 × 0.2 × 0.3 m of density 1000 kg/m³ under uniform gravity, no contacts and no
// collision detection anywhere, fixed step h = 1e-3 s. Every engine gets the same initial states.
//
// Frames: each engine's body frame is the box's own frame — origin at the centre of mass, axes along
// the edges, which are the principal axes. So no engine has an offset between its body frame and the
// inertial frame, and an orientation read from any engine is directly the box's orientation.
//
// This header deliberately uses plain arrays, not Eigen or any engine's types, so that each runner's
// translation unit includes only its own engine.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace peers {

/// Edge lengths along the box's x, y, z axes (m).
inline constexpr std::array<double, 3> kBoxSize{0.1, 0.2, 0.3};
inline constexpr double kDensity = 1000.0;  // kg/m³
/// m = ρ a b c = 6 kg.
inline constexpr double kMass = kDensity * 0.1 * 0.2 * 0.3;
/// Principal moments about x, y, z: m/12 (b² + c², a² + c², a² + b²) = (0.065, 0.05, 0.025) kg m².
inline constexpr std::array<double, 3> kMoments{kMass / 12 * (0.2 * 0.2 + 0.3 * 0.3),
                                                kMass / 12 * (0.1 * 0.1 + 0.3 * 0.3),
                                                kMass / 12 * (0.1 * 0.1 + 0.2 * 0.2)};
inline constexpr std::array<double, 3> kGravity{0.0, 0.0, -9.81};  // m/s²
inline constexpr double kTimestep = 1e-3;                          // s, every engine
inline constexpr double kOmegaNorm = 10.0;                         // |ω| (rad/s) of every box at t = 0
inline constexpr std::uint64_t kSeed = 20261126;                   // the initial states' random seed

/// The state of one box in the engine-neutral form the harness hands out and reads back.
struct BoxState {
  std::array<double, 3> position{};             ///< centre of mass, world (m)
  std::array<double, 4> q{1.0, 0.0, 0.0, 0.0};  ///< box → world, (w, x, y, z), unit
  std::array<double, 3> velocity{};             ///< of the centre of mass, world (m/s)
  std::array<double, 3> omega{};                ///< angular velocity, world (rad/s)
};

/// The first n boxes of the scenario (the same for any n: box i does not depend on n): uniformly
/// random orientations, ω in a uniformly random direction with |ω| = kOmegaNorm, at rest otherwise,
/// centres on a 1 m grid (irrelevant without collision, but keeps the boxes apart). The generator is
/// written out here (splitmix64) so that the states are the same on every platform and library.
std::vector<BoxState> initial_boxes(std::size_t n, std::uint64_t seed = kSeed);

/// Rotational kinetic energy ½ ω_bᵀ Λ ω_b of a box, ω_b = Rᵀ ω (J).
double rotational_energy(const BoxState& box);

/// One engine in one configuration. The harness calls setup, then advance (timed) any number of times,
/// then teardown; set-up and teardown are never timed.
class Runner {
 public:
  virtual ~Runner() = default;
  virtual std::string engine() const = 0;   ///< "mujoco", "bullet", "ode", "tumble"
  virtual std::string variant() const = 0;  ///< "rk4", "euler", ...
  /// One line for the report: library version, precision and the settings chosen.
  virtual std::string describe() const = 0;
  /// Why set-up may grow faster than N, for the message when a size is skipped (empty if it does not).
  virtual std::string setup_note() const { return {}; }
  /// An engine-specific reason not to run n boxes within `budget` seconds of set-up (empty: no
  /// objection). main.cpp also extrapolates every engine's measured set-up and step times.
  virtual std::string skip_reason(std::size_t /*n*/, double /*budget*/) const { return {}; }
  /// Anything the runner observed that a reader of the figures should know (empty if nothing).
  virtual std::string notes() const { return {}; }

  /// Builds a world holding these boxes (replacing any previous one).
  virtual void setup(const std::vector<BoxState>& boxes) = 0;
  /// Advances the world by `steps` steps of kTimestep; returns the number of steps actually taken
  /// (rates count those).
  virtual long advance(long steps) = 0;
  /// The current state of every box.
  virtual void read(std::vector<BoxState>& out) const = 0;
  /// Frees the world.
  virtual void teardown() = 0;

  /// Called with the step count and the boxes after every `every` steps.
  using SampleSink = std::function<void(long step, const std::vector<BoxState>& boxes)>;
  /// Runs `steps` steps on the world set up, reporting every `every` steps (for the accuracy case). By
  /// default advance + read; an engine whose advance restarts something per call overrides it.
  virtual void run_sampled(long steps, long every, const SampleSink& sink);
};

// One factory per engine, each in its own file.
std::vector<std::unique_ptr<Runner>> make_mujoco_runners();  // RK4 and Euler, one compiled model
std::vector<std::unique_ptr<Runner>> make_bullet_runners();
std::vector<std::unique_ptr<Runner>> make_ode_runners();
std::vector<std::unique_ptr<Runner>> make_tumble_runners();  // rk4, splitting, semi_implicit_euler

}  // namespace peers
