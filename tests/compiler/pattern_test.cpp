// Version-1 patterns (thesis 3.5.1), Perlin noise, 8-bit quantization and distinct force levels (3.6.1).
#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "sandpaper/compiler/force_levels.hpp"
#include "sandpaper/compiler/perlin.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

const schema::HeightFieldTerm& field_of(const compiler::CompileResult& r) {
  return std::get<schema::HeightFieldTerm>(r.program->terms.at(0));
}

compiler::CompileResult compile_ok(const std::string& text) {
  auto r = test::shipped_compiler().compile_text(text);
  EXPECT_TRUE(r.ok()) << text << "\n" << compiler::format_diagnostics(r.diagnostics);
  return r;
}

std::size_t distinct_nonzero_magnitudes(const std::vector<double>& d) {
  std::set<double> s;
  for (double x : d)
    if (x != 0) s.insert(std::abs(x));
  return s.size();
}

}  // namespace

TEST(Perlin, SameSeedSameLatticeDifferentSeedDifferent) {
  compiler::PerlinLattice a(9, 7, 2, 1), b(9, 7, 2, 1), c(9, 7, 2, 2);
  bool differs = false;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 9; ++i) {
        EXPECT_EQ(a.control(i, j, k), b.control(i, j, k));
        differs = differs || a.control(i, j, k) != c.control(i, j, k);
      }
  EXPECT_TRUE(differs);
  EXPECT_EQ(a.density(3.3, 2.7, 0.5), b.density(3.3, 2.7, 0.5));
}

TEST(Perlin, ControlValuesArePinnedByTheStandard) {
  // [rand.predef]: the 10000th output of a default-seeded (5489) std::mt19937_64 is
  // 9981545732273789042. Control values are those outputs in order, mapped by their top 53 bits.
  compiler::PerlinLattice lattice(100, 50, 2, 5489);
  const double expected = static_cast<double>(9981545732273789042ULL >> 11) / 9007199254740992.0;  // 2^53
  EXPECT_EQ(lattice.control(99, 49, 1), expected);
  EXPECT_EQ(compiler::unit_interval(0), 0.0);
  EXPECT_LT(compiler::unit_interval(~0ULL), 1.0);
}

TEST(Perlin, InterpolatesTheLatticeAndStaysInTheUnitInterval) {
  compiler::PerlinLattice lattice(6, 5, 3, 42);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) EXPECT_EQ(lattice.density(i, j, k), lattice.control(i, j, k)) << i << j << k;
  std::mt19937 pick(7);
  std::uniform_real_distribution<double> x(0, 5), y(0, 4), z(0, 2);
  for (int n = 0; n < 2000; ++n) {
    double d = lattice.density(x(pick), y(pick), z(pick));
    EXPECT_GE(d, 0.0);
    EXPECT_LE(d, 1.0);
  }
  // Perlin's blend is flat at the lattice points: halfway between two control values along x the
  // density is their mean, on an edge of the lattice.
  EXPECT_NEAR(lattice.density(2.5, 1, 0), 0.5 * (lattice.control(2, 1, 0) + lattice.control(3, 1, 0)), 1e-15);
  EXPECT_DOUBLE_EQ(compiler::perlin_blend(0.25), 0.25 * 0.25 * (3 - 0.5));
}

TEST(Pattern, PerlinFieldIsDeterministicPerSeed) {
  auto a = compile_ok("pattern perlin feature 3.7 mm seed 1 amplitude 1 N");
  auto b = compile_ok("pattern perlin feature 3.7 mm seed 1 amplitude 1 N");
  auto c = compile_ok("pattern perlin feature 3.7 mm seed 2 amplitude 1 N");
  EXPECT_EQ(field_of(a).force_x_N, field_of(b).force_x_N);
  EXPECT_EQ(field_of(a).force_y_N, field_of(b).force_y_N);
  EXPECT_NE(field_of(a).force_x_N, field_of(c).force_x_N);
  // It covers the patch at the pixel pitch: 95 mm / 0.37 mm = 257 px.
  EXPECT_EQ(field_of(a).nx, 257u);
  EXPECT_FALSE(field_of(a).repeat);
}

