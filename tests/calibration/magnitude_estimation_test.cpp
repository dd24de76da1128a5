// The magnitude-estimation fit on synthetic experiments drawn from Minsky 1995's published law
// (Figure 19: log R = 0.76 log F - 0.51) with Ch. 5's design: 15 subjects x 30 stimuli x 4 runs,
// free moduli over 1.5 decades, per-subject exponents, per-stimulus deviations, trial noise.
#include <cmath>

#include <gtest/gtest.h>

#include "sandpaper/calibration/fit.hpp"
#include "synthetic.hpp"

using namespace sandpaper::calibration;
using namespace sandpaper::calibration::synthetic;

namespace {

constexpr int kExperiments = 200;

}  // namespace

// One experiment (seed 1995, fixed before looking): the slope lies within the t(28) 99 % interval of
// the subjects' mean exponent, and of the population's 0.76 with the between-subject error added.
// "Within one standard error" is a statement about 68 % of experiments, which the calibration test
// below checks over 200; this seed happens to land 1.97 s.e. from its panel (a 1-in-20 draw).
TEST(MagnitudeEstimation, RecoversThePublishedSlope) {
  const auto e = simulate_experiment({});
  const auto f = fit_magnitude_estimation(e.data);
  EXPECT_EQ(f.stimuli.size(), 30u);
  EXPECT_EQ(f.subjects.size(), 15u);
  EXPECT_EQ(f.runs, 4);
  EXPECT_EQ(f.trials, 1800);
  EXPECT_EQ(f.force.df_residual, 28);
  const double t99 = 2.763;  // two-sided 99 % point of t(28)
  EXPECT_NEAR(t_two_sided_p(t99, 28), 0.01, 1e-4);
  EXPECT_LT(std::abs(f.slope() - e.panel_slope), t99 * f.slope_se())
      << "slope " << f.slope() << " s.e. " << f.slope_se() << " panel " << e.panel_slope;
  EXPECT_LT(std::abs(f.slope() - 0.76), t99 * std::hypot(f.slope_se(), f.between.slope_se));
  // Statistics as Figure 19 reports them, on the scale of the thesis' (s = 0.0519, R^2 = 0.966).
  const auto& r = f.force;
  EXPECT_GT(r.r_squared, 0.9);
  EXPECT_LT(r.r_squared_adjusted, r.r_squared);
  EXPECT_GT(r.s, 0.02);
  EXPECT_LT(r.s, 0.09);
  EXPECT_NEAR(r.f_ratio, std::pow(r.coefficient("log force").t, 2), 1e-6 * r.f_ratio);
  EXPECT_LT(r.f_p, 1e-10);
  EXPECT_NEAR(r.ss_regression + r.ss_residual, r.ss_total, 1e-12);
  // The intercept in N: the population's, shifted by the panel's mean log modulus (the grand
  // geometric mean sets the scale of normalised estimates), so only loosely.
  EXPECT_NEAR(f.intercept(), e.intercept_N, 0.5);
  // Every subject gets a slope; their mean equals the slope of the means for balanced data.
  EXPECT_EQ(f.between.subjects, 15);
  EXPECT_NEAR(f.between.slope_mean, f.slope(), 1e-9);
  ASSERT_TRUE(f.force_period.has_value());
  ASSERT_TRUE(f.force_period_origin.has_value());
  EXPECT_EQ(f.force_period->df_residual, 27);
  EXPECT_EQ(f.force_period_origin->df_residual, 28);  // the thesis' 30 - 2
}

// The standard error is honest: over 200 seeded experiments the slope falls within 1 s.e. of the
// subjects' mean exponent about as often as Student's t with 28 df says (P(|t| < 1) = 0.674), and
// within 2 s.e. at least 90 % of the time (t says 0.945). With 200 experiments the fraction's
// standard deviation is sqrt(0.674 x 0.326 / 200) = 0.033; the tolerance is 3 of those, 0.10.
TEST(MagnitudeEstimation, StandardErrorIsCalibrated) {
  int within1 = 0, within2 = 0;
  for (int k = 0; k < kExperiments; ++k) {
    ExperimentOptions o;
    o.seed = 1000 + static_cast<std::uint64_t>(k);
    const auto e = simulate_experiment(o);
    const auto f = fit_magnitude_estimation(e.data);
    const double z = std::abs(f.slope() - e.panel_slope) / f.slope_se();
    within1 += z < 1;
    within2 += z < 2;
  }
  const double expected1 = 1 - t_two_sided_p(1.0, 28);
  EXPECT_NEAR(expected1, 0.674, 0.001);
  EXPECT_NEAR(within1 / double(kExperiments), expected1, 0.10) << within1 << " of " << kExperiments;
  EXPECT_GE(within2 / double(kExperiments), 0.90) << within2 << " of " << kExperiments;
}

// What the regression s.e. is not: subjects' exponents differ (sd 0.08 here), and the mean of 15
// people's exponents misses the population's 0.76 by about 0.08 / sqrt(15) = 0.021, which the
// stimulus-level residuals cannot see. The between-subject s.e. (sd of the subjects' own slopes /
// sqrt(15)) covers 0.76 as a t with 14 df says (0.667) when stimuli do not deviate from the law;
// the regression s.e. alone covers it clearly less often. Both facts are in docs/CALIBRATION.md.
TEST(MagnitudeEstimation, BetweenSubjectErrorCoversThePopulationExponent) {
  int between1 = 0, regression1 = 0;
  for (int k = 0; k < kExperiments; ++k) {
    ExperimentOptions o;
    o.seed = 5000 + static_cast<std::uint64_t>(k);
    o.stimulus_sd = 0;
    o.exponent_sd = 0.15;
    const auto e = simulate_experiment(o);
    const auto f = fit_magnitude_estimation(e.data);
    between1 += std::abs(f.between.slope_mean - 0.76) < f.between.slope_se;
    regression1 += std::abs(f.slope() - 0.76) < f.slope_se();
  }
  EXPECT_NEAR(between1 / double(kExperiments), 1 - t_two_sided_p(1.0, 14), 0.10) << between1;
  EXPECT_LT(regression1 / double(kExperiments), 0.45) << regression1;
}

