// Sandpaper's array files (Minsky 1995, Appendix B): byte layout, size check, atomic writes, and
// the .depth quantization and .shade shading that `sandpaper array` writes. Expected bytes and
// shades are worked out here from the format and the lighting rule, not taken from the code.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "sandpaper/compiler/array_export.hpp"
#include "sandpaper/schema/array_file.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

std::vector<unsigned char> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

compiler::HeightFieldImage image(int nx, int ny, const std::function<float(int, int)>& f) {
  compiler::HeightFieldImage img;
  img.nx = nx;
  img.ny = ny;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) img.values.push_back(f(x, y));
  return img;
}

}  // namespace

TEST(ArrayFile, HeaderIsBigEndianWidthThenHeight) {
  schema::ArrayFile a;
  a.width = 258;  // 0x0102
  a.height = 3;
  for (int i = 0; i < 258 * 3; ++i) a.values.push_back(static_cast<std::uint8_t>(i % 251));
  auto bytes = schema::encode_array(a);
  ASSERT_EQ(bytes.size(), 258u * 3 + 4);
  EXPECT_EQ(bytes[0], 0x01);
  EXPECT_EQ(bytes[1], 0x02);
  EXPECT_EQ(bytes[2], 0x00);
  EXPECT_EQ(bytes[3], 0x03);
  EXPECT_EQ(bytes[4 + 258 + 5], (258 + 5) % 251);  // row-major: row 1, column 5
  auto back = schema::decode_array(bytes, "x");
  EXPECT_EQ(back.width, 258);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.values, a.values);
}

TEST(ArrayFile, WrongSizeIsAnErrorNamingBothSizes) {
  std::vector<unsigned char> b{0, 4, 0, 2, 1, 2, 3, 4, 5, 6, 7};  // says 4 x 2 = 8 values, holds 7
  try {
    schema::decode_array(b, "t.depth");
    FAIL() << "a short file was accepted";
  } catch (const schema::ArrayFileError& e) {
    EXPECT_EQ(e.reason, schema::ArrayFileError::Reason::WrongSize);
    std::string m = e.what();
    EXPECT_NE(m.find("t.depth"), std::string::npos) << m;
    EXPECT_NE(m.find("11 bytes"), std::string::npos) << m;
    EXPECT_NE(m.find("12 bytes"), std::string::npos) << m;
  }
  b.push_back(8);
  b.push_back(9);  // one too many
  EXPECT_THROW(schema::decode_array(b, "t.depth"), schema::ArrayFileError);
  EXPECT_THROW(schema::decode_array({0, 1}, "t.depth"), schema::ArrayFileError);  // no whole header
  EXPECT_NO_THROW(schema::decode_array({0, 0, 0, 0}, "empty.depth"));  // 0 x 0 is well-formed
}

TEST(ArrayFile, WritesAtomicallyAndRoundTrips) {
  auto dir = test::temp_dir("arrayfile");
  schema::ArrayFile a;
  a.width = 2;
  a.height = 2;
  a.values = {0, 85, 170, 255};
  schema::write_depth_file(dir + "/a.depth", a);
  EXPECT_EQ(bytes_of(dir + "/a.depth"), (std::vector<unsigned char>{0, 2, 0, 2, 0, 85, 170, 255}));
  auto back = schema::read_array_file(dir + "/a.depth");
  EXPECT_EQ(back.values, a.values);
  // A failed write leaves the old file and no temporary beside it.
  schema::ArrayFile bad = a;
  bad.values.pop_back();
  EXPECT_THROW(schema::write_depth_file(dir + "/a.depth", bad), schema::ArrayFileError);
  EXPECT_EQ(bytes_of(dir + "/a.depth").size(), 8u);
  EXPECT_THROW(schema::write_shade_file(dir + "/no/such/dir/a.shade", a), std::runtime_error);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  try {
    schema::read_array_file(dir + "/missing.depth");
    FAIL();
  } catch (const schema::ArrayFileError& e) {
    EXPECT_EQ(e.reason, schema::ArrayFileError::Reason::Unreadable);
  }
  EXPECT_EQ(schema::array_kind_of("x/Y.DEPTH"), schema::ArrayKind::Depth);
  EXPECT_EQ(schema::array_kind_of("y.shade"), schema::ArrayKind::Shade);
  EXPECT_EQ(schema::array_kind_of("y.png"), schema::ArrayKind::None);
}

