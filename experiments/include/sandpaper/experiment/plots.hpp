#pragma once
// The analysis' pictures as standalone SVG: the magnitude-estimation fit (Figure 19's axes, log
// mean estimate against log force or another percept's physical quantity, with the data points), dendrograms of the sorting task (6.3) and
// the two-interval psychometric function.
#include <string>
#include <vector>

#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/experiment/clustering.hpp"
#include "sandpaper/experiment/psychometric.hpp"

namespace sandpaper::experiment {

struct EstimatePoint {
  double x = 0;         // the fit's predictor, in its SI unit (force N for roughness)
  double estimate = 0;  // normalised estimate of one trial
};

std::string magnitude_plot_svg(const calibration::MagnitudeEstimationFit& fit, const std::vector<EstimatePoint>& trials,
                               const std::string& title);
// `labels[i]` names leaf i; heights on the vertical axis as given (distance units).
std::string dendrogram_svg(const std::vector<std::string>& labels, const std::vector<Merge>& merges,
                           const std::string& title, const std::string& height_label);
struct ProportionPoint {
  double increment = 0;
  double proportion = 0;
  int trials = 0;
};
std::string psychometric_svg(const PsychometricFit& fit, const std::vector<ProportionPoint>& points, const std::string& title);

}  // namespace sandpaper::experiment
