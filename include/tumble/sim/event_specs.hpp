#pragma once
// Events as a scene states them ([[events]], docs/scene-format.md): a condition on one body or particle
// named by what it watches, turned into the Event (simulate.hpp) whose g crosses zero at the moment.
//  - column: a column of the output-field table crosses a value, g = x_k − value; e.g. "w2" (^bω₂,
//    the intermediate-axis component, which changes sign at every flip of a body spinning near that
//    axis), "com_z" (a height), "theta" (the 3-1-3 nutation angle). One table defines what a column
//    means for the CSV, the HDF5 file, Python and the events alike.
//  - angle: the angle between a body-fixed axis a (reference frame) and a world direction d crosses θ,
//    g = ∠(R_ref a, d) − θ, the angle from atan2(|a × d|, a · d): accurate near 0 and π, where acos of
//    the dot product loses half its digits.
#include <string>
#include <vector>

#include "tumble/forces/model.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {

struct EventSpec {
  enum class Kind { column, angle };
  std::string name;
  size_t row = 0;  ///< the body or particle watched: its row in a sample (bodies, then particles)
  Kind kind = Kind::column;
  // column
  const BodyField* field = nullptr;
  int component = 0;
  double value = 0.0;  ///< in the field's unit
  // angle
  Vec3 axis = Vec3::UnitZ();    ///< body-fixed, reference frame
  Vec3 toward = Vec3::UnitZ();  ///< world
  double angle = 0.0;           ///< rad, in [0, π]

  int direction = 0;  ///< +1 rising crossings only, −1 falling only, 0 both
  bool stop = false;  ///< end the run at the crossing
};

/// The Event that watches `spec` in runs of `model` (its g reads row spec.row of the state).
Event make_event(const Model& model, const EventSpec& spec);

/// The Events of a list of specs, in order (EventHit::index is the spec's index).
std::vector<Event> make_events(const Model& model, const std::vector<EventSpec>& specs);

}  // namespace tumble
