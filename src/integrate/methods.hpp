#pragma once
// Factories of the integrators, one per source file; registry.cpp maps names to them.
#include <memory>

#include "tumble/integrate/integrator.hpp"

namespace tumble::methods {

std::unique_ptr<Integrator> explicit_euler();
std::unique_ptr<Integrator> semi_implicit_euler();
std::unique_ptr<Integrator> rk4();
std::unique_ptr<Integrator> lie_rk4();
std::unique_ptr<Integrator> implicit_gyro();
std::unique_ptr<Integrator> splitting();
std::unique_ptr<Integrator> splitting4();
std::unique_ptr<Integrator> implicit_midpoint();
std::unique_ptr<Integrator> exact();
std::unique_ptr<AdaptiveIntegrator> dopri45(const Tolerances& tolerances);

}  // namespace tumble::methods
