#pragma once
// Fitting a psychophysical map from magnitude-estimation data (Minsky 1995, 5.2-5.3): trials with a
// free modulus are normalised per subject by geometric means, averaged per stimulus, and the log
// mean estimate is regressed on log force (Figure 19) and on log force and log period (Figure 20).
// docs/CALIBRATION.md, "Fitting", gives the procedure and why.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/calibration/regression.hpp"

namespace sandpaper::calibration {

// One magnitude estimate: a CSV row `subject,stimulus,force_N,period_mm,response` (roughness), or
// a trial of an experiment on another percept, whose predictor is its stimulus's physical quantity.
struct Trial {
  std::string subject;
  std::string stimulus;
  double x = 0;             // the predictor's value, SI (> 0): maximum lateral force N for roughness
  double period_m = 0;      // spatial period of the stimulus, m (> 0); 0: none (not a texture)
  std::optional<double> response;  // the estimate (> 0); nullopt: an empty cell, the trial gave no answer
  int line = 0;             // 1-based CSV line, 0 for trials made in code
};

// The physical quantity a percept is regressed on: roughness on force (Minsky 1995 Figure 19),
// softness on stiffness, viscosity on damping, slipperiness on the friction coefficient
// (docs/CALIBRATION.md). `name` is the map's predictor name; `unit` the SI unit the fit's
// logarithms are taken in ("1": dimensionless).
struct FitPredictor {
  std::string name = "force";
  std::string unit = "N";
  std::string quantity = "maximum lateral force of the stimulus";
};

struct MagnitudeEstimationData {
  std::string path;         // the CSV, for diagnostics and the map's [source]
  FitPredictor predictor;
  std::vector<Trial> trials;
};

// Reads the CSV (csv.hpp's format; other columns ignored, any order). An empty or `NA` response is
// a trial without an answer; anything else must be a positive finite number. Throws FitError naming
// file:line for a missing column, a bad number, a non-positive force, period or response.
MagnitudeEstimationData read_magnitude_estimation_csv(const std::filesystem::path& path);
MagnitudeEstimationData parse_magnitude_estimation_csv(std::string_view text, const std::string& path);

enum class Normalisation {
  GeometricMean,  // each subject's estimates / that subject's geometric mean x the grand geometric mean
  None,           // raw estimates (for comparison only: free moduli then mix into the means)
};

struct StimulusMean {
  std::string stimulus;
  double x = 0, period_m = 0;   // the predictor's value (SI) and the period, m (0: none)
  int estimates = 0;            // answered trials averaged
  double mean_response = 0;     // geometric mean of the (normalised) estimates
};

struct SubjectSummary {
  std::string subject;
  int trials = 0;               // rows, answered or not
  int answered = 0;
  double geometric_mean = 0;    // of the subject's raw estimates: the subject's modulus
  std::optional<double> slope;  // the subject's own log-log slope (per-stimulus geometric means);
                                // nullopt when the subject's data cannot support one
};

// Per-subject slopes summarised across subjects (Minsky 1995, 5.3.3, Figure 21 fitted subjects one
// by one): the spread of exponents between people, which the regression on means cannot see.
struct BetweenSubjects {
  int subjects = 0;             // subjects with a slope
  double slope_mean = 0, slope_sd = 0;
  double slope_se = 0;          // slope_sd / sqrt(subjects); 0 with fewer than 2 subjects
};

struct MagnitudeEstimationFit {
  std::string path;
  FitPredictor predictor;
  Normalisation normalisation = Normalisation::GeometricMean;
  double grand_geometric_mean = 0;       // geometric mean of the subjects' geometric means
  std::vector<StimulusMean> stimuli;     // in order of first appearance
  std::vector<SubjectSummary> subjects;  // in order of first appearance
  int runs = 0;                          // the most trials any subject gave one stimulus
  int trials = 0, answered = 0;
  // Figure 19: log10 mean estimate = constant + slope * log10(x / 1 unit). Names "constant" and
  // "log <predictor>" ("log force").
  RegressionResult force;
  // Figure 20 with a constant: ... + c * log10(period / 1 mm). nullopt with `period_note` saying why
  // (one period, too few stimuli, period collinear with force).
  std::optional<RegressionResult> force_period;
  // Figure 20 as the thesis fitted it: through the origin (no constant); for comparison with it.
  std::optional<RegressionResult> force_period_origin;
  std::string period_note;
  BetweenSubjects between;

  std::string slope_name() const { return "log " + predictor.name; }
  double slope() const { return force.coefficient(slope_name()).value; }
  double slope_se() const { return force.coefficient(slope_name()).se; }
  double intercept() const { return force.coefficient("constant").value; }
};

// Fits the map. Throws FitError saying what is missing: fewer than 3 distinct stimuli, one force
// level, a stimulus given two forces or periods, a subject with no answered trial (or, normalised,
// answers to fewer than 2 stimuli), a stimulus no one answered, mean estimates exactly on a line
// (no residual to estimate errors from).
MagnitudeEstimationFit fit_magnitude_estimation(const MagnitudeEstimationData& data,
                                                Normalisation normalisation = Normalisation::GeometricMean);

struct MapFileOptions {
  std::string id;           // map id; empty: "fitted-<percept>"
  std::string percept = "roughness";
  std::string description;  // empty: "<percept> against maximum lateral force, fitted by sandpaper calibrate fit"
  // Non-empty: a device's own map (use = "device", [domain] device = this), which the compiler uses
  // only for that device (docs/EXPERIMENTS.md). Empty: the default compile map (use = "compile").
  std::string device;
  double reference_N = 0;   // ratio-scale reference, in the predictor's SI unit (a force N for roughness);
                            // 0: the most intense stimulus
  std::string provenance;   // "# " lines written first, and the [source] where; empty: calibrate fit's
  std::string citation;     // [source] citation; empty: "magnitude-estimation data in <csv>"
  // The predictor's [domain] range to write (SI), when wider than the stimuli: it then also writes
  // [domain] stimuli with the stimuli's range. Empty: the stimuli's range (rounded outward).
  std::vector<double> widen_domain_to;
  std::string apparatus;    // [domain] apparatus ("joystick"); empty: not written
  // [jnd]: the predictor's Weber fraction and its source; not written when 0.
  double weber_fraction = 0;
  std::string jnd_source;
};

// Options for a default roughness compile map with id `id` (what `calibrate fit -o` writes).
inline MapFileOptions compile_map_options(std::string id) {
  MapFileOptions o;
  o.id = std::move(id);
  return o;
}

// The map file (docs/CALIBRATION.md, schema/files/map.schema.json): the Figure 19 form with force in
// N, status "measured", use "compile", ratio-scale reference at the largest stimulus force, domain
// from the stimuli, source the CSV. Statistics the schema has no key for are written as comments.
// Throws FitError for a fit whose slope is 0, which no map can hold (the compiler inverts it).
std::string map_file_text(const MagnitudeEstimationFit& fit, const MapFileOptions& options);

// "%.6g" with a unit: "3.74612 N". Quantities in data files are strings with their unit.
std::string quantity_text(double value, const char* unit);

}  // namespace sandpaper::calibration