TEST(Pattern, BarsFollowTheLateralForceGradient) {
  // valley 15 px, hill 20 px, kernel 2 (sigma 2 px), 8-bit: F = -k d, k = target / max |d|.
  auto r = compile_ok("pattern bars valley 5.55 mm hill 7.4 mm kernel 2 amplitude 1.5 N; quantize 8 bit");
  const auto& f = field_of(r);
  auto d = test::bar_gradient_8bit(15, 20, 2);
  ASSERT_EQ(f.nx, d.size());
  ASSERT_EQ(f.ny, 1u);
  double peak = 0;
  for (double x : d) peak = std::max(peak, std::abs(x));
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_FLOAT_EQ(f.force_x_N[i], static_cast<float>(-1.5 / peak * d[i])) << i;
    EXPECT_EQ(f.force_y_N[i], 0.0f);
  }
}

TEST(Pattern, QuantizationLeavesAHandfulOfForceLevels) {
  // Thesis 3.6.1: 8-bit version-1 textures show only a few force levels. For bars the 0.37 mm
  // sampling of the narrow walls already limits them (float heights give about as few); 8-bit
  // heights cut them further once the walls span many pixels, and cut Perlin fields drastically.
  for (double kernel : {0.5, 1.0, 2.0, 6.0}) {
    std::string bars = "pattern bars valley 5.55 mm hill 7.4 mm kernel " + std::to_string(kernel) + " amplitude 1 N";
    auto q = compile_ok(bars + "; quantize 8 bit");
    auto f = compile_ok(bars);
    auto lq = compiler::count_force_levels(*q.program);
    auto lf = compiler::count_force_levels(*f.program);
    EXPECT_EQ(lq.magnitudes, distinct_nonzero_magnitudes(test::bar_gradient_8bit(15, 20, kernel))) << kernel;
    EXPECT_GE(lf.magnitudes, lq.magnitudes) << kernel;
    if (kernel <= 2) {
      EXPECT_LE(lq.magnitudes, 8u) << kernel;
    } else {
      EXPECT_GT(lf.magnitudes, lq.magnitudes) << kernel;
    }
    // Signed: each magnitude in both directions, plus zero.
    EXPECT_EQ(lq.signed_values, 2 * lq.magnitudes + 1) << kernel;
    EXPECT_EQ(lq.tables, 2u);
  }
  auto perlin_q = compile_ok("pattern perlin feature 3.7 mm amplitude 1 N; quantize 8 bit");
  auto perlin_f = compile_ok("pattern perlin feature 3.7 mm amplitude 1 N");
  EXPECT_LE(compiler::count_force_levels(*perlin_q.program).magnitudes, 255u);  // |h(i+1) - h(i-1)| <= 255, and hypot scaling
  EXPECT_GT(compiler::count_force_levels(*perlin_f.program).magnitudes, 10000u);
}

