// The version-2 grating table: shape, sign and scale.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "sandpaper/compiler/textures.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {
float table_max(const std::vector<float>& v) {
  float m = 0;
  for (float x : v) m = std::max(m, std::abs(x));
  return m;
}
}  // namespace

TEST(Grating, MaximumForceIsTheTarget) {
  for (double period : {0.0007, 0.0025, 0.01})
    for (double hill : {0.2, 0.5, 0.8}) {
      auto g = compiler::make_grating(period, hill, 0, period * compiler::kSeedSigmaPerPeriod, 1.5);
      ASSERT_EQ(g.force_N.size(), static_cast<std::size_t>(compiler::kGratingSamples));
      EXPECT_NEAR(table_max(g.force_N), 1.5, 1e-6) << period << " " << hill;
    }
}

TEST(Grating, ForcePointsDownhillTowardTheValley) {
  // Hill centred on u = 0 spanning [-P/4, P/4] for hill 50%. At the rising edge u = -P/4
  // (table index 3N/4) the slope is up in +u, so the force is in -u; at the falling edge u = +P/4
  // (index N/4) the force is in +u. On the hill top and valley floor it is near zero.
  const int n = compiler::kGratingSamples;
  auto g = compiler::make_grating(0.004, 0.5, 0, 0.004 * compiler::kSeedSigmaPerPeriod, 2.0);
  EXPECT_NEAR(g.force_N[3 * n / 4], -2.0, 1e-3);
  EXPECT_NEAR(g.force_N[n / 4], 2.0, 1e-3);
  EXPECT_NEAR(g.force_N[0], 0.0, 1e-6);
  EXPECT_NEAR(g.force_N[n / 2], 0.0, 1e-6);
  // Odd symmetry about the hill's centre: F(-u) = -F(u).
  for (int i = 1; i < n; ++i) EXPECT_NEAR(g.force_N[i], -g.force_N[n - i], 1e-5) << i;
}

TEST(Grating, WallWidthFollowsTheSmoothing) {
  // Half-maximum width of a Gaussian pulse is 2.3548 sigma.
  const int n = compiler::kGratingSamples;
  double period = 0.01, sigma = period * 20 / n;
  auto g = compiler::make_grating(period, 0.5, 0, sigma, 1.0);
  int above = 0;
  for (int i = 0; i < n / 2; ++i) above += g.force_N[i] >= 0.5f;
  EXPECT_NEAR(above, 2.3548 * 20, 2.0);
}

TEST(Grating, TooSharpSmoothingIsRejected) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm smoothing 0 mm amplitude 1 N");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0304"});
}

TEST(Grating, OrientationAndPeriodReachTheProgram) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm orientation 30 deg amplitude 1 N");
  ASSERT_TRUE(r.ok());
  const auto& g = std::get<schema::GratingTerm>(r.program->terms.at(0));
  EXPECT_DOUBLE_EQ(g.period_m, 0.002);
  EXPECT_NEAR(g.orientation_rad, M_PI / 6, 1e-15);
}
