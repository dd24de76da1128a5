#pragma once
// A magnitude-estimation fit as JSON: the object `sandpaper calibrate fit --json` prints and the
// `magnitude_estimation` member of `sandpaper experiment analyse --json` (docs/CALIBRATION.md,
// docs/EXPERIMENTS.md). Keys: slope, slope_se, intercept, intercept_se, r2, r2_adj, s, df, f (the
// statistics of Minsky 1995 Figure 19), the period regression (Figure 20), per-stimulus means and
// per-subject summaries. Non-finite statistics are null.
#include <nlohmann/json.hpp>

#include "sandpaper/calibration/fit.hpp"

namespace sandpaper::calibration {

inline constexpr double kSignificanceLevel = 0.05;  // for "log period adds anything"

nlohmann::json regression_json(const RegressionResult& r);
nlohmann::json fit_json(const MagnitudeEstimationFit& fit);
// "log period adds nothing significant once force is known (p = 0.33 >= 0.05)" or its opposite.
std::string period_verdict(const Coefficient& log_period);
// "< 0.0001" or "0.3312"
std::string p_value_text(double p);

}  // namespace sandpaper::calibration
