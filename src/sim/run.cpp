#include "tumble/sim/run.hpp"

#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble {
namespace {

/// The model with its held inputs back at the start (ForceModel::restart_inputs), so that the drift
/// monitor's invariants at t = 0 are the start's even for a model that ran before.
const Model& restarted(const Model& model) {
  for (const auto& f : model.forces) f->restart_inputs();
  return model;
}

}  // namespace

Run::Run(const Model& model, SystemState initial, const RunSettings& settings, Conservation conserved)
    : model_(model),
      initial_(std::move(initial)),
      settings_((validate(settings), settings)),
      monitor_(restarted(model), initial_, conserved, settings.drift_threshold, settings) {}

Run& Run::watch(std::vector<Event> events) {
  events_.insert(events_.end(), std::make_move_iterator(events.begin()),
                 std::make_move_iterator(events.end()));
  return *this;
}

Run& Run::attach(RunObserver& observer) {
  observers_.push_back(&observer);
  return *this;
}

Run& Run::stop_when(std::function<bool()> asked) {
  stop_ = std::move(asked);
  return *this;
}

Run& Run::keep_run_points(RunPoint& point) {
  point_ = &point;
  return *this;
}

Run& Run::resume_from(const RunPoint& point) {
  resume_ = &point;
  return *this;
}

Run& Run::as_lanes(std::vector<Lane> lanes) {
  lanes_ = std::move(lanes);
  return *this;
}

Run& Run::carry_sensitivities(SensitivityParameters parameters) {
  sensitivities_ = parameters;
  return *this;
}

SystemState Run::run() {
  if (sensitivities_) {
    if (!events_.empty() || !lanes_.empty() || point_ || resume_) {
      throw InvalidArgument(fmt::format(
          "sensitivities are computed by their own loop, which {} yet: run without sensitivities for that, "
          "or remove the [[events]] from the scene",
          !events_.empty() || !lanes_.empty() ? "watches no events" : "keeps no checkpoints"));
    }
    SystemState end = simulate_sensitivities(model_, initial_, settings_, *sensitivities_,
                                             [this](const SystemState& state, const Sensitivities& s) {
                                               const DriftSample d = monitor_.observe(state);
                                               for (RunObserver* o : observers_) {
                                                 o->on_sample(state, d);
                                                 o->on_sensitivities(s);
                                               }
                                               stopped_ = stopped_ || (stop_ && stop_());
                                               return !stopped_;
                                             });
    return end;
  }
  RunHooks hooks;
  hooks.events = events_;
  hooks.stats = &stats_;
  hooks.on_sample = [this](const SystemState& state) {
    const DriftSample d = monitor_.observe(state);
    for (RunObserver* o : observers_) o->on_sample(state, d);
    stopped_ = stopped_ || (stop_ && stop_());
    return !stopped_;  // stop at this sample: everything handed over so far stays valid
  };
  if (lanes_.empty()) {  // lanes report their own crossings
    hooks.on_event = [this](const EventHit& hit) {
      for (RunObserver* o : observers_) o->on_event(hit);
    };
  }
  if (stop_) {
    hooks.stop_requested = [this] {
      stopped_ = stopped_ || stop_();
      return stopped_;
    };
  }
  if (point_) {
    hooks.run_point = point_;
    hooks.on_run_point = [this](const RunPoint& p) {
      for (RunObserver* o : observers_) o->on_run_point(p);
    };
  }
  hooks.resume_from = resume_;
  hooks.lanes = std::move(lanes_);
  return simulate(model_, std::move(initial_), settings_, hooks);  // run() runs once: no copy of the start
}

}  // namespace tumble
