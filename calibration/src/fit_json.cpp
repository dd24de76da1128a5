#include "sandpaper/calibration/fit_json.hpp"

#include <cmath>

#include <fmt/format.h>

namespace sandpaper::calibration {
namespace {

using nlohmann::json;

// JSON has no infinity: a non-finite statistic becomes null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json coefficient_json(const Coefficient& c) { return {{"value", c.value}, {"se", c.se}, {"t", num(c.t)}, {"p", num(c.p)}}; }

}  // namespace

std::string p_value_text(double p) { return p < 0.0001 ? "< 0.0001" : fmt::format("{:.4f}", p); }

std::string period_verdict(const Coefficient& c) {
  return c.p < kSignificanceLevel
             ? fmt::format("log period is significant (p = {}): roughness depends on period beyond force", p_value_text(c.p))
             : fmt::format("log period adds nothing significant once force is known (p = {} >= {:g})", p_value_text(c.p),
                           kSignificanceLevel);
}

json regression_json(const RegressionResult& r) {
  json coeffs = json::object();
  for (const auto& c : r.coefficients) coeffs[c.name] = coefficient_json(c);
  return {{"constant", r.has_constant}, {"coefficients", coeffs}, {"r2", r.r_squared}, {"r2_adj", r.r_squared_adjusted},
          {"s", r.s}, {"df", r.df_residual}, {"df_regression", r.df_regression}, {"f", num(r.f_ratio)},
          {"f_p", num(r.f_p)}, {"ss_regression", r.ss_regression}, {"ss_residual", r.ss_residual},
          {"ss_total", r.ss_total}, {"n", r.n}};
}

json fit_json(const MagnitudeEstimationFit& fit) {
  const auto& r = fit.force;
  const auto& slope = r.coefficient(fit.slope_name());
  const auto& constant = r.coefficient("constant");
  const auto& x = fit.predictor;
  json j = {{"law", "log10 mean estimate = intercept + slope * log10(" + x.name + " / 1 " + x.unit + ")"},
            {"predictor", x.name},
            {x.name == "force" ? "force_unit" : "predictor_unit", x.unit},
            {"slope", slope.value},
            {"slope_se", slope.se},
            {"slope_t", num(slope.t)},
            {"slope_p", num(slope.p)},
            {"intercept", constant.value},
            {"intercept_se", constant.se},
            {"intercept_t", num(constant.t)},
            {"intercept_p", num(constant.p)},
            {"r2", r.r_squared},
            {"r2_adj", r.r_squared_adjusted},
            {"s", r.s},
            {"df", r.df_residual},
            {"f", num(r.f_ratio)},
            {"f_p", num(r.f_p)},
            {"ss_regression", r.ss_regression},
            {"ss_residual", r.ss_residual},
            {"ss_total", r.ss_total},
            {"n_stimuli", fit.stimuli.size()},
            {"n_subjects", fit.subjects.size()},
            {"runs", fit.runs},
            {"trials", fit.trials},
            {"trials_answered", fit.answered},
            {"normalisation", fit.normalisation == Normalisation::GeometricMean ? "geometric-mean" : "none"},
            {"grand_geometric_mean", fit.grand_geometric_mean}};
  if (fit.force_period) {
    const auto& fp = *fit.force_period;
    const auto& c = fp.coefficient("log period");
    json p = {{"fitted", true},
              {"coefficient", c.value},
              {"se", c.se},
              {"t", num(c.t)},
              {"p", num(c.p)},
              {"significant", c.p < kSignificanceLevel},
              {"alpha", kSignificanceLevel},
              {"verdict", period_verdict(c)},
              {"unit", "mm"},
              {"regression", regression_json(fp)}};
    if (fit.force_period_origin) {
      p["through_origin"] = regression_json(*fit.force_period_origin);
      p["through_origin"]["note"] =
          "Figure 20's form, for comparison only: without a constant the coefficients depend on the units (N, mm)";
    }
    j["period"] = p;
  } else {
    j["period"] = {{"fitted", false}, {"reason", fit.period_note}};
  }
  j["between_subjects"] = {{"subjects", fit.between.subjects}, {"slope_mean", fit.between.slope_mean},
                           {"slope_sd", fit.between.slope_sd}, {"slope_se", fit.between.slope_se}};
  json stimuli = json::array();
  for (std::size_t i = 0; i < fit.stimuli.size(); ++i) {
    const auto& s = fit.stimuli[i];
    json e = {{"stimulus", s.stimulus}, {"estimates", s.estimates}, {"mean_response", s.mean_response},
              {"log_residual", r.residuals[i]}};
    if (x.name == "force") e["force_N"] = s.x;
    else e[x.name] = s.x;  // in predictor_unit
    if (s.period_m > 0) e["period_mm"] = s.period_m * 1e3;
    stimuli.push_back(std::move(e));
  }
  j["stimuli"] = stimuli;
  json subjects = json::array();
  for (const auto& s : fit.subjects)
    subjects.push_back({{"subject", s.subject}, {"trials", s.trials}, {"answered", s.answered},
                        {"geometric_mean", s.geometric_mean}, {"slope", s.slope ? json(*s.slope) : json(nullptr)}});
  j["subjects"] = subjects;
  return j;
}

}  // namespace sandpaper::calibration