TEST(Pattern, QuantizedSeedGratingHasTheSeedsLevels) {
  // The version-2 seed the thesis' way: 256 px, hill 128, sigma 6 px (kernel 24), 8-bit.
  auto r = compile_ok("grating period 2.5 mm amplitude 1 N; quantize 8 bit");
  const auto& g = std::get<schema::GratingTerm>(r.program->terms.at(0));
  ASSERT_EQ(g.force_N.size(), 256u);
  // Independent: hill 128 px centred on sample 0, wrapped Gaussian of sigma 6 px, rounded.
  const int n = 256;
  std::vector<double> h(n), d(n);
  for (int i = 0; i < n; ++i) {
    double s = 0, sum = 0;
    for (int j = -18; j <= 18; ++j) {
      int q = ((i + j) % n + n) % n;
      bool hill = q < 64 || q >= 192;
      double w = std::exp(-j * j / 72.0);
      s += w * (hill ? 255 : 0);
      sum += w;
    }
    h[static_cast<std::size_t>(i)] = std::round(s / sum);
  }
  for (int i = 0; i < n; ++i) d[static_cast<std::size_t>(i)] = h[static_cast<std::size_t>((i + 1) % n)] - h[static_cast<std::size_t>((i + n - 1) % n)];
  EXPECT_EQ(compiler::count_force_levels(*r.program).magnitudes, distinct_nonzero_magnitudes(d));
  float peak = 0;
  for (float x : g.force_N) peak = std::max(peak, std::abs(x));
  EXPECT_FLOAT_EQ(peak, 1.0f);
  // Float (unquantized) gratings keep many levels.
  auto f = compile_ok("grating period 2.5 mm amplitude 1 N");
  EXPECT_GT(compiler::count_force_levels(*f.program).magnitudes, 100u);
}

TEST(Pattern, GridOffsetShiftsAlternateRows) {
  // gridB5W5off5: plateaus 5 x 5 px; the second row of plateaus is shifted 5 px along x.
  auto r = compile_ok("pattern grid valley 1.85 mm hill 1.85 mm offset 1.85 mm amplitude 1 N; quantize 8 bit");
  const auto& f = field_of(r);
  ASSERT_EQ(f.nx, 10u);
  ASSERT_EQ(f.ny, 20u);
  auto fx = [&](int x, int y) { return f.force_x_N[static_cast<std::size_t>(y) * f.nx + x]; };
  // Row 7 (first plateau row, plateau x 5-9): the rising wall at x = 4..5 pushes toward -x.
  EXPECT_LT(fx(4, 7), 0.0f);
  EXPECT_GT(fx(0, 7), 0.0f);  // wrapped falling wall at x = 9 | 0
  // Row 17 (second plateau row, plateau x 0-4): the walls swap.
  EXPECT_GT(fx(4, 17), 0.0f);
  EXPECT_LT(fx(0, 17), 0.0f);
}

TEST(Pattern, StripesAreWideHillsAcrossThePatch) {
  auto r = compile_ok("pattern stripes count 2 kernel 4 amplitude 1 N; size 94.72 mm");
  const auto& f = field_of(r);
  ASSERT_EQ(f.nx, 256u);
  // Along a row: rising wall (force -x), falling wall (+x), twice.
  std::vector<int> signs;
  for (std::uint32_t x = 0; x < f.nx; ++x) {
    float v = f.force_x_N[x];
    int s = v > 0 ? 1 : v < 0 ? -1 : 0;
    if (s != 0 && (signs.empty() || signs.back() != s)) signs.push_back(s);
  }
  EXPECT_EQ(signs, (std::vector<int>{-1, 1, -1, 1}));
  for (float v : f.force_y_N) EXPECT_EQ(v, 0.0f);
}

TEST(Pattern, NoiseJittersFromPixelToPixel) {
  auto a = compile_ok("pattern noise seed 3 amplitude 1 N; quantize 8 bit");
  auto b = compile_ok("pattern noise seed 3 amplitude 1 N; quantize 8 bit");
  EXPECT_EQ(field_of(a).force_x_N, field_of(b).force_x_N);
  auto levels = compiler::count_force_levels(*a.program);
  EXPECT_LE(levels.magnitudes, 255u);  // 8-bit differences: 1 .. 255
  EXPECT_GT(levels.magnitudes, 200u);
  // Cells of 2 px: neighbouring pixels in a cell share a height.
  auto c = compile_ok("pattern noise feature 0.74 mm seed 3 amplitude 1 N");
  EXPECT_EQ(test::provenance(*c.program, "texture.feature").value_si, 0.74e-3);
}

