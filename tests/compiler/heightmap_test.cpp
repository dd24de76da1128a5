// Images as height fields: gradient direction and scale, pixel formats, and unusable images.
#include <cmath>
#include <fstream>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace sandpaper;

namespace {

// Writes a one-channel image whose value at (x, y) (row y from the top) is f(x, y).
template <class F>
void write_image(const std::string& path, int w, int h, OIIO::TypeDesc type, F f, int channels = 1) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(w, h, channels, type);
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  std::vector<float> px(static_cast<std::size_t>(w) * h * channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) px[(static_cast<std::size_t>(y) * w + x) * channels + c] = f(static_cast<float>(x), static_cast<float>(y), c);
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
  out->close();
}

const schema::HeightFieldTerm& field_of(const compiler::CompileResult& r) {
  return std::get<schema::HeightFieldTerm>(r.program->terms.at(0));
}

}  // namespace

TEST(Heightmap, RampInXGivesConstantForceDownhill) {
  auto dir = test::temp_dir("ramp");
  // Height rises with x: the force must point to -x, everywhere the same, at the target.
  write_image(dir + "/ramp.tif", 40, 30, OIIO::TypeDesc::FLOAT, [](float x, float, int) { return 0.01f * x; });
  auto r = test::shipped_compiler().compile_text("heightmap \"" + dir + "/ramp.tif\" size 40 mm x 30 mm amplitude 2 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& f = field_of(r);
  EXPECT_EQ(f.nx, 40u);
  EXPECT_EQ(f.ny, 30u);
  EXPECT_DOUBLE_EQ(f.spacing_m[0], 0.001);
  EXPECT_DOUBLE_EQ(f.origin_m[0], -0.0195);
  for (std::size_t i = 0; i < f.force_x_N.size(); ++i) {
    EXPECT_NEAR(f.force_x_N[i], -2.0, 1e-4) << i;
    EXPECT_NEAR(f.force_y_N[i], 0.0, 1e-6) << i;
  }
  EXPECT_DOUBLE_EQ(r.program->size_m[0], 0.040);  // the image sets the patch size
  EXPECT_DOUBLE_EQ(r.program->size_m[1], 0.030);
}

TEST(Heightmap, ImageTopIsPositiveY) {
  auto dir = test::temp_dir("ramp16");
  // 16-bit PNG, brighter toward the bottom row: height falls with +y, so downhill is +y.
  write_image(dir + "/ramp.png", 32, 32, OIIO::TypeDesc::UINT16, [](float, float y, int) { return y / 31.0f; });
  auto r = test::shipped_compiler().compile_text("heightmap \"" + dir + "/ramp.png\" size 32 mm amplitude 1 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& f = field_of(r);
  std::size_t centre = 16 * 32 + 16;
  EXPECT_NEAR(f.force_y_N[centre], 1.0, 1e-3);
  EXPECT_NEAR(f.force_x_N[centre], 0.0, 1e-6);
}

TEST(Heightmap, ColourUsesLuminanceAndEightBitWorks) {
  auto dir = test::temp_dir("rgb");
  // Only the blue channel varies: luminance weight 0.0722, still a ramp in x.
  write_image(dir + "/blue.png", 20, 20, OIIO::TypeDesc::UINT8, [](float x, float, int c) { return c == 2 ? x / 19.0f : 0.5f; }, 3);
  auto r = test::shipped_compiler().compile_text("heightmap \"" + dir + "/blue.png\" size 20 mm amplitude 1 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_LT(field_of(r).force_x_N[10 * 20 + 10], -0.9f);
}

TEST(Heightmap, MaximumExcludesTheRim) {
  auto dir = test::temp_dir("rim");
  // A cliff in the first column only: inside the rim the image is a gentle ramp.
  write_image(dir + "/cliff.tif", 50, 50, OIIO::TypeDesc::FLOAT, [](float x, float, int) { return x == 0 ? 10.0f : 0.001f * x; });
  auto r = test::shipped_compiler().compile_text("heightmap \"" + dir + "/cliff.tif\" size 50 mm amplitude 1 N");
  ASSERT_TRUE(r.ok());
  const auto& f = field_of(r);
  EXPECT_NEAR(f.force_x_N[25 * 50 + 25], -1.0, 1e-4);  // the ramp sets the scale...
  EXPECT_GT(std::abs(f.force_x_N[25 * 50 + 0]), 100.0f);  // ...and the rim's cliff is left outside it
}

TEST(Heightmap, SmoothingSoftensAStep) {
  auto dir = test::temp_dir("step");
  write_image(dir + "/step.tif", 64, 40, OIIO::TypeDesc::FLOAT, [](float x, float, int) { return x < 32 ? 0.0f : 1.0f; });
  auto sharp = test::shipped_compiler().compile_text("heightmap \"" + dir + "/step.tif\" size 64 mm x 40 mm amplitude 1 N");
  auto soft = test::shipped_compiler().compile_text("heightmap \"" + dir + "/step.tif\" size 64 mm x 40 mm smoothing 3 mm amplitude 1 N");
  ASSERT_TRUE(sharp.ok());
  ASSERT_TRUE(soft.ok()) << compiler::format_diagnostics(soft.diagnostics);
  auto count = [](const schema::HeightFieldTerm& f) {
    int n = 0;
    for (int x = 0; x < 64; ++x) n += std::abs(f.force_x_N[20 * 64 + x]) > 0.1f;
    return n;
  };
  EXPECT_EQ(count(field_of(sharp)), 2);  // central differences see the step from both sides
  EXPECT_GT(count(field_of(soft)), 10);  // a 3 mm Gaussian: above 10 % of the peak for +-2.1 sigma
}

TEST(Heightmap, UnusableImagesAreClearErrors) {
  auto dir = test::temp_dir("bad");
  auto code_of = [&](const std::string& stmt) {
    auto r = test::shipped_compiler().compile_text(stmt);
    EXPECT_FALSE(r.ok());
    return r.diagnostics.all().empty() ? std::string("none") : r.diagnostics.all()[0].code;
  };
  EXPECT_EQ(code_of("heightmap \"" + dir + "/missing.png\" size 10 mm amplitude 1 N"), "E0401");
  std::ofstream(dir + "/junk.png") << "not an image";
  EXPECT_EQ(code_of("heightmap \"" + dir + "/junk.png\" size 10 mm amplitude 1 N"), "E0401");
  write_image(dir + "/flat.png", 16, 16, OIIO::TypeDesc::UINT8, [](float, float, int) { return 0.5f; });
  EXPECT_EQ(code_of("heightmap \"" + dir + "/flat.png\" size 10 mm amplitude 1 N"), "E0403");
  write_image(dir + "/tiny.png", 2, 2, OIIO::TypeDesc::UINT8, [](float x, float, int) { return x * 1.0f; });
  EXPECT_EQ(code_of("heightmap \"" + dir + "/tiny.png\" size 10 mm amplitude 1 N"), "E0402");
  write_image(dir + "/huge.tif", 4097, 4096, OIIO::TypeDesc::UINT8, [](float x, float, int) { return std::fmod(x, 7.0f) / 7.0f; });
  EXPECT_EQ(code_of("heightmap \"" + dir + "/huge.tif\" size 10 mm amplitude 1 N"), "E0402");
}

TEST(Heightmap, RealPhotographCompiles) {
  auto r = test::shipped_compiler().compile_file("examples/gravel.hmat");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& f = field_of(r);
  EXPECT_EQ(f.nx, 512u);
  EXPECT_NEAR(r.program->max_lateral_force_N, test::expected_force_for_roughness(0.6), 1e-9);
  // The field's largest force inside the rim is the target; none is NaN.
  float peak = 0;
  for (std::size_t i = 0; i < f.force_x_N.size(); ++i) {
    ASSERT_TRUE(std::isfinite(f.force_x_N[i]) && std::isfinite(f.force_y_N[i]));
    peak = std::max(peak, std::hypot(f.force_x_N[i], f.force_y_N[i]));
  }
  EXPECT_GE(peak, r.program->max_lateral_force_N * 0.9999);
}
