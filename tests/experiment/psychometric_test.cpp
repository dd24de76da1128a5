// The two-interval psychometric fit: it recovers sigma from counts made by the model itself, its
// interval contains the truth and narrows with more trials, and degenerate data are refused.
#include <gtest/gtest.h>

#include <cmath>

#include <boost/math/distributions/normal.hpp>

#include "sandpaper/experiment/psychometric.hpp"

namespace sandpaper::experiment {
namespace {

// Counts exactly as the model predicts for a Weber fraction (75 % point) `w`, n trials per increment.
std::vector<IncrementCount> ideal(double w, int n) {
  const boost::math::normal z;
  const double sigma = std::log1p(w) / (std::sqrt(2.0) * boost::math::quantile(z, 0.75));
  std::vector<IncrementCount> out;
  for (double inc : {0.025, 0.05, 0.1, 0.2, 0.4}) {
    const double p = boost::math::cdf(z, std::log1p(inc) / (sigma * std::sqrt(2.0)));
    out.push_back({inc, n, static_cast<int>(std::lround(p * n))});
  }
  return out;
}

TEST(Psychometric, RecoversTheWeberFraction) {
  const auto f = fit_two_interval(ideal(0.12, 10000));
  EXPECT_NEAR(f.weber_fraction, 0.12, 0.002);
  EXPECT_LT(f.weber_low, 0.12);
  EXPECT_GT(f.weber_high, 0.12);
  EXPECT_NEAR(f.p_correct(f.weber_fraction), 0.75, 1e-9);
  const auto few = fit_two_interval(ideal(0.12, 40));
  EXPECT_GT(few.weber_high - few.weber_low, f.weber_high - f.weber_low);
  EXPECT_LT(few.weber_low, 0.12);
  EXPECT_GT(few.weber_high, 0.12);
}

TEST(Psychometric, RefusesWhatCannotBeFitted) {
  EXPECT_THROW(fit_two_interval({}), std::invalid_argument);
  EXPECT_THROW(fit_two_interval({{0.1, 10, 10}, {0.2, 10, 10}}), std::invalid_argument);  // all correct
  EXPECT_THROW(fit_two_interval({{0.1, 10, 5}, {0.2, 10, 4}}), std::invalid_argument);    // chance
  EXPECT_THROW(fit_two_interval({{0.0, 10, 7}}), std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::experiment
