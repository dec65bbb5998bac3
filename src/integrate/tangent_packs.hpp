#pragma once
// Tangents on SIMD packs (issue 25's cost target). step_tangent steps a TangentCoordinates a body at a
// time on Dual<double, 16>: each operation is a loop over 16 derivatives of one body, and a step costs
// about 13 state steps per direction. Here the same dual numbers are regrouped so that a pack's lanes
// are (body, group of k slots) pairs — lane ℓ holds body ℓ / G and its slots (ℓ mod G)·k … + k − 1,
// G = ⌈slots / k⌉, k = 2 or 4 — and stepped by the same templates (newton_euler, advanced,
// semi_implicit_euler_update, rk4::stage) on Dual<Pack, k>: a value and a few derivatives per lane,
// in registers, every body and group at once; about 2 state steps per direction. Each derivative is computed by the operations step_tangent applies to it, in the same order,
// so the numbers are step_tangent's bit for bit (tests/integrate/tangent_packs_test.cpp); only the
// layout differs. The bench: bench/sensitivity_bench.cpp, section 1.
//
// The loads a pack forms itself are those of uniform fields (f = m g through each centre of mass, the
// only loads constant over a step; g may be seeded, for sensitivities with respect to it); systems
// with any other force model step a body at a time.
#include <span>

#include "tumble/integrate/tangent_system.hpp"

namespace tumble::tangent_packs {

/// The one-step maps the packs take (each the template its integrator's step_tangent instantiates).
enum class Method { euler, semi_implicit_euler, rk4 };

/// Whether packs can step `model`'s tangents: no force model, or uniform fields only (each with its
/// three parameters g, ForceModel::uniform_acceleration).
[[nodiscard]] bool applies(const Model& model);

/// Takes x through steps of the given lengths by `method`, every body on packs, with the derivatives in
/// x's first `slots` slots (the seeded ones; the others stay as they are, zero). x.t is the caller's.
/// False, and x untouched, when !applies(model).
bool steps(Method method, const Model& model, Formulation formulation, TangentCoordinates& x,
           std::span<const double> lengths, int slots);

}  // namespace tumble::tangent_packs
