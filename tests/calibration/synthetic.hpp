#pragma once
// Synthetic measurements for the fitting tools' tests and the shipped examples: magnitude estimates
// drawn from Minsky 1995's published law (Figure 19: log R = 0.76 log F - 0.51, F in program units)
// on Table 6's 30 force amplitudes, and force-gauge readings of a joystick. SYNTHETIC, never measured.
// Deterministic for a seed on every platform (own normal deviates: std distributions are not).
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit.hpp"

namespace sandpaper::calibration::synthetic {

// mt19937_64 with uniform and standard normal deviates defined bit for bit (Box-Muller).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform();  // [0, 1)
  double normal();   // N(0, 1)

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

// 1 program unit = 4 joystick units x 0.490909 gf (Table 6; calibration/devices/sandpaper-1995.toml), N.
inline constexpr double kNewtonsPerProgramUnit = 4 * 0.490909 * 9.80665e-3;

struct Stimulus {
  std::string name;        // a<level>p<period in 0.1 mm>, Table 8's naming (level = 10 pu = 40 ju; may be 8.5)
  int program_units = 0;   // Table 6 command amplitude
  double force_N = 0;
  double period_mm = 0;
};
// Table 6's 30 amplitudes (docs: /work/shared/reference/sandpaper-numbers.md), each given one of the
// 9 version-2 periods in turn (the OCR loses which period went with which amplitude).
std::vector<Stimulus> table6_stimuli();

struct ExperimentOptions {
  std::uint64_t seed = 1995;
  int subjects = 15, runs = 4;    // Ch. 5: 15 subjects, a practice run and three more
  double slope = 0.76;            // population exponent (Figure 19)
  double intercept_pu = -0.51;    // Figure 19's constant, F in program units
  double modulus_decades = 1.5;   // each subject's free modulus: log10 uniform over this span
  double exponent_sd = 0.08;      // each subject's exponent: slope + N(0, sd)
  double stimulus_sd = 0.045;     // each stimulus' own deviation from the law, log10 (shared by all)
  double trial_sd = 0.15;         // each estimate's multiplicative noise, log10 (a factor of 1.41)
  double period_slope = 0.0;      // log10 R += period_slope * log10(period / 1 mm); the thesis found 0
  double missing = 0.0;           // probability that a trial has no answer (empty response)
  int significant_digits = 3;     // estimates are said as short numbers
};

struct Experiment {
  MagnitudeEstimationData data;
  std::vector<double> exponents;  // each subject's exponent
  double panel_slope = 0;         // mean of `exponents`: the slope these subjects' mean estimates follow
  double intercept_N = 0;         // the population law's constant with F in N
};

// Trials in presentation order: run by run, each subject, stimuli shuffled per run.
Experiment simulate_experiment(const ExperimentOptions& o);

// The trials as a CSV with the header subject,run,stimulus,force_N,period_mm,response after
// `comment` ('#' lines).
std::string experiment_csv(const MagnitudeEstimationData& d, const std::vector<int>& runs, const std::string& comment);
// Run numbers of simulate_experiment's trials, in order.
std::vector<int> experiment_runs(const ExperimentOptions& o);

struct GaugeOptions {
  std::uint64_t seed = 2024;
  double gain_x = 0.00026, gain_y = 0.00028;  // N per command unit
  double offset_N = 0.02;                     // gauge zero error
  double saturation = 0.02;                   // force falls short by this fraction at full command, quadratically
  double noise_N = 0.015;
  double resolution_N = 0.01;                 // gauge display
  int command_max = 32767, steps = 10, repeats = 2;  // commands rounded to whole units
};
DeviceReadings simulate_gauge(const GaugeOptions& o);
std::string readings_csv(const DeviceReadings& d, const std::string& comment);

}  // namespace sandpaper::calibration::synthetic
