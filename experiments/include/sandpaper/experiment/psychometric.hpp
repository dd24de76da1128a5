#pragma once
// The psychometric function of a two-interval forced choice on force (docs/EXPERIMENTS.md, "Two
// intervals"): each interval's log force is perceived with Gaussian noise of sd sigma, so
//   P(correct | increment d) = Phi( ln(1 + d) / (sigma sqrt 2) ),
// fitted by maximum likelihood (Boost.Math's Brent minimiser and normal distribution). The Weber
// fraction reported is the increment answered correctly 75 % of the time, the usual 2IFC JND;
// its 95 % interval comes from the likelihood-ratio test (profile likelihood, chi-square 1 df).
#include <vector>

namespace sandpaper::experiment {

struct IncrementCount {
  double increment = 0;  // fraction: 0.1 = the comparison 10 % stronger
  int trials = 0, correct = 0;
};

struct PsychometricFit {
  double sigma = 0;                   // perceptual noise, natural-log units per interval
  double weber_fraction = 0;          // increment at 75 % correct
  double weber_low = 0, weber_high = 0;  // 95 % likelihood-ratio interval (high may be +inf)
  double log_likelihood = 0;
  int trials = 0;
  // P(correct) the fit predicts at `increment`.
  double p_correct(double increment) const;
};

// Throws std::invalid_argument with no trials, or increments <= 0, or when every answer is
// correct or every answer is at chance level or below (no finite, positive sigma fits).
PsychometricFit fit_two_interval(const std::vector<IncrementCount>& data);

}  // namespace sandpaper::experiment
