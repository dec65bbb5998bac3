#include "gyrostat_split.hpp"

namespace tumble::gyrostat {

const Model& RotorSplit::kick_model(const Model& model) {
  rotors_ = rotors_of(model);
  if (!rotors_) return model;
  if (source_ != &model || source_bodies_ != model.bodies.data() || source_forces_ != model.forces) {
    source_ = &model;
    source_bodies_ = model.bodies.data();
    source_forces_ = model.forces;
    kick_model_ = model;
    kick_model_.forces.clear();
    for (const auto& f : model.forces)
      if (f.get() != rotors_) kick_model_.forces.push_back(f);
  }
  return kick_model_;
}

void RotorSplit::momenta(double t, double h) {
  const size_t n = source_->bodies.size();
  h_.ensure(n, 9);
  const double times[3] = {t, t + 0.5 * h, t + h};
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < n; ++i) {
      const Vec3 momentum = rotors_->momentum(i, times[k]).first;
      for (int j = 0; j < 3; ++j) h_[static_cast<size_t>(3 * k + j)][i] = momentum(j);
    }
  }
}

}  // namespace tumble::gyrostat
