// Bullet (3.24 from Debian's libbullet-dev): one btRigidBody per box in a btDiscreteDynamicsWorld.
//
// - Precision: Debian ships a float build and a double build (bullet-float64, with
//   BT_USE_DOUBLE_PRECISION); CMake picks the double one unless TUMBLE_PEERS_BULLET_DOUBLE=OFF, and
//   describe() reports sizeof(btScalar) as compiled.
// - Shape: one shared btEmptyShape — no geometry, so nothing to collide. Bullet cannot derive an
//   inertia from it, so the principal moments are given as the body's local inertia (the body frame is
//   the box frame: principal axes, centre of mass at the origin).
// - No collision: bodies are added with collision group 1 and mask 0, so the broadphase never accepts
//   a pair (it still keeps an AABB per body, as it does in any Bullet world).
// - Deactivation off (DISABLE_DEACTIVATION): a sleeping body would stop being integrated.
// - Damping 0 (also the default); gyroscopic term: Bullet's default flag
//   BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY, set explicitly here so the choice is visible.
// - One step per stepSimulation(h, 0): maxSubSteps = 0 is Bullet's variable-step mode, exactly one
//   internal step of h per call, without the fixed-step accumulator and its motion-state interpolation.
#include <memory>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "scenario.hpp"

namespace peers {
namespace {

class BulletRunner final : public Runner {
 public:
  ~BulletRunner() override { teardown(); }
  std::string engine() const override { return "bullet"; }
  std::string variant() const override { return "default_gyro"; }
  std::string describe() const override {
    return "Bullet " + std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100) +
           " (" + PEERS_BULLET_PKG + ", btScalar " + (sizeof(btScalar) == 8 ? "double" : "float") +
           "), btEmptyShape, collision mask 0, deactivation off, damping 0, "
           "BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY, stepSimulation(h, 0)";
  }

  void setup(const std::vector<BoxState>& boxes) override {
    teardown();
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       config_.get());
    world_->setGravity(btVector3(kGravity[0], kGravity[1], kGravity[2]));  // before adding bodies
    shape_ = std::make_unique<btEmptyShape>();
    const btVector3 inertia(kMoments[0], kMoments[1], kMoments[2]);
    bodies_.reserve(boxes.size());
    for (const BoxState& b : boxes) {
      btRigidBody::btRigidBodyConstructionInfo info(kMass, nullptr, shape_.get(), inertia);
      info.m_linearDamping = 0;
      info.m_angularDamping = 0;
      auto body = std::make_unique<btRigidBody>(info);
      // btQuaternion takes (x, y, z, w).
      body->setWorldTransform(btTransform(btQuaternion(b.q[1], b.q[2], b.q[3], b.q[0]),
                                          btVector3(b.position[0], b.position[1], b.position[2])));
      body->setLinearVelocity(btVector3(b.velocity[0], b.velocity[1], b.velocity[2]));
      body->setAngularVelocity(btVector3(b.omega[0], b.omega[1], b.omega[2]));  // world axes
      body->setActivationState(DISABLE_DEACTIVATION);
      body->setFlags(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
      world_->addRigidBody(body.get(), 1, 0);
      bodies_.push_back(std::move(body));
    }
  }

  long advance(long steps) override {
    for (long s = 0; s < steps; ++s) world_->stepSimulation(btScalar(kTimestep), 0);
    return steps;
  }

  void read(std::vector<BoxState>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const btRigidBody& body = *bodies_[i];
      const btTransform& t = body.getWorldTransform();
      const btQuaternion q = t.getRotation();
      const btVector3& p = t.getOrigin();
      const btVector3& v = body.getLinearVelocity();
      const btVector3& w = body.getAngularVelocity();
      out[i].position = {p.x(), p.y(), p.z()};
      out[i].q = {q.w(), q.x(), q.y(), q.z()};
      out[i].velocity = {v.x(), v.y(), v.z()};
      out[i].omega = {w.x(), w.y(), w.z()};
    }
  }

  void teardown() override {
    // The world goes first: its destructor releases every body's broadphase proxy. Removing bodies one
    // by one instead costs O(N) each (a linear search in the world's body list), O(N²) in all.
    world_.reset();
    bodies_.clear();
    shape_.reset();
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
  }

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::unique_ptr<btEmptyShape> shape_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

}  // namespace

std::vector<std::unique_ptr<Runner>> make_bullet_runners() {
  std::vector<std::unique_ptr<Runner>> runners;
  runners.push_back(std::make_unique<BulletRunner>());
  return runners;
}

}  // namespace peers
