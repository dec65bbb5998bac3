// The T-handle of the Dzhanibekov video, as a library user writes it: mass properties from shapes,
// a torque-free spin about the intermediate axis, and the times at which the handle flips over.
#include <cstdio>

#include "tumble/dynamics/quantities.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/sim/simulate.hpp"

int main() {
  using namespace tumble;
  // Aluminium: a bar 80 mm × 16 mm × 16 mm with a 40 mm stem screwed into its middle.
  const MassSpec aluminium = MassSpec::density(2700.0);
  const MassProperties bar = solid_mass_properties(Box{Vec3(0.08, 0.016, 0.016)}, aluminium);
  const MassProperties stem = solid_mass_properties(Cylinder{0.006, 0.04}, aluminium)
                                  .transformed(Mat3::Identity(), Vec3(0, 0, 0.028));
  Model model;
  model.add_body(RigidBody::from_mass_properties(bar + stem, "t_handle"));
  const RigidBody& handle = model.bodies[0];
  std::printf("principal moments (kg m^2): %.6g %.6g %.6g\n", handle.Lambda()(0), handle.Lambda()(1),
              handle.Lambda()(2));

  // Spin at 20 rad/s about the intermediate principal axis, with a small wobble about the others.
  const Vec3 omega_b(0.05, 20.0, 0.05);
  BodyState s;
  s.omega_w = s.q * omega_b;
  RunSettings settings;
  settings.duration = 5.0;
  settings.timestep = 1e-4;
  settings.integrator = "rk4";
  double last = 0.0;
  simulate(model, SystemState{0.0, {s}, {}}, settings, [&](const SystemState& x) {
    const double w2 = x.bodies[0].omega_b().y();
    if ((w2 > 0) != (last > 0) && x.t > 0) std::printf("flip at t = %.4f s\n", x.t);
    last = w2;
    return true;
  });
  return 0;
}