// Why normalise: with a free modulus, who answered a stimulus decides its raw mean. When trials go
// unanswered (25 % here, at random) raw geometric means mix the subjects' moduli (1.5 decades) into
// the stimulus means. Over 200 experiments the normalised fit has the smaller residual s in most of
// them and a clearly smaller slope error; with stimuli that follow the law exactly (no stimulus
// deviations to hide behind) the difference is stark. Thresholds sit well inside what was measured
// when this test was written (s smaller in 191 and 199 of 200; rms ratios 1.25 and 1.83).
TEST(MagnitudeEstimation, GeometricMeanNormalisationMatters) {
  for (const double stimulus_sd : {0.045, 0.0}) {
    double sq_norm = 0, sq_raw = 0;
    int s_smaller = 0;
    for (int k = 0; k < kExperiments; ++k) {
      ExperimentOptions o;
      o.seed = 9000 + static_cast<std::uint64_t>(k);
      o.missing = 0.25;
      o.stimulus_sd = stimulus_sd;
      const auto e = simulate_experiment(o);
      const auto norm = fit_magnitude_estimation(e.data, Normalisation::GeometricMean);
      const auto raw = fit_magnitude_estimation(e.data, Normalisation::None);
      s_smaller += norm.force.s < raw.force.s;
      sq_norm += std::pow(norm.slope() - e.panel_slope, 2);
      sq_raw += std::pow(raw.slope() - e.panel_slope, 2);
    }
    const double rms_norm = std::sqrt(sq_norm / kExperiments), rms_raw = std::sqrt(sq_raw / kExperiments);
    const bool exact_law = stimulus_sd == 0;
    EXPECT_GT(s_smaller, exact_law ? 190 : 160) << "stimulus sd " << stimulus_sd;
    EXPECT_GT(rms_raw / rms_norm, exact_law ? 1.5 : 1.1)
        << "stimulus sd " << stimulus_sd << ": rms slope error normalised " << rms_norm << ", raw " << rms_raw;
  }
}

// ... and with complete data the normalisation changes nothing at all: every subject rated every
// stimulus equally often, so the subjects' moduli cancel in the geometric mean per stimulus. A
// check on the algebra in docs/CALIBRATION.md.
TEST(MagnitudeEstimation, NormalisationIsExactForCompleteData) {
  const auto e = simulate_experiment({});
  const auto norm = fit_magnitude_estimation(e.data, Normalisation::GeometricMean);
  const auto raw = fit_magnitude_estimation(e.data, Normalisation::None);
  EXPECT_NEAR(norm.slope(), raw.slope(), 1e-12);
  EXPECT_NEAR(norm.intercept(), raw.intercept(), 1e-12);
  EXPECT_NEAR(norm.force.s, raw.force.s, 1e-12);
}

// Normalised estimates keep each subject's ratios and put every subject's geometric mean at the
// grand geometric mean: a subject answering twice as large numbers changes nothing after it.
TEST(MagnitudeEstimation, NormalisationRemovesAModulus) {
  auto e = simulate_experiment({});
  const auto before = fit_magnitude_estimation(e.data);
  for (auto& t : e.data.trials)
    if (t.subject == "S03" && t.response) *t.response *= 2;
  const auto after = fit_magnitude_estimation(e.data);
  EXPECT_NEAR(after.subjects[2].geometric_mean, 2 * before.subjects[2].geometric_mean, 1e-9 * after.subjects[2].geometric_mean);
  EXPECT_NEAR(after.slope(), before.slope(), 1e-12);
  EXPECT_NEAR(after.grand_geometric_mean, before.grand_geometric_mean * std::pow(2.0, 1.0 / 15), 1e-9);
  for (std::size_t i = 0; i < before.stimuli.size(); ++i)
    EXPECT_NEAR(after.stimuli[i].mean_response / before.stimuli[i].mean_response, std::pow(2.0, 1.0 / 15), 1e-9);
}

// Figure 20: with no period effect in the data, log period is significant at 5 % about 5 % of the
// time (false positives; binomial sd over 200 is 0.015, tolerance 0.05); with a planted effect of
// -0.2 per decade of period it is found every time.
TEST(MagnitudeEstimation, PeriodRegressionFindsWhatIsThere) {
  int false_positive = 0, found = 0;
  for (int k = 0; k < kExperiments; ++k) {
    ExperimentOptions o;
    o.seed = 20000 + static_cast<std::uint64_t>(k);
    const auto none = fit_magnitude_estimation(simulate_experiment(o).data);
    false_positive += none.force_period->coefficient("log period").p < 0.05;
    o.period_slope = -0.2;
    const auto planted = fit_magnitude_estimation(simulate_experiment(o).data);
    const auto& c = planted.force_period->coefficient("log period");
    found += c.p < 0.05 && std::abs(c.value + 0.2) < 3 * c.se;
  }
  EXPECT_LT(false_positive / double(kExperiments), 0.10) << false_positive;
  EXPECT_GT(found / double(kExperiments), 0.95) << found;
}
