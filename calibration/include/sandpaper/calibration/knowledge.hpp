#pragma once
// Qualitative and psychophysical findings the compiler warns and explains with, read from
// calibration/knowledge/*.toml (docs/CALIBRATION.md). Force JND: Minsky 1995 5.4.2.
#include <string>
#include <vector>

namespace sandpaper::calibration {

// A published force just-noticeable difference: relative (a Weber fraction of the reference force,
// over a force range) or absolute (newtons).
struct ForceJnd {
  std::string id;                    // "tan1992"
  bool relative = true;
  double fraction_min = 0, fraction_max = 0;   // relative: e.g. 0.10-0.15 (Tan 1992)
  double absolute_N = 0;             // absolute: e.g. 0.5 N (Shimoga 1993)
  double force_min_N = 0, force_max_N = 0;     // reference forces it was measured over; 0 = not stated
  std::string effector;              // "grip force on the fingers"
  std::string citation, where;
};

// The force JNDs, and the Weber fraction the compiler counts JND steps with.
struct ForceJndData {
  std::string file;                  // "calibration/knowledge/force-jnd.toml"
  std::vector<ForceJnd> jnds;
  double weber_fraction = 0;         // the fraction used: one JND at force F is weber_fraction * F
  std::string weber_rationale;
  // One JND at `force_N` (N).
  double jnd_at(double force_N) const { return weber_fraction * force_N; }
  // JND steps between two positive forces: ln(F2 / F1) / ln(1 + weber_fraction), signed.
  double steps_between(double f1_N, double f2_N) const;
};

struct Knowledge {
  ForceJndData force_jnd;
};

}  // namespace sandpaper::calibration
