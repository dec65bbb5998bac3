// ODE (0.16 from Debian's libode-dev): one dBody per box in a dWorld, stepped by dWorldStep.
//
// - No geoms and no space: ODE's collision detection is a separate library layer that is simply not
//   used, so bodies only integrate.
// - Mass: dMassSetParameters with the centre of mass at the body origin and the principal moments on
//   the diagonal, so the body frame is the box frame.
// - Gyroscopic mode on (dBodySetGyroscopicMode, also ODE's default): without it ODE drops ω × Iω.
// - dWorldStep: the "big matrix" stepper named in the brief (dWorldQuickStep is the iterative one;
//   with no joints both reduce to a per-body update).
// - ODE's defaults otherwise: no auto-disable, no damping, infinitesimal orientation update
//   (finite rotation mode 0).
// - Conventions: dQuaternion is (w, x, y, z); angular velocity is in world axes.
#include <stdexcept>
#include <string>
#include <vector>

#include <ode/ode.h>

#include "scenario.hpp"

namespace peers {
namespace {

class OdeRunner final : public Runner {
 public:
  OdeRunner() {
    // ODE's global data (once per process; kept until exit, as ODE's own demos do).
    static const bool initialised = dInitODE2(0) != 0;
    if (!initialised) throw std::runtime_error("ODE: dInitODE2 failed");
  }
  ~OdeRunner() override { teardown(); }

  std::string engine() const override { return "ode"; }
  std::string variant() const override { return "dworldstep"; }
  std::string describe() const override {
    return std::string("ODE ") + PEERS_ODE_VERSION + " (dReal " + (sizeof(dReal) == 8 ? "double" : "float") +
           "; " + dGetConfiguration() + "), no geoms or space, gyroscopic mode on, dWorldStep";
  }

  void setup(const std::vector<BoxState>& boxes) override {
    teardown();
    world_ = dWorldCreate();
    dWorldSetGravity(world_, kGravity[0], kGravity[1], kGravity[2]);
    dWorldSetAutoDisableFlag(world_, 0);  // the default, stated: a disabled body is not integrated
    dMass mass;
    dMassSetParameters(&mass, kMass, 0, 0, 0, kMoments[0], kMoments[1], kMoments[2], 0, 0, 0);
    bodies_.reserve(boxes.size());
    for (const BoxState& b : boxes) {
      const dBodyID body = dBodyCreate(world_);
      dBodySetMass(body, &mass);
      dBodySetPosition(body, b.position[0], b.position[1], b.position[2]);
      const dQuaternion q{b.q[0], b.q[1], b.q[2], b.q[3]};  // (w, x, y, z), as ODE
      dBodySetQuaternion(body, q);
      dBodySetLinearVel(body, b.velocity[0], b.velocity[1], b.velocity[2]);
      dBodySetAngularVel(body, b.omega[0], b.omega[1], b.omega[2]);  // world axes
      dBodySetGyroscopicMode(body, 1);
      dBodySetLinearDamping(body, 0);
      dBodySetAngularDamping(body, 0);
      bodies_.push_back(body);
    }
  }

  long advance(long steps) override {
    for (long s = 0; s < steps; ++s) dWorldStep(world_, kTimestep);
    return steps;
  }

  void read(std::vector<BoxState>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const dReal* p = dBodyGetPosition(bodies_[i]);
      const dReal* q = dBodyGetQuaternion(bodies_[i]);
      const dReal* v = dBodyGetLinearVel(bodies_[i]);
      const dReal* w = dBodyGetAngularVel(bodies_[i]);
      out[i].position = {p[0], p[1], p[2]};
      out[i].q = {q[0], q[1], q[2], q[3]};
      out[i].velocity = {v[0], v[1], v[2]};
      out[i].omega = {w[0], w[1], w[2]};
    }
  }

  void teardown() override {
    if (world_) dWorldDestroy(world_);  // destroys its bodies too
    world_ = nullptr;
    bodies_.clear();
  }

 private:
  dWorldID world_ = nullptr;
  std::vector<dBodyID> bodies_;
};

}  // namespace

std::vector<std::unique_ptr<Runner>> make_ode_runners() {
  std::vector<std::unique_ptr<Runner>> runners;
  runners.push_back(std::make_unique<OdeRunner>());
  return runners;
}

}  // namespace peers
