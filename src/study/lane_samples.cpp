#include "lane_samples.hpp"

#include <cmath>
#include <limits>
#include <type_traits>

#include "tumble/math/simd.hpp"
#include "tumble/sim/diagnostics.hpp"

namespace tumble {
namespace {

using Pack = xsimd::batch<double>;
constexpr size_t kWidth = Pack::size;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Rows row0 + w·stride (w = 0 … W − 1) of a column (T = Pack; for double, row0 itself).
template <class T>
T lanes_value(const double* column, size_t row0, size_t stride) {
  if constexpr (std::is_same_v<T, double>) {
    return column[row0];
  } else {
    if (stride == 1) return T::load_aligned(column + row0);
    alignas(64) double gathered[kWidth];
    for (size_t w = 0; w < kWidth; ++w) gathered[w] = column[row0 + w * stride];
    return T::load_aligned(gathered);
  }
}

/// Body j of the lanes l … l + W − 1 whose row is row0 + w·stride (T = Pack; for double, row0 itself).
template <class T>
Coordinates<T> lanes_body(const BodyColumns& x, size_t row0, size_t stride) {
  if constexpr (std::is_same_v<T, double>) {
    return x.load<double>(row0);
  } else {
    if (stride == 1) return x.load<T>(row0);  // consecutive rows: aligned, as row0 is a multiple of W
    alignas(64) double gathered[BodyColumns::kCount][kWidth];
    double* columns[BodyColumns::kCount];
    for (size_t k = 0; k < BodyColumns::kCount; ++k) {
      for (size_t w = 0; w < kWidth; ++w) gathered[k][w] = x[k][row0 + w * stride];
      columns[k] = gathered[k];
    }
    return BodyColumnsRef(columns, 0).load<T>(0);
  }
}

/// The larger of a running maximum and x; NaN (no value yet) gives way to any x.
double larger(double current, double x) { return std::isnan(current) || x > current ? x : current; }

}  // namespace

LaneSamples::LaneSamples(const EnsembleOutputs& outputs, Formulation F, size_t lanes, size_t bodies_per_lane,
                         size_t particles_per_lane)
    : o_(outputs), F_(F), lanes_(lanes), n_(bodies_per_lane), rows_(bodies_per_lane + particles_per_lane) {
  for (const std::string& c : o_.extrema) {
    const auto [field, k] = *find_column(c);
    columns_.emplace_back(*field, k);
    fields_.emplace_back(field, k);
    converted_ = converted_ || columns_.back().variable(F) < 0;
  }
  bodies_.resize(lanes * n_);
  monitors_.resize(lanes);
  constants_.resize(lanes, mass_of(n_));
  state_.resize(lanes, kState);
  lo_.resize(lanes, rows_ * columns_.size());
  hi_.resize(lanes, rows_ * columns_.size());
  for (size_t c = 0; c < lo_.count(); ++c) {
    std::fill(lo_[c], lo_[c] + lanes, kNaN);
    std::fill(hi_[c], hi_[c] + lanes, kNaN);
  }
  std::fill(state_[kEnergy], state_[kEnergy] + lanes, kNaN);
  std::fill(state_[kMomentum], state_[kMomentum] + lanes, kNaN);
}

void LaneSamples::add(size_t l, const Scene& s) {
  const Model& model = s.model;
  for (size_t j = 0; j < n_; ++j) bodies_[l * n_ + j] = &model.bodies[j];
  state_[kRunning][l] = 1.0;
  if (!o_.drift) return;
  const SystemCoordinates x0 = to_coordinates(F_, s.initial);
  // The runs of a batch have the same force models: all lanes are packed or none.
  packed_drifts_ = model.forces.empty() && model.particles.empty();
  if (!packed_drifts_) {
    SystemState scratch;
    monitors_[l].emplace(model, invariants(model, F_, x0, 0, scratch), s.conserved, 0.0, s.settings);
    return;
  }
  BodySums<double> sum;
  for (size_t j = 0; j < n_; ++j) {
    const RigidBody& b = model.bodies[j];
    constants_[mass_of(j)][l] = b.mass();
    for (size_t k = 0; k < 3; ++k)
      constants_[mass_of(j) + 1 + k][l] = b.Lambda()(static_cast<Eigen::Index>(k));
    add_body_sums<double>(b.mass(), b.Lambda(), x0.bodies.load(j), F_, sum);
  }
  // E₀ = T₀ (no potential), so DriftMonitor's scale max(|E₀|, T₀) is T₀.
  constants_[kE0][l] = sum.kinetic_energy;
  constants_[kScale][l] = sum.kinetic_energy;
  for (size_t k = 0; k < 3; ++k) constants_[kL0 + k][l] = sum.angular_momentum(static_cast<Eigen::Index>(k));
  constants_[kL0Norm][l] = std::sqrt(squared_norm<double>(sum.angular_momentum));
}

template <class T>
void LaneSamples::observe_packed(const BodyColumns& x, size_t l, size_t row0, size_t stride) {
  using std::isnan;
  const auto at = [&](const Columns& c, size_t k) { return Lanes<T>::load(c[k] + l); };
  const auto running = at(state_, kRunning) == T(1.0);
  // Extrema of the columns held as variables: min and max, NaN (no sample yet) giving way to any value.
  const size_t E = columns_.size();
  for (size_t j = 0; j < n_; ++j) {
    for (size_t k = 0; k < E; ++k) {
      const int c = columns_[k].variable(F_);
      if (c < 0) continue;
      const T v = lanes_value<T>(x[static_cast<size_t>(c)], row0 + j, stride);
      const T lo = at(lo_, j * E + k), hi = at(hi_, j * E + k);
      Lanes<T>::store(lo_[j * E + k] + l, select(running && (isnan(lo) || v < lo), v, lo));
      Lanes<T>::store(hi_[j * E + k] + l, select(running && (isnan(hi) || v > hi), v, hi));
    }
  }
  if (packed_drifts_) observe_drifts<T>(x, l, row0, stride, running);
}

template <class T, class Mask>
void LaneSamples::observe_drifts(const BodyColumns& x, size_t l, size_t row0, size_t stride,
                                 const Mask& running) {
  using std::abs, std::isnan, std::sqrt;
  const auto at = [&](const Columns& c, size_t k) { return Lanes<T>::load(c[k] + l); };
  BodySums<T> sum;
  for (size_t j = 0; j < n_; ++j) {
    const size_t m = mass_of(j);
    add_body_sums<T>(at(constants_, m),
                     Vec3T<T>(at(constants_, m + 1), at(constants_, m + 2), at(constants_, m + 3)),
                     lanes_body<T>(x, row0 + j, stride), F_, sum);
  }
  const T scale = at(constants_, kScale), L0_norm = at(constants_, kL0Norm);
  const Vec3T<T> L0(at(constants_, kL0), at(constants_, kL0 + 1), at(constants_, kL0 + 2));
  const T energy = abs((sum.kinetic_energy - at(constants_, kE0)) / scale);
  const T momentum = sqrt(squared_norm<T>(Vec3T<T>(sum.angular_momentum - L0))) / L0_norm;
  // The larger, where defined: a quantity that is zero at t = 0 has no relative drift.
  const auto keep = [&](size_t k, const T& drift, const auto& defined) {
    const T now = at(state_, k);
    Lanes<T>::store(state_[k] + l, select(running && defined && (isnan(now) || drift > now), drift, now));
  };
  keep(kEnergy, energy, scale > T(0.0));
  keep(kMomentum, momentum, L0_norm > T(0.0));
}

void LaneSamples::observe_extrema(size_t l, const SystemCoordinates& x, size_t first) {
  const size_t E = columns_.size();
  const auto take = [&](size_t at, double v) {
    double& lo = lo_[at][l];
    lo = std::isnan(lo) || v < lo ? v : lo;
    hi_[at][l] = larger(hi_[at][l], v);
  };
  for (size_t j = 0; j < n_; ++j) {
    for (size_t k = 0; k < E; ++k) {
      if (columns_[k].variable(F_) < 0)  // (the others are observe_packed's)
        take(j * E + k, columns_[k](*bodies_[l * n_ + j], x.bodies, first + j, F_));
    }
  }
  for (size_t p = 0; p < x.particles.size(); ++p) {  // a run alone may have particles
    for (size_t k = 0; k < E; ++k) {
      double v[4];
      fields_[k].first->of_particle(x.particles[p], v);
      take((n_ + p) * E + k, v[fields_[k].second]);
    }
  }
}

void LaneSamples::observe_unpacked(size_t l, const SystemCoordinates& x, size_t first) {
  if (monitors_[l]) {
    const DriftSample d = monitors_[l]->observe(x, first);
    if (d.energy_drift) state_[kEnergy][l] = larger(state_[kEnergy][l], std::abs(*d.energy_drift));
    if (d.angular_momentum_drift)
      state_[kMomentum][l] = larger(state_[kMomentum][l], std::abs(*d.angular_momentum_drift));
  }
  if (converted_ || rows_ > n_) observe_extrema(l, x, first);
}

void LaneSamples::observe(const SystemCoordinates& x) {
  size_t l = 0;
  for (; l + kWidth <= lanes_; l += kWidth) observe_packed<Pack>(x.bodies, l, l * n_, n_);
  for (; l < lanes_; ++l) observe_packed<double>(x.bodies, l, l * n_, n_);
  const bool monitored = o_.drift && !packed_drifts_;
  if (!monitored && !converted_ && rows_ == n_) return;  // nothing is taken lane by lane
  for (l = 0; l < lanes_; ++l) {
    if (state_[kRunning][l] == 1.0) observe_unpacked(l, x, l * n_);
  }
}

void LaneSamples::observe_last(size_t l, const SystemCoordinates& x, size_t first) {
  observe_packed<double>(x.bodies, l, first, 1);
  observe_unpacked(l, x, first);
  state_[kRunning][l] = 0.0;
}

void LaneSamples::append_extrema(size_t l, std::vector<double>& row) const {
  for (size_t c = 0; c < lo_.count(); ++c) {
    row.push_back(lo_[c][l]);
    row.push_back(hi_[c][l]);
  }
}

double LaneSamples::energy_drift_max(size_t l) const { return state_[kEnergy][l]; }
double LaneSamples::angular_momentum_drift_max(size_t l) const { return state_[kMomentum][l]; }

}  // namespace tumble
