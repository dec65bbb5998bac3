// Scenes and runs in Python: tumble.Scene, load_scene, and simulate, which records every sample as
// NumPy arrays made from the output-field table (sim/output_fields.hpp), as the CSV and HDF5 writers are.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "bindings.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/sim/event_specs.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/run.hpp"
#include "tumble/sim/run_plan.hpp"
#include "tumble/sim/run_settings.hpp"

namespace py = pybind11;

namespace tumble::python {
namespace {

/// Samples of one quantity, grown as the run goes and handed to NumPy as (T, ...shape) at the end.
struct Series {
  std::vector<double> values;
  std::vector<py::ssize_t> shape;  // of one sample
  /// The samples as a NumPy array that *is* this buffer (no copy: the vector moves into a capsule that
  /// the array owns), so a long run is never held twice. Leaves `values` empty.
  py::array_t<double> release() {
    std::vector<py::ssize_t> full{0};
    py::ssize_t per = 1;
    for (const py::ssize_t n : shape) per *= n;
    full[0] = per == 0 ? 0 : static_cast<py::ssize_t>(values.size()) / per;
    full.insert(full.end(), shape.begin(), shape.end());
    auto* buffer = new std::vector<double>(std::move(values));
    const py::capsule owner(buffer, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    return py::array_t<double>(full, buffer->data(), owner);
  }
};

/// The world quantities of every body at a state as NumPy arrays (n, 3) and (n, 4): centre of mass,
/// w-first quaternion of the principal frame, centre-of-mass velocity, angular velocity.
py::tuple body_arrays(std::span<const BodyState> bodies) {
  const auto n = static_cast<py::ssize_t>(bodies.size());
  py::array_t<double> o({n, py::ssize_t{3}}), q({n, py::ssize_t{4}}), v({n, py::ssize_t{3}}),
      w({n, py::ssize_t{3}});
  auto O = o.mutable_unchecked<2>();
  auto Q = q.mutable_unchecked<2>();
  auto V = v.mutable_unchecked<2>();
  auto W = w.mutable_unchecked<2>();
  for (py::ssize_t j = 0; j < n; ++j) {
    const BodyState& b = bodies[static_cast<size_t>(j)];
    for (int k = 0; k < 3; ++k) {
      O(j, k) = b.o(k);
      V(j, k) = b.v(k);
      W(j, k) = b.omega_w(k);
    }
    Q(j, 0) = b.q.w();
    Q(j, 1) = b.q.x();
    Q(j, 2) = b.q.y();
    Q(j, 3) = b.q.z();
  }
  return py::make_tuple(o, q, v, w);
}

/// An event written in Python: g(t, position, orientation, velocity, omega) over every body (the arrays
/// of body_arrays), a float whose sign change is the event. It watches no one row.
Event python_event(const py::tuple& e) {
  if (e.size() != 4) throw InvalidArgument("a Python event is (name, g, direction, stop)");
  Event out{e[0].cast<std::string>(), {}, e[2].cast<int>(), e[3].cast<bool>()};
  out.g = [g = e[1].cast<py::function>(), name = out.name](const SystemState& s) {
    py::gil_scoped_acquire python;
    const py::tuple a = body_arrays(s.bodies);
    const py::object r = g(s.t, a[0], a[1], a[2], a[3]);
    try {
      return r.cast<double>();
    } catch (const py::cast_error&) {
      throw InvalidArgument(py::str("event '{}': its function returned {!r}; it must return a number whose "
                                    "sign changes at the event")
                                .format(name, r)
                                .cast<std::string>());
    }
  };
  return out;
}

/// A force law written in Python, called once per block of bodies (never once per body) with the time,
/// the bodies' indices and their world quantities as (n, 3) and (n, 4) arrays; it returns the force
/// (N) and the torque about the centre of mass (N·m), world axes, as two (n, 3) arrays.
/// Ctrl-C that arrived while a Python force ran: Python raised KeyboardInterrupt inside it. The step is
/// abandoned (its loads were never given) and the run ends with the samples so far, as a Ctrl-C between
/// steps does (simulate below). Not an Error: nothing may add context to it on its way out.
struct InterruptedInForce {};

std::shared_ptr<const ForceModel> python_force(py::function f) {
  return std::make_shared<const BlockCallback>(
      [f = std::move(f)](const BodyBlock& b, BlockLoads& loads) {
        py::gil_scoped_acquire python;
        const auto n = static_cast<py::ssize_t>(b.count);
        py::array_t<std::int64_t> index(n);
        py::array_t<double> o({n, py::ssize_t{3}}), q({n, py::ssize_t{4}}), v({n, py::ssize_t{3}}),
            w({n, py::ssize_t{3}});
        auto I = index.mutable_unchecked<1>();
        auto O = o.mutable_unchecked<2>();
        auto Q = q.mutable_unchecked<2>();
        auto V = v.mutable_unchecked<2>();
        auto W = w.mutable_unchecked<2>();
        for (py::ssize_t j = 0; j < n; ++j) {
          I(j) = static_cast<std::int64_t>(b.begin) + j;
          for (int k = 0; k < 3; ++k) {
            O(j, k) = b.o[k][j];
            V(j, k) = b.v[k][j];
            W(j, k) = b.omega_w[k][j];
          }
          for (int k = 0; k < 4; ++k) Q(j, k) = b.q[k][j];
        }
        py::object result;
        try {
          result = f(b.t, index, o, q, v, w);
        } catch (py::error_already_set& e) {
          if (e.matches(PyExc_KeyboardInterrupt)) throw InterruptedInForce{};
          throw;
        }
        if (!py::isinstance<py::tuple>(result) && !py::isinstance<py::list>(result)) {
          throw InvalidArgument(
              py::str("the force function returned {} (a {}); it must return (force, torque), two (n, 3) "
                      "arrays for the n = {} bodies it was given (a function without `return` gives None)")
                  .format(py::repr(result), py::type::of(result).attr("__name__"), n)
                  .cast<std::string>());
        }
        const auto pair = py::tuple(result);
        if (pair.size() != 2) {
          throw InvalidArgument(fmt::format(
              "the force function returned {} values; it must return (force, torque), two (n, 3) arrays",
              pair.size()));
        }
        using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
        const auto F = pair[0].cast<Array>();
        const auto T = pair[1].cast<Array>();
        for (const Array* a : {&F, &T}) {
          if (a->ndim() != 2 || a->shape(0) != n || a->shape(1) != 3) {
            throw InvalidArgument(
                py::str("the force function returned an array of shape {}; force and torque must be (n, 3) "
                        "for the n = {} bodies it was given")
                    .format(py::getattr(*a, "shape"), n)
                    .cast<std::string>());
          }
        }
        const auto Fv = F.unchecked<2>();
        const auto Tv = T.unchecked<2>();
        for (py::ssize_t j = 0; j < n; ++j) {
          loads.add(static_cast<size_t>(j), Vec3(Fv(j, 0), Fv(j, 1), Fv(j, 2)),
                    Vec3(Tv(j, 0), Tv(j, 1), Tv(j, 2)));
        }
      },
      "a Python force function");
}

/// The scene's rotors driven by a controller written in Python, controller(t, position, orientation,
/// velocity, omega, speeds) -> torques: the bodies' arrays (body_arrays) and the rotors' speeds (R,),
/// returning R motor torques (N m), in the scene's rotor order; sampled every `interval`, held between.
std::shared_ptr<const ForceModel> python_controller(const Model& model, py::function f, double interval) {
  const Rotors* rotors = rotors_of(model);
  if (!rotors) throw InvalidArgument("controller: the scene has no [[rotors]] for it to drive");
  const size_t R = rotors->rotors().size();
  return rotors->controlled_by(
      {interval,
       [f = std::move(f), R](const SystemView& v, std::span<const double> speeds, std::span<double> u) {
         py::gil_scoped_acquire python;
         const py::tuple a = body_arrays(v.body_states);
         py::array_t<double> Omega(static_cast<py::ssize_t>(R));
         std::copy(speeds.begin(), speeds.end(), Omega.mutable_data());
         py::object result;
         try {
           result = f(v.t, a[0], a[1], a[2], a[3], Omega);
         } catch (py::error_already_set& e) {
           if (e.matches(PyExc_KeyboardInterrupt)) throw InterruptedInForce{};
           throw;
         }
         py::array_t<double, py::array::c_style | py::array::forcecast> torques;
         try {
           torques = result.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
         } catch (const py::cast_error&) {
         }
         if (!torques || torques.ndim() != 1 || static_cast<size_t>(torques.size()) != R) {
           throw InvalidArgument(
               py::str("controller: at t = {} s it returned {!r}; it must return the {} rotors' "
                       "torques (N m), one per [[rotors]] in the scene's order")
                   .format(v.t, result, R)
                   .cast<std::string>());
         }
         std::copy_n(torques.data(), R, u.begin());
       }});
}

/// A run's samples and crossings as they arrive, into the vectors the arrays are made of.
struct Recorded {
  const Model& model;
  const std::vector<const BodyField*>& fields;
  std::span<const SystemField> system;
  const std::vector<EventSpec>& specs;
  std::vector<double>& t;
  std::vector<Series>& body;
  std::vector<Series>& diagnostics;
  Series& rotor_speed;
  Series& rotor_torque;
  std::vector<std::string>& event_names;
  std::vector<double>& event_t;
  std::vector<long>& event_rows;
  std::optional<AngleUnwrapper> unwrap;  // the scene's [output] unwrap_angles

