#pragma once
// Qualitative and psychophysical findings the compiler warns and explains with, read from
// calibration/knowledge/*.toml (docs/CALIBRATION.md, "Knowledge"). Force JND: Minsky 1995 5.4.2;
// texture believability: Ch. 4; roughness groups: 6.3.6-6.3.7.
#include <limits>
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

// --- Texture believability (Minsky 1995 Ch. 4, calibration/knowledge/believability.toml) ---

// A region of low mean confidence that a texture feels like a textured surface: textures of one of
// `textures` with maximum lateral force below `force_below_N` and spatial period (feature size)
// above `period_bound_m` (at or above it when `period_inclusive`).
struct LowConfidenceRegion {
  std::string id;                      // "gratings-and-grids"
  std::vector<std::string> textures;   // "grating", "grid", "perlin"
  bool reading = false;                // a bound the thesis does not state (see `reading_note`)
  std::string reading_note;
  double force_below_N = 0;            // low when F < this (strictly)
  double period_bound_m = 0;
  bool period_inclusive = false;       // period >= bound (true) or > bound (false)
  std::string where, text;             // where in the thesis, and its own words
  bool applies_to(const std::string& texture) const;
  // Whether (F, period) lies in the region. A value within 1e-9 (relative) of a bound counts as
  // on it, so 120 ju and 30 pu, the same force written two ways, meet the force bound exactly.
  bool contains(double force_N, double period_m) const;
};

// A non-textural stimulus of Ch. 4 (4.3) and its mean confidence (Table 4).
struct NonTexturalConfidence {
  std::string name;       // "Slick"
  std::string law;        // the force law it compiles to ("AntiViscous"); empty for stimulus matches
  std::string stimulus;   // the thesis name a material must come from ("Noise35"); empty for law matches
  double mean = 0, sd = 0;  // fractions (0.11 = 11 %), over subjects and runs
  std::string where;
};

struct BelievabilityData {
  std::string file;                    // "calibration/knowledge/believability.toml"
  int subjects = 0, stimuli = 0, runs = 0;
  double high_confidence = 0;          // fraction: mean confidence at or above it is "high"
  std::string question, device;
  std::vector<LowConfidenceRegion> low_confidence;
  std::vector<NonTexturalConfidence> non_textural;
  std::string citation, where;
  // The low-confidence region for textures of `texture` ("grating", "grid", "perlin"); nullptr if none.
  const LowConfidenceRegion* region_for(const std::string& texture) const;
  const NonTexturalConfidence* find_law(const std::string& law) const;
  const NonTexturalConfidence* find_stimulus(const std::string& name) const;
};

// --- Perceptual groupings (Minsky 1995 6.3.6-6.3.7, calibration/knowledge/roughness-groups.toml) ---

// One rectangle in (maximum lateral force, spatial period), SI. Lower edges inclusive, upper edges
// exclusive; edges are the geometric midpoints between measured values, or 0 / infinity outside
// the measured ones.
struct GroupRegion {
  double force_min_N = 0, force_max_N = std::numeric_limits<double>::infinity();
  double period_min_m = 0, period_max_m = std::numeric_limits<double>::infinity();
  std::vector<std::string> stimuli;    // the measured stimuli inside; empty: no measurement here
  std::string goes_with;               // id of a group its stimuli sort with (6.3.6's 2.5 mm), or empty
  std::string sometimes;               // id of a group its stimuli are sometimes sorted into, or empty
  std::string note;
  bool measured() const { return !stimuli.empty(); }
  bool contains(double force_N, double period_m) const {
    return force_N >= force_min_N && force_N < force_max_N && period_m >= period_min_m && period_m < period_max_m;
  }
};

struct Group {
  std::string id, name, description;  // "moguls", "moguls", "large-period features with ..."
  std::vector<GroupRegion> regions;
};

// One way of grouping the measured stimuli ("period-class", "character"). Its regions tile the plane.
struct Grouping {
  std::string id, title, where, text;
  std::vector<Group> groups;
  struct Hit {
    const Group* group = nullptr;
    const GroupRegion* region = nullptr;
  };
  // The group and region holding (F, period); both set for any positive F and period.
  Hit classify(double force_N, double period_m) const;
  const Group* find(const std::string& group_id) const;
};

struct MeasuredStimulus {
  std::string name;       // "a3p25"
  double force_N = 0, period_m = 0;
};

struct GroupsData {
  std::string file;                    // "calibration/knowledge/roughness-groups.toml"
  std::string percept, texture, device;
  std::vector<double> forces_N, periods_m;  // the measured levels and periods, ascending
  std::vector<MeasuredStimulus> stimuli;
  std::vector<Grouping> groupings;
  std::string citation, where;
  // Inside the measured rectangle (lowest to highest measured force and period, edges included).
  bool in_domain(double force_N, double period_m) const;
  // The measured stimulus nearest in log force and log period; nullptr if none.
  const MeasuredStimulus* nearest(double force_N, double period_m) const;
  const Grouping* find(const std::string& grouping_id) const;
};

struct Knowledge {
  ForceJndData force_jnd;
  BelievabilityData believability;
  GroupsData roughness_groups;
};

}  // namespace sandpaper::calibration
