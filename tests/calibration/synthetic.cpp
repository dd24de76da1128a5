#include "synthetic.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace sandpaper::calibration::synthetic {

double Random::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double Random::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u1 = 0;
  while (u1 == 0) u1 = uniform();
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1)), a = 2.0 * 3.14159265358979323846 * u2;
  spare_ = r * std::sin(a);
  has_spare_ = true;
  return r * std::cos(a);
}

std::vector<Stimulus> table6_stimuli() {
  static const int amplitudes[30] = {85, 17, 41, 97, 9,  159, 16,  21, 42, 52,  172, 36, 90,  42, 105,
                                     44, 109, 21, 20, 50, 26, 51, 71, 64, 14, 120, 24, 137, 35, 194};
  static const double periods[9] = {0.7, 0.9, 1.2, 1.8, 2.5, 3.7, 5.0, 7.5, 10.0};
  std::vector<Stimulus> out;
  for (int i = 0; i < 30; ++i) {
    Stimulus s;
    s.program_units = amplitudes[i];
    s.period_mm = periods[i % 9];
    s.force_N = s.program_units * kNewtonsPerProgramUnit;
    // Table 8's naming, which the stimulus generator reads: force level = 40 joystick units = 10 pu,
    // so Table 6's 85 pu at 1.8 mm is a8.5p18 (one decimal is exact: every amplitude is whole pu).
    s.name = fmt::format("a{:g}p{}", s.program_units / 10.0, static_cast<int>(std::lround(s.period_mm * 10)));
    out.push_back(s);
  }
  return out;
}

namespace {

double round_significant(double v, int digits) {
  if (!(v > 0)) return v;
  const double e = std::floor(std::log10(v)) - (digits - 1);
  const double scale = std::pow(10.0, e);
  return std::round(v / scale) * scale;
}

}  // namespace

std::vector<int> experiment_runs(const ExperimentOptions& o) {
  std::vector<int> runs;
  const auto n = table6_stimuli().size();
  for (int run = 1; run <= o.runs; ++run)
    for (int j = 0; j < o.subjects; ++j)
      for (std::size_t i = 0; i < n; ++i) runs.push_back(run);
  return runs;
}

Experiment simulate_experiment(const ExperimentOptions& o) {
  Random rng(o.seed);
  const auto stimuli = table6_stimuli();
  Experiment e;
  e.data.path = fmt::format("synthetic(seed {})", o.seed);
  e.intercept_N = o.intercept_pu - o.slope * std::log10(kNewtonsPerProgramUnit);
  std::vector<double> log_modulus(static_cast<std::size_t>(o.subjects));
  for (int j = 0; j < o.subjects; ++j) {
    log_modulus[static_cast<std::size_t>(j)] = (rng.uniform() - 0.5) * o.modulus_decades;
    e.exponents.push_back(o.slope + o.exponent_sd * rng.normal());
  }
  double sum = 0;
  for (double b : e.exponents) sum += b;
  e.panel_slope = sum / static_cast<double>(e.exponents.size());
  std::vector<double> stim_dev;
  for (std::size_t i = 0; i < stimuli.size(); ++i) stim_dev.push_back(o.stimulus_sd * rng.normal());

  for (int run = 1; run <= o.runs; ++run)
    for (int j = 0; j < o.subjects; ++j) {
      std::vector<std::size_t> order(stimuli.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      for (std::size_t i = order.size(); i > 1; --i)  // Fisher-Yates with our own deviates
        std::swap(order[i - 1], order[static_cast<std::size_t>(rng.uniform() * static_cast<double>(i))]);
      for (std::size_t i : order) {
        const auto& s = stimuli[i];
        const auto ju = static_cast<std::size_t>(j);
        const double log_r = log_modulus[ju] + o.intercept_pu + e.exponents[ju] * std::log10(s.program_units) +
                             o.period_slope * std::log10(s.period_mm) + stim_dev[i] + o.trial_sd * rng.normal();
        Trial t;
        t.subject = fmt::format("S{:02d}", j + 1);
        t.stimulus = s.name;
        t.x = s.force_N;
        t.period_m = s.period_mm * 1e-3;
        const bool answered = rng.uniform() >= o.missing;
        if (answered) t.response = round_significant(std::pow(10.0, log_r), o.significant_digits);
        e.data.trials.push_back(t);
      }
    }
  return e;
}

std::string experiment_csv(const MagnitudeEstimationData& d, const std::vector<int>& runs, const std::string& comment) {
  std::string out = comment + "subject,run,stimulus,force_N,period_mm,response\n";
  for (std::size_t k = 0; k < d.trials.size(); ++k) {
    const auto& t = d.trials[k];
    out += fmt::format("{},{},{},{:.6g},{:g},{}\n", t.subject, k < runs.size() ? runs[k] : 0, t.stimulus, t.x,
                       t.period_m * 1e3, t.response ? fmt::format("{:g}", *t.response) : std::string());
  }
  return out;
}

DeviceReadings simulate_gauge(const GaugeOptions& o) {
  Random rng(o.seed);
  DeviceReadings d;
  d.path = fmt::format("synthetic-gauge(seed {})", o.seed);
  d.has_axis = true;
  for (char axis : {'x', 'y'})
    for (int rep = 0; rep < o.repeats; ++rep)
      for (int k = 0; k <= o.steps; ++k) {
        const double c = std::round(static_cast<double>(o.command_max) * k / o.steps);
        const double u = c / o.command_max;
        const double gain = axis == 'x' ? o.gain_x : o.gain_y;
        double f = gain * c * (1 - o.saturation * u * u) + o.offset_N + o.noise_N * rng.normal();
        f = std::round(f / o.resolution_N) * o.resolution_N;
        if (f == 0) f = 0;  // no "-0.00" in the file
        d.readings.push_back({c, f, axis, 0});
      }
  return d;
}

std::string readings_csv(const DeviceReadings& d, const std::string& comment) {
  std::string out = comment + "axis,command,force_N\n";
  for (const auto& r : d.readings) out += fmt::format("{},{:g},{:.2f}\n", r.axis, r.command, r.force_N);
  return out;
}

}  // namespace sandpaper::calibration::synthetic