  void sample(const SystemState& state, const DriftSample& d) {
    t.push_back(state.t);
    for (size_t f = 0; f < fields.size(); ++f) {
      std::vector<double>& v = body[f].values;
      const auto w = static_cast<size_t>(fields[f]->width);
      for (size_t r = 0; r < model.bodies.size() + state.particles.size(); ++r) {
        v.resize(v.size() + w);
        field_of_row(*fields[f], model, state, r, v.data() + v.size() - w);
        if (unwrap) unwrap->field(r, f, v.data() + v.size() - w);
      }
    }
    for (size_t f = 0; f < system.size(); ++f) {
      std::vector<double>& v = diagnostics[f].values;
      const auto w = static_cast<size_t>(system[f].width);
      v.resize(v.size() + w, std::numeric_limits<double>::quiet_NaN());  // NaN: undefined here
      if (!system[f].of_sample(d, v.data() + v.size() - w)) {
        std::fill(v.end() - static_cast<std::ptrdiff_t>(w), v.end(),
                  std::numeric_limits<double>::quiet_NaN());
      }
    }
    rotor_speed.values.insert(rotor_speed.values.end(), d.rotor_speed.begin(), d.rotor_speed.end());
    rotor_torque.values.insert(rotor_torque.values.end(), d.rotor_torque.begin(), d.rotor_torque.end());
  }
  void crossing(const EventHit& hit) {
    event_names.push_back(hit.name);
    event_t.push_back(hit.state.t);
    event_rows.push_back(hit.index < specs.size() ? static_cast<long>(specs[hit.index].row) : -1L);
  }
};

/// The scene's settings with those given as keywords on top (sim/run_settings.hpp: the keys of
/// [simulation], and threads), validated; None leaves a setting as the scene has it.
RunSettings settings_with(const Scene& scene, const py::dict& given) {
  RunSettings s = scene.settings;
  for (const auto& [key, value] : given) {
    const std::string k = py::str(key);
    const RunSetting* setting = find_run_setting(k);
    if (setting == nullptr || k.starts_with("-")) {
      std::vector<std::string_view> keys;
      for (const RunSetting& r : run_settings()) keys.push_back(r.key);
      throw InvalidArgument(
          fmt::format("simulate() has no setting '{}'; the settings are: {}", k, fmt::join(keys, ", ")));
    }
    if (value.is_none()) continue;
    const std::string given_as = k + "=";
    if (py::isinstance<py::str>(value)) {
      set_run_setting(s, *setting, value.cast<std::string>(), given_as);
    } else if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
      set_run_setting(s, *setting, value.cast<double>(), given_as);
    } else {
      throw InvalidArgument(fmt::format("{} takes a {}, not {}", given_as,
                                        setting->kind == RunSetting::Kind::name ? "name" : "number",
                                        py::repr(value).cast<std::string>()));
    }
  }
  validate(s);
  return s;
}

/// One lane per body of a scene whose bodies move independently, each watching the events given on
/// every body (every_body[k], body = "*") and those given on it: each body locates its own crossings.
std::vector<Lane> lanes_per_body(const Model& model, std::vector<Model>& lane_models,
                                 const std::vector<EventSpec>& specs, const std::vector<bool>& every_body,
                                 const std::function<void(size_t body, const EventHit&)>& record) {
  const bool independent = model.particles.empty() &&
                           std::all_of(model.forces.begin(), model.forces.end(),
                                       [](const auto& f) { return f->acts_alike_on_every_body(); });
  if (!independent) {
    throw InvalidArgument(
        "an event on every body (body = \"*\") needs bodies that move independently: no particles, and only "
        "forces that act alike on every body (gravity, central gravity, damping or drag of all bodies)");
  }
  lane_models.resize(model.bodies.size());
  std::vector<Lane> lanes(model.bodies.size());
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    lane_models[i].bodies = {model.bodies[i]};
    lane_models[i].forces = model.forces;
    Lane& lane = lanes[i];
    lane.model = &lane_models[i];
    lane.label = [&model, i] { return fmt::format("body '{}'", model.bodies[i].name()); };
    for (size_t k = 0; k < specs.size(); ++k) {
      if (!every_body[k] && specs[k].row != i) continue;
      EventSpec e = specs[k];
      e.row = 0;  // the lane's one body
      lane.events.push_back(make_event(lane_models[i], e));
    }
    lane.on_event = [record, i](const EventHit& hit) {
      record(i, hit);
    };  // a copy: the argument is a temporary
  }
  return lanes;
}

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The state to start from instead of the scene's: at time t, each row's reference-frame origin,
/// orientation (w first, reference -> world), origin velocity and ω in world axes, as a trajectory's
/// position, orientation, velocity and angular_velocity hold them (rows: bodies, then particles, whose
/// orientation and ω are not read). python/tumble/__init__.py checks the shapes.
SystemState initial_state(const Model& model, double t, const Rows& position, const Rows& orientation,
                          const Rows& velocity, const Rows& omega) {
  const auto p = position.unchecked<2>(), q = orientation.unchecked<2>(), v = velocity.unchecked<2>(),
             w = omega.unchecked<2>();
  const size_t n = model.bodies.size();
  const auto row3 = [](const auto& a, size_t i) { return Vec3(a(i, 0), a(i, 1), a(i, 2)); };
  const auto finite = [](const auto& a, size_t i, py::ssize_t width) {
    for (py::ssize_t k = 0; k < width; ++k)
      if (!std::isfinite(a(i, k))) return false;
    return true;
  };
  if (!std::isfinite(t))
    throw InvalidArgument(fmt::format("initial t = {} is not a time: give a finite one", t));
  SystemState s;
  s.t = t;
  for (size_t i = 0; i < n + model.particles.size(); ++i) {
    const bool body = i < n;
    const std::string& name = body ? model.bodies[i].name() : model.particles[i - n].name;
    if (!finite(p, i, 3) || !finite(v, i, 3) || (body && (!finite(q, i, 4) || !finite(w, i, 3)))) {
      throw InvalidArgument(fmt::format("the initial state of {} '{}' (row {}) is not finite",
                                        body ? "body" : "particle", name, i));
    }
    if (!body) {
      s.particles.push_back(ParticleState{row3(p, i), row3(v, i)});
      continue;
    }
    const Quat q_ref(q(i, 0), q(i, 1), q(i, 2), q(i, 3));
    // A trajectory's quaternions are unit to rounding; one far from it is not an orientation.
    if (std::abs(q_ref.norm() - 1.0) > 1e-6) {
      throw InvalidArgument(
          fmt::format("the initial orientation of body '{}' (row {}) has norm {}, not 1: give "
                      "a unit quaternion (w, x, y, z)",
                      name, i, q_ref.norm()));
    }
    s.bodies.push_back(state_from_reference(model.bodies[i], row3(p, i), q_ref, row3(v, i), row3(w, i)));
  }
  return s;
}

py::dict simulate(const Scene& scene_in, const py::dict& settings,
                  std::optional<std::vector<std::string>> field_names, std::optional<py::function> force,
                  const std::vector<EventSpec>& event_specs, const std::vector<py::tuple>& python_events,
                  const std::vector<bool>& every_body, std::vector<double> sample_times,
                  std::optional<py::tuple> initial, std::optional<std::string> sensitivities,
                  std::optional<py::tuple> controller) {
  // A Python force joins a copy of the model (the force list is shared, the bodies copied); what it
  // conserves is unknown, so no drift is judged, and it runs on one thread (one interpreter). A
  // controller takes the place of the scene's rotors in such a copy: the motors work, so the energy is
  // not conserved, the angular momentum still is (the rotors' torques are internal).
  std::optional<Scene> with_force;
  if (force || controller) with_force.emplace(scene_in);
  if (controller) {
    const py::object interval = (*controller)[1];  // None: every step
    const auto law = python_controller(scene_in.model, (*controller)[0].cast<py::function>(),
                                       interval.is_none() ? settings_with(scene_in, settings).timestep
                                                          : interval.cast<double>());
    for (auto& f : with_force->model.forces)
      if (dynamic_cast<const Rotors*>(f.get())) f = law;
    with_force->conserved.energy = false;
  }
  if (force) {
    with_force->model.forces.push_back(python_force(*force));
    with_force->conserved = Conservation{false, false, false};
  }
  const Scene& scene = with_force ? *with_force : scene_in;
  RunSettings s = settings_with(scene, settings);
  if (force || controller) s.threads = 1;
  s.sample_times = std::move(sample_times);
  const Model& model = scene.model;
  const std::vector<const BodyField*> fields =
      body_fields(field_names ? *field_names : scene.output_fields, model);  // names checked here
  const auto rows = static_cast<py::ssize_t>(model.bodies.size() + model.particles.size());

  // Room for every planned sample at once: growing by doubling would hold up to twice the final size.
  // Up to 1 GiB per array reserved (address space, touched only as samples arrive); beyond, or for an
  // adaptive run's extra samples, the vectors grow.
  const double planned = s.sample_times.empty()
                             ? plan_run(s, model.bodies.size(), model.particles.size()).samples
                             : static_cast<double>(s.sample_times.size() + 1);
  const auto reserve = [planned](std::vector<double>& v, double per_sample) {
    v.reserve(static_cast<size_t>(std::min(planned * per_sample, 0x1p27)));
  };
  std::vector<double> t;
  reserve(t, 1);
  std::vector<Series> body(fields.size());
  for (size_t f = 0; f < fields.size(); ++f) {
    body[f].shape = {rows, fields[f]->width};
    reserve(body[f].values, static_cast<double>(rows * fields[f]->width));
  }
  const auto system = system_fields();
  std::vector<Series> diagnostics(system.size());
  for (size_t f = 0; f < system.size(); ++f) diagnostics[f].shape = {system[f].width};
  std::vector<std::string> rotor_names;
  if (const Rotors* rotors = rotors_of(model))
    for (const Rotor& r : rotors->rotors()) rotor_names.push_back(r.name);
  Series rotor_speed{{}, {static_cast<py::ssize_t>(rotor_names.size())}}, rotor_torque = rotor_speed;
  // Events: the scene's, those given as specs, then those written in Python; each crossing is kept as
  // (name, t, row), the row -1 for a Python event.
  std::vector<EventSpec> specs = scene.events;
  specs.insert(specs.end(), event_specs.begin(), event_specs.end());
  std::vector<Event> events = make_events(model, specs);
  for (const py::tuple& e : python_events) events.push_back(python_event(e));
  std::vector<std::string> event_names;
  std::vector<double> event_t;
  std::vector<long> event_rows;
  // What the run hands over, kept as the arrays of the output-field tables.
  // Sensitivities, when carried: each body's own blocks (samples, B, 12, 12) and (samples, B, 12, P)
  // for bodies that do not interact, the whole matrices (samples, 12B, 12B) and (samples, 12B, PB) for
  // coupled ones (python/tumble/trajectory.py makes the dense views).
  Series stm, parameter_sensitivity;
  bool coupled = false;
  std::vector<std::string> parameter_names;
  class Arrays final : public RunObserver {
   public:
    Arrays(Recorded& r, Series& stm, Series& parameters, bool& coupled, std::vector<std::string>& names)
        : r_(r), stm_(stm), parameters_(parameters), coupled_(coupled), names_(names) {}
    void on_sample(const SystemState& state, const DriftSample& d) override { r_.sample(state, d); }
    void on_event(const EventHit& hit) override { r_.crossing(hit); }
    void on_sensitivities(const Sensitivities& S) override {
      coupled_ = S.coupled;
      names_ = S.parameter_names;
      append(stm_, S.stm, S.coupled);
      append(parameters_, S.parameters, S.coupled);
    }

   private:
    /// A matrix in row-major order, shaped (rows, columns) when coupled, else (B, 12, columns).
    static void append(Series& series, const Eigen::MatrixXd& M, bool whole) {
      const auto rows = static_cast<py::ssize_t>(M.rows()), cols = static_cast<py::ssize_t>(M.cols());
      if (whole) {
        series.shape = {rows, cols};
      } else {
        series.shape = {rows / 12, 12, cols};
      }
      for (Eigen::Index i = 0; i < M.rows(); ++i)
        for (Eigen::Index j = 0; j < M.cols(); ++j) series.values.push_back(M(i, j));
    }
    Recorded& r_;
    Series &stm_, &parameters_;
    bool& coupled_;
    std::vector<std::string>& names_;
  };
  Recorded recorded{model,
                    fields,
                    system,
                    specs,
                    t,
                    body,
                    diagnostics,
                    rotor_speed,
                    rotor_torque,
                    event_names,
                    event_t,
                    event_rows,
                    scene.unwrap_angles
                        ? std::optional<AngleUnwrapper>(std::in_place, fields, static_cast<size_t>(rows))
                        : std::nullopt};
  Arrays arrays_observer(recorded, stm, parameter_sensitivity, coupled, parameter_names);
  // Ctrl-C: Python's handler only sets a flag while the run holds no GIL; it is looked at every 50 ms
  // (taking the GIL for that moment), and the run then stops with the samples so far, which the caller
  // gets with the KeyboardInterrupt (python/tumble/trajectory.py).
  bool interrupted = false;
  auto next_check = std::chrono::steady_clock::now();
  const SystemState start = initial ? initial_state(model, (*initial)[0].cast<double>(),
                                                    (*initial)[1].cast<Rows>(), (*initial)[2].cast<Rows>(),
                                                    (*initial)[3].cast<Rows>(), (*initial)[4].cast<Rows>())
                                    : scene.initial;
  Run run(model, start, s, scene.conserved);
  std::vector<bool> every(specs.size(), false);  // the scene's own events first: on their bodies
  std::copy(every_body.begin(), every_body.end(),
            every.end() - static_cast<std::ptrdiff_t>(every_body.size()));
  std::vector<Model> lane_models;
  if (std::find(every.begin(), every.end(), true) != every.end()) {
    if (!python_events.empty() || force) {
      throw InvalidArgument(
          "an event on every body (body = \"*\") cannot be watched with events or forces written in Python");
    }
    run.as_lanes(lanes_per_body(model, lane_models, specs, every, [&](size_t row, const EventHit& hit) {
      event_names.push_back(hit.name);
      event_t.push_back(hit.state.t);
      event_rows.push_back(static_cast<long>(row));
    }));
  } else {
    run.watch(std::move(events));
  }
  if (sensitivities) run.carry_sensitivities(parse_sensitivity_parameters(*sensitivities));
  run.attach(arrays_observer).stop_when([&] {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_check) return interrupted;
    next_check = now + std::chrono::milliseconds(50);
    py::gil_scoped_acquire python;
    if (PyErr_CheckSignals() != 0) {
      if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
        PyErr_Clear();
        interrupted = true;
      } else {
        throw py::error_already_set();
      }
    }
    return interrupted;
  });
  {
    py::gil_scoped_release free_python;  // the run touches no Python object but the callbacks, which take it
    try {
      run.run();
    } catch (const InterruptedInForce&) {
      interrupted = true;  // the samples before the abandoned step are whole
    }
  }
  py::dict out, arrays, units, frames, diag;
  Series times{std::move(t), {}};
  out["t"] = times.release();
  for (size_t f = 0; f < fields.size(); ++f) {
    const std::string name(fields[f]->name);
    arrays[name.c_str()] = body[f].release();
    units[name.c_str()] = std::string(fields[f]->unit);
    frames[name.c_str()] = std::string(fields[f]->frame);
  }
  for (size_t f = 0; f < system.size(); ++f) {
    py::array_t<double> a = diagnostics[f].release();
    diag[std::string(system[f].name).c_str()] = system[f].width == 1 ? py::object(a.attr("reshape")(-1))
                                                                     : py::object(a);
  }
  out["fields"] = arrays;
  out["units"] = units;
  out["frames"] = frames;
  if (!rotor_names.empty()) {
    diag["rotor_speed"] = rotor_speed.release();
    diag["rotor_torque"] = rotor_torque.release();
  }
  out["diagnostics"] = diag;
  out["rotor_names"] = rotor_names;
  std::vector<std::string> names;
  for (const RigidBody& b : model.bodies) names.push_back(b.name());
  for (const Particle& p : model.particles) names.push_back(p.name);
  out["names"] = names;
  out["integrator"] = s.integrator;
  out["formulation"] = formulation_name(s.formulation);
  out["timestep"] = s.timestep;
  if (auto w = run.monitor().warning()) out["warning"] = *w;
  out["event_names"] = event_names;
  out["event_t"] = event_t;
  out["event_rows"] = event_rows;
  out["interrupted"] = interrupted;
  if (sensitivities) {
    out["stm"] = stm.release();
    out["parameter_sensitivity"] = parameter_sensitivity.release();
    out["sensitivity_parameters"] = *sensitivities;
    out["coupled"] = coupled;
    out["parameter_names"] = parameter_names;
  }
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A scene file read and validated: bodies, particles, forces, settings.")
      .def_property_readonly("path", [](const Scene& s) { return s.path; })
      .def_readonly("text", &Scene::text, "the scene file's TOML")
      .def_property_readonly(
          "bodies",
          [](const Scene& s) {
            std::vector<std::string> names;
            for (const RigidBody& b : s.model.bodies) names.push_back(b.name());
            return names;
          },
          "the bodies' names, in file order")
      .def_property_readonly(
          "particles",
          [](const Scene& s) {
            std::vector<std::string> names;
            for (const Particle& p : s.model.particles) names.push_back(p.name);
            return names;
          },
          "the particles' names")
      .def_property_readonly(
          "duration", [](const Scene& s) { return s.settings.duration; }, "s")
      .def_property_readonly(
          "timestep", [](const Scene& s) { return s.settings.timestep; }, "s")
      .def_property_readonly("integrator", [](const Scene& s) { return s.settings.integrator; })
      .def_readonly("warnings", &Scene::warnings)
      .def_readonly("output_fields", &Scene::output_fields,
                    "the scene's [output] fields (empty: the defaults)")
      .def_property_readonly(
          "events",
          [](const Scene& s) {
            std::vector<std::string> names;
            for (const EventSpec& e : s.events) names.push_back(e.name);
            return names;
          },
          "the names of the scene's [[events]]");
  m.def("load_scene", &load_scene, py::arg("path"),
        "Read and validate a scene file (TOML, docs/scene-format.md); ValueError 'file:line:column: ...' "
        "for anything wrong in it, OSError if it cannot be read.");
  m.def("parse_scene", &parse_scene, py::arg("text"), py::arg("path") = "scene.toml",
        "A scene from TOML text; `path` names it in messages and anchors relative mesh paths.");
  m.def("_simulate", &simulate, py::arg("scene"), py::arg("settings"), py::arg("fields"), py::arg("force"),
        py::arg("event_specs"), py::arg("python_events"), py::arg("every_body"), py::arg("sample_times"),
        py::arg("initial"), py::arg("sensitivities") = std::nullopt, py::arg("controller") = std::nullopt);
  m.def(
      "_run_settings",
      [] {
        py::list out;
        for (const RunSetting& s : run_settings()) {
          out.append(py::dict(py::arg("key") = std::string(s.key), py::arg("flag") = std::string(s.flag),
                              py::arg("unit") = std::string(s.unit), py::arg("help") = std::string(s.help),
                              py::arg("in_scene") = s.in_scene));
        }
        return out;
      },
      "The run settings (sim/run_settings.hpp): key, command-line flag, unit, help, whether a scene's "
      "[simulation] has it.");
  py::class_<EventSpec>(m, "EventSpec", "An event checked against a scene (tumble.Event makes them).")
      .def_readonly("name", &EventSpec::name)
      .def_readonly("row", &EventSpec::row, "the body or particle watched: its index in the trajectory");
  m.def("_parse_events", &parse_events, py::arg("scene"), py::arg("text"), py::arg("path") = "events.toml");
  m.def(
      "_field_table",
      [] {
        py::list bodies, system;
        auto describe = [](const auto& f) {
          py::dict d;
          d["name"] = std::string(f.name);
          d["width"] = f.width;
          std::vector<std::string> columns;
          for (int k = 0; k < f.width; ++k) columns.emplace_back(f.columns[static_cast<size_t>(k)]);
          d["columns"] = columns;
          d["unit"] = std::string(f.unit);
          d["frame"] = std::string(f.frame);
          d["meaning"] = std::string(f.meaning);
          return d;
        };
        for (const BodyField& f : body_fields()) bodies.append(describe(f));
        for (const SystemField& f : system_fields()) system.append(describe(f));
        return py::make_tuple(bodies, system);
      },
      "the output-field table (sim/output_fields.hpp): per-body fields and diagnostics, each with its name, "
      "width, CSV columns, unit, frame and meaning");
  m.def(
      "output_fields",
      [] {
        std::vector<std::string> names;
        for (const BodyField& f : body_fields()) names.emplace_back(f.name);
        return names;
      },
      "the names of every per-body output field (docs/scene-format.md)");
}

}  // namespace tumble::python