TEST(Pattern, LengthsRoundToWholePixels) {
  auto r = compile_ok("pattern bars valley 5 mm hill 7.4 mm amplitude 1 N");
  const auto& v = test::provenance(*r.program, "texture.valley");
  EXPECT_NEAR(v.value_si, 14 * 0.37e-3, 1e-12);  // 5 / 0.37 = 13.5 -> 14 px
  EXPECT_NE(v.stated.find("rounded to 14 px"), std::string::npos) << v.stated;
  auto p = compile_ok("pattern bars valley 1 mm hill 1 mm pixel 0.5 mm amplitude 1 N");
  EXPECT_EQ(field_of(p).nx, 4u);
  EXPECT_DOUBLE_EQ(field_of(p).spacing_m[0], 0.5e-3);
}

TEST(Pattern, StatementErrors) {
  const auto& c = test::shipped_compiler();
  auto codes = [&](const std::string& text) { return test::codes(c.compile_text(text)); };
  using V = std::vector<std::string>;
  EXPECT_EQ(codes("pattern bars valley 5.55 mm amplitude 1 N"), V{"E0219"});          // needs hill
  EXPECT_EQ(codes("pattern waves valley 5.55 mm"), V{"E0217"});                       // unknown kind
  EXPECT_EQ(codes("pattern perlin feature 1 mm offset 1 mm"), V{"E0209"});            // option of another kind
  EXPECT_EQ(codes("pattern bars valley 1 mm hill 1 mm kernel 2 mm"), V{"E0205"});     // kernel is in pixels
  EXPECT_EQ(codes("pattern bars valley 1 mm hill 1 mm kernel 2 kernel 3"), V{"E0206"});
  EXPECT_EQ(codes("pattern bars valley 0.1 mm hill 1 mm amplitude 1 N"), V{"E0304"}); // under one pixel
  EXPECT_EQ(codes("pattern bars valley 1 mm hill 1 mm kernel -1 amplitude 1 N"), V{"E0304"});
  EXPECT_EQ(codes("pattern perlin feature 1 mm seed 1.5 amplitude 1 N"), V{"E0304"});
  EXPECT_EQ(codes("pattern stripes count 0 amplitude 1 N"), V{"E0304"});
  EXPECT_EQ(codes("pattern perlin feature 1 mm pixel 0.01 mm amplitude 1 N"), V{"E0304"});  // 9500 px a side
  EXPECT_EQ(codes("pattern bars valley 1 mm hill 1 mm"), V{"E0308"});                 // no force
  EXPECT_EQ(codes("pattern bars valley 1 mm hill 1 mm amplitude 1 N; grating period 2 mm"), V{"E0302"});
  EXPECT_EQ(codes("quantize 8; grating period 2 mm amplitude 1 N"), V{"E0216"});
  EXPECT_EQ(codes("quantize 0 bit; grating period 2 mm amplitude 1 N"), V{"E0304"});
  EXPECT_EQ(codes("quantize 8.5 bit; grating period 2 mm amplitude 1 N"), V{"E0304"});
  EXPECT_EQ(codes("quantize 8 bit; quantize 4 bit; grating period 2 mm amplitude 1 N"), V{"E0302"});
  EXPECT_EQ(codes("like gravel; quantize 8 bit"), V{"E0304"});  // an image is quantized already
  // Noise cells larger than the patch: one height everywhere, no slope, no force.
  EXPECT_EQ(codes("pattern noise feature 200 mm amplitude 1 N"), V{"E0304"});
}

TEST(Pattern, QuantizeIsInheritedAndRecorded) {
  auto r = compile_ok("like barsB15W15_2; roughness 0.3");
  EXPECT_EQ(test::provenance(*r.program, "texture.quantization").layer, "representative");
  EXPECT_NEAR(r.program->max_lateral_force_N, test::expected_force_for_roughness(0.3), 1e-9);
  // The inherited pattern, re-scaled: its levels are the same, only the gain changes.
  auto base = compile_ok("barsB15W15_2");
  EXPECT_EQ(compiler::count_force_levels(*r.program).magnitudes, compiler::count_force_levels(*base.program).magnitudes);
}
