#pragma once
// Pooling results folders and analysing them as the thesis did (docs/EXPERIMENTS.md, "Analysis"):
//   magnitude estimation: per-subject geometric-mean normalisation and the regression of log R on
//     log F (Figure 19) and on log F and log period (Figure 20): calibration/fit.hpp;
//   confidence: mean confidence per stimulus against force and period (Figures 13-15) and the 50 %
//     boundary re-estimated by regressing logit(mean confidence) on log force and log period;
//   sorting: the co-occurrence matrix (sorts in which two stimuli share a pile) and single- and
//     average-linkage clustering of it (6.3), with dendrograms;
//   two-interval: the psychometric fit and the Weber fraction with its interval (psychometric.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/experiment/results.hpp"

namespace sandpaper::experiment {

struct AnalyseOptions {
  bool allow_mixed_designs = false;   // pool results of designs with different checksums
  bool include_incomplete = false;    // pool runs that did not answer every trial (left out by default)
  std::filesystem::path pictures_dir; // where the SVG pictures go; empty: <dir>/analysis
};

struct Analysis {
  nlohmann::json report;              // what `analyse --json` prints
  std::string task;
  std::vector<Results> runs;          // the results folders pooled, in path order
  std::vector<std::filesystem::path> left_out;  // incomplete runs not pooled
  std::optional<calibration::MagnitudeEstimationFit> magnitude;  // magnitude estimation only
  std::vector<std::filesystem::path> pictures;                   // written
};

// Every results folder at or under `dir` (a folder holding results.jsonl), sorted by path.
std::vector<std::filesystem::path> find_results(const std::filesystem::path& dir);

// Reads, pools and analyses; writes the pictures. Runs that did not answer every trial are left out
// (reported in `runs` and `left_out`) unless options.include_incomplete. Throws DesignError for no
// results, no complete run, runs of different tasks, or of different designs (unless allowed),
// listing the folders of each; and
// calibration::FitError when the data cannot support the fit (say what is missing).
Analysis analyse(const std::filesystem::path& dir, const AnalyseOptions& options);

}  // namespace sandpaper::experiment