TEST(ArrayExport, QuantizationIsNearestWithHalvesUp) {
  // Range 0..255 in steps the format can hold, plus points just below, on and above a half step.
  auto img = image(6, 1, [](int x, int) {
    const float v[] = {0.0f, 255.0f, 10.49f, 10.5f, 10.51f, 127.5f};
    return v[x];
  });
  auto a = compiler::quantize_depth(img);
  EXPECT_EQ(a.width, 6);
  EXPECT_EQ(a.height, 1);
  EXPECT_EQ(a.values, (std::vector<std::uint8_t>{0, 255, 10, 11, 11, 128}));
  // Any range maps to 0..255: -2..2 by steps of 1 -> 0, 63.75, 127.5, 191.25, 255.
  auto b = compiler::quantize_depth(image(5, 1, [](int x, int) { return static_cast<float>(x - 2); }));
  EXPECT_EQ(b.values, (std::vector<std::uint8_t>{0, 64, 128, 191, 255}));
}

TEST(ArrayExport, ShadingIsLambertianLitFromTheUpperLeft) {
  // Light at azimuth 135 deg (up and left), elevation 45 deg: l = (-1/2, 1/2, 1/sqrt 2).
  const double lz = std::sqrt(0.5);
  // Level ground: L = l_z, so 255 (1 - 0.7071) = 74.7 -> 75.
  auto flat = compiler::shade_relief(image(4, 4, [](int x, int y) { return x == 3 && y == 3 ? 1.0f : 0.0f; }), 1e-3, 1e-3, 0.0);
  EXPECT_EQ(flat.values[0], static_cast<std::uint8_t>(std::lround(255 * (1 - lz))));
  // A plane facing the light (rising to the right and down the picture, slope 1 along (1, -1)/sqrt 2
  // with y up): its normal is l, so it is white (0) everywhere.
  auto facing = compiler::shade_relief(image(5, 5, [](int x, int y) { return static_cast<float>(x + y); }), 1e-3, 1e-3,
                                       std::nullopt);
  for (auto v : facing.values) EXPECT_EQ(v, 0);
  // The same plane turned away (rising up and to the left): normal (1, -1, sqrt 2)/2, n.l = 0: black.
  auto away = compiler::shade_relief(image(5, 5, [](int x, int y) { return static_cast<float>(-x - y); }), 1e-3, 1e-3,
                                     std::nullopt);
  for (auto v : away.values) EXPECT_EQ(v, 255);
  // With a stated relief: heights 0..4 samples become 0..2 mm over 4 mm along x (slope 0.5, along
  // +x only): n = (-0.5, 0, 1) / |.|, n.l = (0.25 + 0.7071) / 1.118 = 0.8561 -> 255 x 0.1439 = 36.7 -> 37.
  auto ramp = compiler::shade_relief(image(5, 2, [](int x, int) { return static_cast<float>(x); }), 1e-3, 1e-3, 2e-3);
  double n_dot_l = (0.25 + lz) / std::sqrt(1.25);
  EXPECT_EQ(ramp.values[2], static_cast<std::uint8_t>(std::lround(255 * (1 - n_dot_l))));
}

TEST(ArrayExport, DepthFileRoundTripsThroughTheCompiler) {
  // A height image written as .depth and read back by a heightmap statement gives the force the
  // quantized ramp implies: 8-bit steps of 5 over 52 columns of 1 mm, relief 2.55 mm over 0..255.
  auto dir = test::temp_dir("roundtrip");
  auto img = image(52, 8, [](int x, int) { return static_cast<float>(x) / 51.0f; });
  schema::write_depth_file(dir + "/ramp.depth", compiler::quantize_depth(img));
  auto r = test::shipped_compiler().compile_text("heightmap \"" + dir + "/ramp.depth\" size 52 mm x 8 mm depth 2.55 mm press 1 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& f = std::get<schema::HeightFieldTerm>(r.program->terms.at(0));
  // Slope = 2.55 mm x 5/255 per 1 mm column = 0.05: F = 1 N x 0.05, toward -x.
  for (std::size_t i = 0; i < f.force_x_N.size(); ++i) ASSERT_NEAR(f.force_x_N[i], -0.05, 1e-6) << i;
}
