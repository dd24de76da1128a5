#include "examples.hpp"

#include "synthetic.hpp"

namespace sandpaper::calibration::synthetic {

std::string roughness_responses_example() {
  ExperimentOptions o;  // the defaults: seed 1995, 15 subjects x 4 runs x 30 stimuli
  o.missing = 0.01;     // a few trials without an answer, as in any real session
  const auto e = simulate_experiment(o);
  const std::string comment =
      "# SYNTHETIC magnitude estimates, NOT MEASURED: made by tests/calibration/examples.cpp (seed 1995) to show\n"
      "# `sandpaper calibrate fit`. Drawn from Minsky 1995's published law, log R = 0.76 log F - 0.51 (Figure 19,\n"
      "# F in program units; 1 program unit = 4 x 0.490909 gf), on Table 6's 30 force amplitudes, each given one\n"
      "# of the 9 version-2 periods in turn; 15 subjects x 4 runs, each subject with a free modulus (log-uniform\n"
      "# over 1.5 decades) and an exponent 0.76 + N(0, 0.08); each stimulus deviates from the law by N(0, 0.045)\n"
      "# log10 units; each estimate by N(0, 0.15) log10 units; 1 % of trials unanswered (empty response);\n"
      "# estimates rounded to 3 significant digits. Regenerate: cmake --build <build> --target update-calibration-examples\n";
  return experiment_csv(e.data, experiment_runs(o), comment);
}

std::string openffboard_readings_example() {
  GaugeOptions o;  // the defaults
  const auto d = simulate_gauge(o);
  const std::string comment =
      "# SYNTHETIC force-gauge readings, NOT MEASURED: made by tests/calibration/examples.cpp (seed 2024) to show\n"
      "# `sandpaper calibrate device`. A 2-axis joystick commanded 0..32767 (HID PID constant-force magnitude) in\n"
      "# 10 steps of whole units, twice per axis; true gains 0.00026 N (x) and 0.00028 N (y) per command unit, a 0.02 N\n"
      "# gauge zero error, 2 % saturation at full command (quadratic), N(0, 0.015 N) noise, read to 0.01 N.\n"
      "# Regenerate: cmake --build <build> --target update-calibration-examples\n";
  return readings_csv(d, comment);
}

}  // namespace sandpaper::calibration::synthetic
