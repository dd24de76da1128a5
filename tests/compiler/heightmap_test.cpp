// Images as height fields: gradient direction and scale, pixel formats and channels, sampling,
// inversion, the stylus reading (depth + press), .depth files, and unusable images. Expected forces
// are computed here from the images' own formulas (a ramp has one slope), not from the compiler.
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "sandpaper/schema/array_file.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

// Writes a one-channel image whose value at (x, y) (row y from the top) is f(x, y).
template <class F>
void write_image(const std::string& path, int w, int h, OIIO::TypeDesc type, F f, int channels = 1) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(w, h, channels, type);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // store colour as given, not divided by alpha
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

// The first error of a compile: a warning such as a stretched picture's W0307 may come before it.
compiler::Diagnostic error_of(const compiler::CompileResult& r) {
  for (const auto& d : r.diagnostics.all())
    if (d.severity == compiler::Severity::Error) return d;
  return {};
}

// The first error of a compile that must be refused with `code` (an empty one if it was not).
compiler::Diagnostic refusal(const std::string& text, const std::string& code) {
  const auto r = test::shipped_compiler().compile_text(text);
  EXPECT_FALSE(r.ok()) << text;
  const auto d = error_of(r);
  EXPECT_EQ(d.code, code) << compiler::format_diagnostics(r.diagnostics);
  return d;
}

// A 16 x 16 px ramp written by OpenImageIO as `dir/ramp.EXT`, as bytes: a good file to damage.
std::string ramp_bytes(const std::string& dir, const std::string& ext, OIIO::TypeDesc type) {
  write_image(dir + "/ramp" + ext, 16, 16, type, [](float x, float, int) { return x / 15.0f; });
  std::ifstream in(dir + "/ramp" + ext, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// `bytes` saved as `dir/name` and compiled as a 16 mm height map.
compiler::CompileResult compile_image_bytes(const std::string& dir, const std::string& name, const std::string& bytes) {
  std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
  return test::shipped_compiler().compile_text("heightmap \"" + dir + "/" + name + "\" size 16 mm amplitude 1 N");
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

TEST(Heightmap, APictureKeepsItsShapeAndAStretchedOneIsSaid) {
  auto dir = test::temp_dir("aspect");
  // 720 x 477 px, the photograph the issue found stretched over a 60 mm square.
  write_image(dir + "/board.png", 720, 477, OIIO::TypeDesc::UINT8,
              [](float x, float y, int) { return 0.5f + 0.25f * std::sin(x / 7) + 0.25f * std::sin(y / 5); });
  const std::string head = "heightmap \"" + dir + "/board.png\" size 60 mm";
  auto one = test::shipped_compiler().compile_text(head + " amplitude 1 N");
  ASSERT_TRUE(one.ok()) << compiler::format_diagnostics(one.diagnostics);
  EXPECT_DOUBLE_EQ(one.program->size_m[0], 0.060);
  EXPECT_NEAR(one.program->size_m[1], 0.060 * 477 / 720, 1e-12);  // 39.75 mm
  EXPECT_NEAR(field_of(one).spacing_m[0], field_of(one).spacing_m[1], 1e-12);
  EXPECT_TRUE(test::codes(one, compiler::Severity::Warning).empty());
  // Both sides given: as written, with a warning that names both spacings and the size that fits.
  auto square = test::shipped_compiler().compile_text(head + " x 60 mm amplitude 1 N");
  ASSERT_TRUE(square.ok()) << compiler::format_diagnostics(square.diagnostics);
  EXPECT_DOUBLE_EQ(square.program->size_m[1], 0.060);
  EXPECT_EQ(test::codes(square, compiler::Severity::Warning), std::vector<std::string>{"W0307"});
  for (const auto& d : square.diagnostics.all())
    if (d.code == "W0307") {
      EXPECT_NE(d.message.find("0.08333 mm per px across and 0.1258 mm per px down"), std::string::npos) << d.message;
      EXPECT_NE(d.suggestion.find("(60 mm x 39.75 mm)"), std::string::npos) << d.suggestion;
    }
  // Within 1 %: said to keep the shape, no warning (60 x 39.9 mm is 0.4 % off).
  auto close = test::shipped_compiler().compile_text(head + " x 39.9 mm amplitude 1 N");
  EXPECT_TRUE(test::codes(close, compiler::Severity::Warning).empty()) << compiler::format_diagnostics(close.diagnostics);
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

// Under 3 px a side is known from the header: the pixels are not decoded first. Shown with a file
// whose pixel data is corrupt (decoded, it is E0401), as the fuzzer's 528-byte OpenEXR file that
// claimed 1 x 16,776,449 px. With `sampling` the same strip is enlarged, so it is read.
TEST(Heightmap, APictureUnderThreePixelsASideIsRefusedFromItsHeader) {
  auto dir = test::temp_dir("strip");
  auto compile = [](const std::string& text) { return test::shipped_compiler().compile_text(text); };
  write_image(dir + "/strip.png", 2, 400, OIIO::TypeDesc::UINT16, [](float, float y, int) { return std::fmod(y, 9.0f) / 9.0f; });
  std::string bytes;
  {
    std::ifstream in(dir + "/strip.png", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto data = bytes.find("IDAT");
  ASSERT_NE(data, std::string::npos);
  // Every chunk whole, so the header reads; the pixel data overwritten, so decoding fails (E0401).
  std::string corrupt = bytes;
  for (std::size_t i = data + 4; i < data + 4 + 16 && i < corrupt.size(); ++i) corrupt[i] = '\xff';
  std::ofstream(dir + "/cut.png", std::ios::binary) << corrupt;
  auto cut = compile("heightmap \"" + dir + "/cut.png\" size 2 mm x 400 mm amplitude 1 N");
  ASSERT_FALSE(cut.ok());
  EXPECT_EQ(error_of(cut).code, "E0402") << compiler::format_diagnostics(cut.diagnostics);
  EXPECT_NE(error_of(cut).message.find("2 x 400 px; a height map needs at least 3 x 3"), std::string::npos)
      << error_of(cut).message;
  auto whole = compile("heightmap \"" + dir + "/strip.png\" size 2 mm x 400 mm amplitude 1 N");
  ASSERT_FALSE(whole.ok());
  EXPECT_EQ(error_of(whole).code, "E0402");
  auto sampled = compile("heightmap \"" + dir + "/strip.png\" size 20 mm x 400 mm sampling 1 mm amplitude 1 N");
  ASSERT_TRUE(sampled.ok()) << compiler::format_diagnostics(sampled.diagnostics);
  EXPECT_EQ(field_of(sampled).nx, 20u);
  EXPECT_EQ(field_of(sampled).ny, 400u);
  auto sampled_cut = compile("heightmap \"" + dir + "/cut.png\" size 20 mm x 400 mm sampling 1 mm amplitude 1 N");
  ASSERT_FALSE(sampled_cut.ok());
  EXPECT_EQ(error_of(sampled_cut).code, "E0401");  // read, and found corrupt
}

// Without `repeat` the peak slope is taken inside a rim of 3 sigma plus the outermost two samples.
// A picture 3 samples tall has nothing inside even unsmoothed: that is its size (E0402, with a
// sampling that gives 5 a side), not a smoothing it never asked for, which E0304 used to blame.
// A smoothing too wide for a picture large enough is E0304, naming the widest that fits.
TEST(Heightmap, NothingInsideTheRimNamesItsCauseAndAFixThatCompiles) {
  auto dir = test::temp_dir("rim");
  const auto ridges = [](float x, float y, int) { return 0.5f + 0.25f * std::sin(x) + 0.25f * std::sin(0.7f * y); };
  write_image(dir + "/short.tif", 40, 3, OIIO::TypeDesc::UINT8, ridges);
  write_image(dir + "/square.tif", 40, 40, OIIO::TypeDesc::UINT8, ridges);
  write_image(dir + "/six.tif", 6, 40, OIIO::TypeDesc::UINT8, ridges);
  auto compile = [](const std::string& text) { return test::shipped_compiler().compile_text(text); };
  const auto quoted = [](const std::string& suggestion, const std::string& word) {
    const auto at = suggestion.find("`" + word + " ");
    return at == std::string::npos ? std::string() : suggestion.substr(at + 1, suggestion.find('`', at + 1) - at - 1);
  };
  const auto smoothing_of = [](const std::string& suggestion) {
    const auto at = suggestion.find("at most ");
    return at == std::string::npos ? std::string() : suggestion.substr(at + 8, suggestion.find(" mm", at) - at - 8);
  };

  const std::string short_head = "heightmap \"" + dir + "/short.tif\" size 40 mm x 3 mm";
  const auto tall = refusal(short_head + " amplitude 1 N", "E0402");
  EXPECT_NE(tall.message.find("40 x 3 samples"), std::string::npos) << tall.message;
  EXPECT_NE(tall.message.find("at least 5 x 5"), std::string::npos) << tall.message;
  EXPECT_EQ(tall.message.find("smoothing"), std::string::npos) << tall.message;
  const std::string sampling = quoted(tall.suggestion, "sampling");
  ASSERT_FALSE(sampling.empty()) << tall.suggestion;
  auto resampled = compile(short_head + " " + sampling + " amplitude 1 N");
  ASSERT_TRUE(resampled.ok()) << sampling << "\n" << compiler::format_diagnostics(resampled.diagnostics);
  EXPECT_GE(field_of(resampled).ny, 5u);
  auto tiled = compile(short_head + " repeat amplitude 1 N");
  EXPECT_TRUE(tiled.ok()) << compiler::format_diagnostics(tiled.diagnostics);

  const std::string square_head = "heightmap \"" + dir + "/square.tif\" size 40 mm";
  const auto wide = refusal(square_head + " smoothing 8 mm amplitude 1 N", "E0304");
  EXPECT_NE(wide.message.find("smoothing 8 mm"), std::string::npos) << wide.message;
  const std::string widest = smoothing_of(wide.suggestion);
  ASSERT_FALSE(widest.empty()) << wide.suggestion;
  auto fits = compile(square_head + " smoothing " + widest + " mm amplitude 1 N");
  EXPECT_TRUE(fits.ok()) << widest << "\n" << compiler::format_diagnostics(fits.diagnostics);
  // Just past it is refused: the named smoothing is the widest, not merely one that fits.
  refusal(square_head + " smoothing " + std::to_string(std::stod(widest) * 1.02) + " mm amplitude 1 N", "E0304");

  // Six samples wide leaves one inside an unsmoothed rim, and any smoothing covers it.
  const std::string six_head = "heightmap \"" + dir + "/six.tif\" size 6 mm x 40 mm";
  EXPECT_TRUE(compile(six_head + " amplitude 1 N").ok());
  const auto any = refusal(six_head + " smoothing 0.01 mm amplitude 1 N", "E0304");
  EXPECT_NE(any.suggestion.find("remove the smoothing"), std::string::npos) << any.suggestion;
}

// Smoothing's work grows with the samples times the kernel's width: the image fuzzer's F38 was a
// 16 x 64,524 px TIFF over 20 mm under 0.5 mm, 1e10 multiply-adds (4 s in release, over 25 s under
// ASan; its input is replayed as fuzz.replay.image). Here 1200 x 1200 px over 1 mm under 0.2 mm is
// 4.2e9. Refused before the blur, with a sampling and a smoothing that fit, and each of those compiles.
TEST(Heightmap, AnImageSmoothingPastTheBudgetIsRefusedWithASamplingThatFits) {
  auto dir = test::temp_dir("slow-blur");
  auto compile = [](const std::string& text) { return test::shipped_compiler().compile_text(text); };
  write_image(dir + "/noise.png", 1200, 1200, OIIO::TypeDesc::UINT8,
              [](float x, float y, int) { return std::fmod(x * 7 + y * 13, 17.0f) / 17.0f; });
  const std::string head = "heightmap \"" + dir + "/noise.png\" size 1 mm repeat";
  auto slow = compile(head + " smoothing 0.2 mm amplitude 1 N");
  ASSERT_FALSE(slow.ok());
  const auto d = error_of(slow);
  EXPECT_EQ(d.code, "E0304") << compiler::format_diagnostics(slow.diagnostics);
  EXPECT_NE(d.message.find("1200 x 1200 samples"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("more than the limit of 1e+09"), std::string::npos) << d.message;
  // The suggestion names both ways out; each must compile.
  const auto sampling_at = d.suggestion.find("`sampling ");
  const auto smoothing_at = d.suggestion.find("smoothing of at most ");
  ASSERT_NE(sampling_at, std::string::npos) << d.suggestion;
  ASSERT_NE(smoothing_at, std::string::npos) << d.suggestion;
  const double sampling_mm = std::stod(d.suggestion.substr(sampling_at + 10));
  const double smoothing_mm = std::stod(d.suggestion.substr(smoothing_at + 21));
  EXPECT_GT(sampling_mm, 1.0 / 1200);  // coarser than the image's own pixels: fewer samples
  auto resampled = compile(head + " sampling " + std::to_string(sampling_mm) + " mm smoothing 0.2 mm amplitude 1 N");
  EXPECT_TRUE(resampled.ok()) << compiler::format_diagnostics(resampled.diagnostics);
  auto less = compile(head + " smoothing " + std::to_string(smoothing_mm) + " mm amplitude 1 N");
  EXPECT_TRUE(less.ok()) << compiler::format_diagnostics(less.diagnostics);
  // About 0.048 mm: 1e9 / (1,440,000 samples x 2 passes) = 347 taps, a sigma of 57 px of 0.83 um.
  EXPECT_LT(smoothing_mm, 0.05);
  EXPECT_GT(smoothing_mm, 0.04);
}

// F38's strip (16 x 64,524 px over 20 mm under 0.5 mm) once had E0304 suggest `sampling 0.0137 mm`,
// whose resize (1,460 x 1,460 samples from 16 px across: a window of 5 x 16,133 each) F39's limits
// refuse. The suggested sampling must also fit the resize limits, and compile.
TEST(Heightmap, ASmoothingSuggestionNamesASamplingWhoseResizeFits) {
  auto dir = test::temp_dir("strip-smoothing");
  write_image(dir + "/strip.tif", 16, 64524, OIIO::TypeDesc::UINT8, [](float x, float y, int) {
    return 0.5f + 0.25f * std::sin(6.2832f * y / 6452.4f) + 0.25f * std::sin(6.2832f * x / 16.0f);
  });
  auto compile = [](const std::string& text) { return test::shipped_compiler().compile_text(text); };
  const std::string head = "heightmap \"" + dir + "/strip.tif\" size 20 mm x 20 mm repeat";
  auto slow = compile(head + " smoothing 0.5 mm amplitude 1 N");
  ASSERT_FALSE(slow.ok());
  const auto d = error_of(slow);
  EXPECT_EQ(d.code, "E0304") << compiler::format_diagnostics(slow.diagnostics);
  const auto at = d.suggestion.find("`sampling ");
  ASSERT_NE(at, std::string::npos) << d.suggestion;
  const std::string sampling = d.suggestion.substr(at + 1, d.suggestion.find('`', at + 1) - at - 1);
  auto resampled = compile(head + " " + sampling + " smoothing 0.5 mm amplitude 1 N");
  EXPECT_TRUE(resampled.ok()) << sampling << "\n" << compiler::format_diagnostics(resampled.diagnostics);

  // The other way round: E0402 for the resize names a sampling under which the smoothing fits too,
  // and not the picture's own pixels, over which the smoothing is what E0304 refused.
  auto fine = compile(head + " sampling 0.0137 mm smoothing 0.5 mm amplitude 1 N");
  ASSERT_FALSE(fine.ok());
  const auto f = error_of(fine);
  EXPECT_EQ(f.code, "E0402") << compiler::format_diagnostics(fine.diagnostics);
  EXPECT_EQ(f.suggestion.find("leave out"), std::string::npos) << f.suggestion;
  const auto at2 = f.suggestion.find("`sampling ");
  ASSERT_NE(at2, std::string::npos) << f.suggestion;
  const std::string sampling2 = f.suggestion.substr(at2 + 1, f.suggestion.find('`', at2 + 1) - at2 - 1);
  auto resampled2 = compile(head + " " + sampling2 + " smoothing 0.5 mm amplitude 1 N");
  EXPECT_TRUE(resampled2.ok()) << sampling2 << "\n" << compiler::format_diagnostics(resampled2.diagnostics);
}

// `sampling` on a picture much longer than the samples along y (F39): OpenImageIO's resize walks a
// window of source rows for each sample, kept on a thread's stack, and lengthens it when x is
// enlarged. 2 x 800,000 px to 40 x 3 samples needs 21,333,335 rows: OpenImageIO aborted the
// compiler (its assertion at 2^20). Refused past 65,537, naming a sampling that fits when one does.
TEST(Heightmap, AResampleWhoseWindowIsTooLongIsRefusedWithASamplingThatFits) {
  auto dir = test::temp_dir("long-window");
  auto compile = [](const std::string& text) { return test::shipped_compiler().compile_text(text); };
  auto stripes = [](float x, float y, int) { return std::fmod(x + y, 2.0f); };
  write_image(dir + "/strip.tif", 2, 800000, OIIO::TypeDesc::UINT8, stripes);
  auto aborted = compile("heightmap \"" + dir + "/strip.tif\" size 40 mm x 3 mm sampling 1 mm amplitude 1 N");
  ASSERT_FALSE(aborted.ok());
  const auto a = error_of(aborted);
  EXPECT_EQ(a.code, "E0402") << compiler::format_diagnostics(aborted.diagnostics);
  EXPECT_NE(a.message.find("would walk a window of 21333335 pixels along y"), std::string::npos) << a.message;
  // Finer sampling enlarges x, which lengthens the window as much as it adds rows; 2 px is too narrow
  // to use as it is: no way out but another picture.
  EXPECT_NE(a.suggestion.find("closer in number to the samples"), std::string::npos) << a.suggestion;

  // 20 x 200,000 px to 3 x 3 samples (shrinking both ways: Lanczos-3) walks 400,001 rows a sample,
  // which the resize would do, on a 1.6 MB stack window. At 19 rows or more and at most 20 columns
  // the window is under the limit: about 1.58 mm.
  write_image(dir + "/tall.tif", 20, 200000, OIIO::TypeDesc::UINT8, stripes);
  const std::string head = "heightmap \"" + dir + "/tall.tif\" size 30 mm x 30 mm";
  auto refused = compile(head + " sampling 10 mm amplitude 1 N");
  ASSERT_FALSE(refused.ok());
  const auto d = error_of(refused);
  EXPECT_EQ(d.code, "E0402");
  EXPECT_NE(d.message.find("to 3 x 3 samples: OpenImageIO's resize would walk a window of 400001 pixels along y"),
            std::string::npos)
      << d.message;
  EXPECT_NE(d.message.find("more than the limit of 65537"), std::string::npos) << d.message;
  EXPECT_NE(d.suggestion.find("or leave out `sampling` to use the image's 20 x 200000 px as they are"), std::string::npos)
      << d.suggestion;
  const auto at = d.suggestion.find("`sampling ");
  ASSERT_NE(at, std::string::npos) << d.suggestion;
  const double sampling_mm = std::stod(d.suggestion.substr(at + 10));
  EXPECT_LT(sampling_mm, 30.0 / 18.5);
  EXPECT_GT(sampling_mm, 30.0 / 20.5);
  auto finer = compile(head + " sampling " + std::to_string(sampling_mm) + " mm amplitude 1 N");
  EXPECT_TRUE(finer.ok()) << compiler::format_diagnostics(finer.diagnostics);
}

// The x window's weights are precomputed for every column of samples, on the heap: a 5,000,000 x
// 1 px picture over 30 x 30 samples would hold 666,669 x 30 of them (80 MB), past 2^24 (64 MiB).
// (Before the limit it compiled, in 15 s.)
TEST(Heightmap, AResampleWhoseXWeightsWouldPassTheirLimitIsRefused) {
  auto dir = test::temp_dir("wide-window");
  write_image(dir + "/wide.tif", 5000000, 1, OIIO::TypeDesc::UINT8, [](float x, float, int) { return std::fmod(x, 2.0f); });
  const auto d = refusal("heightmap \"" + dir + "/wide.tif\" size 30 mm x 30 mm sampling 1 mm amplitude 1 N", "E0402");
  EXPECT_NE(d.message.find("would hold 666669 weights for each of the 30 columns, 20000070 in all, more than the limit "
                           "of 16777216"),
            std::string::npos)
      << d.message;
}

// A resize whose window fits but whose whole walk does not: a 1 x 200 px profile stretched to
// 2,000 x 2,000 samples walks 5 x 801 pixels for each (enlarging x by 2,000 lengthens the y window
// to 801 rows, of which 5 weigh anything): 4e6 x (5 x 5 + 801) = 3.3e9 visits, about 30 s.
TEST(Heightmap, AResamplePastItsBudgetOfVisitsIsRefused) {
  auto dir = test::temp_dir("slow-resize");
  write_image(dir + "/profile.tif", 1, 200, OIIO::TypeDesc::UINT8, [](float, float y, int) { return std::fmod(y, 2.0f); });
  const auto d = refusal("heightmap \"" + dir + "/profile.tif\" size 20 mm x 20 mm sampling 0.01 mm amplitude 1 N", "E0402");
  EXPECT_NE(d.message.find("to 2000 x 2000 samples: OpenImageIO's resize would walk a window of 5 x 801 pixels for "
                           "each sample (5 of its rows weighted), about 3.304e+09 pixel visits, more than the limit of 2e+09"),
            std::string::npos)
      << d.message;
  // Fewer samples, the same window: at most 1,556 a side, so a sampling of 0.01285 mm or more.
  EXPECT_EQ(d.suggestion.find("leave out"), std::string::npos) << d.suggestion;
  const auto at = d.suggestion.find("`sampling ");
  ASSERT_NE(at, std::string::npos) << d.suggestion;
  const double sampling_mm = std::stod(d.suggestion.substr(at + 10));
  EXPECT_GE(sampling_mm, 20.0 / 1556.5);
  EXPECT_LT(sampling_mm, 0.0132);
}

// A PNG's chunks are walked before libpng allocates them at the lengths they claim (F20): a chunk
// running past the end of the file, or no IEND, is E0401 at once.
TEST(Heightmap, APngWhoseChunkClaimsMoreThanTheFileIsRefusedBeforeDecoding) {
  auto dir = test::temp_dir("png-claim");
  const std::string png = ramp_bytes(dir, ".png", OIIO::TypeDesc::UINT8);
  const std::size_t after_header = 8 + 12 + 13;  // the signature, then IHDR's 13 bytes in 12 of framing
  ASSERT_EQ(png.substr(12, 4), "IHDR");
  auto compile_png = [&](const std::string& name, const std::string& bytes) { return compile_image_bytes(dir, name, bytes); };
  ASSERT_TRUE(compile_png("whole.png", png).ok());
  // A text chunk claiming 1,814,043,494 bytes (0x6c201b66) in a file of a few hundred.
  const std::string claim = std::string("\x6c\x20\x1b\x66tEXtComment", 15) + std::string(40, 'x');
  auto r = compile_png("claim.png", png.substr(0, after_header) + claim + png.substr(after_header));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(error_of(r).code, "E0401");
  EXPECT_NE(error_of(r).message.find("chunk 'tEXt' at byte 33 claims 1814043494 bytes"), std::string::npos)
      << error_of(r).message;
  const auto iend = png.rfind("IEND");
  ASSERT_NE(iend, std::string::npos);
  r = compile_png("no-end.png", png.substr(0, iend - 4));  // every chunk whole, but no IEND
  ASSERT_FALSE(r.ok());
  EXPECT_NE(error_of(r).message.find("without its IEND chunk"), std::string::npos) << error_of(r).message;
}

// An OpenEXR header's attributes are walked before OpenEXR Core allocates them at the sizes they
// claim (F44): one running past the end of the file, a negative size, or a file ending inside the
// header is E0401 at once, in these words, not Core's "unable to read" after it has mapped them.
TEST(Heightmap, AnExrWhoseAttributeClaimsMoreThanTheFileIsRefusedBeforeDecoding) {
  auto dir = test::temp_dir("exr-claim");
  const std::string exr = ramp_bytes(dir, ".exr", OIIO::TypeDesc::HALF);
  ASSERT_EQ(exr.substr(0, 4), "v/1\x01");
  auto compile_exr = [&](const std::string& name, const std::string& bytes) { return compile_image_bytes(dir, name, bytes); };
  auto message = [](const compiler::CompileResult& r) {
    if (r.diagnostics.all().empty()) return std::string("none");
    return error_of(r).code + " " + error_of(r).message;
  };
  ASSERT_TRUE(compile_exr("whole.exr", exr).ok());
  // An attribute of a type Core does not know, claiming 994,377,728 bytes (0x3b450000), in front of
  // the file's own: as found by the image target.
  auto with_attribute = [&](const std::string& size_le) {
    return exr.substr(0, 8) + std::string("junk\0opaque\0", 12) + size_le + "xy" + exr.substr(8);
  };
  // The file is 18 bytes longer than ramp.exr, and the size field ends at byte 24.
  auto r = compile_exr("claim.exr", with_attribute(std::string("\x00\x00\x45\x3b", 4)));
  EXPECT_NE(message(r).find("E0401 cannot read image"), std::string::npos) << message(r);
  EXPECT_NE(message(r).find("its attribute 'junk' at byte 8 claims 994377728 bytes, and the file has " +
                            std::to_string(exr.size() - 6) + " after its size"),
            std::string::npos)
      << message(r);
  r = compile_exr("negative.exr", with_attribute(std::string("\xff\xff\xff\xff", 4)));
  EXPECT_NE(message(r).find("the OpenEXR header is damaged: its attribute 'junk' at byte 8 claims -1 bytes, a negative size"),
            std::string::npos)
      << message(r);
  // A name of 40 bytes without the long-names flag: Core reads it (F44's file had one of 42), so the
  // walk does too.
  const std::string long_name(40, 'n');
  r = compile_exr("long-name.exr",
                  exr.substr(0, 8) + long_name + std::string("\0opaque\0\x00\x00\x45\x3b", 12) + exr.substr(8));
  EXPECT_NE(message(r).find("its attribute '" + long_name + "' at byte 8 claims 994377728 bytes"), std::string::npos)
      << message(r);
  // A name of 256 bytes, one past the longest a name may be.
  const std::string attribute_tail("\0opaque\0\x02\x00\x00\x00xy", 14);  // its type, a size of 2, its value
  r = compile_exr("too-long.exr", exr.substr(0, 8) + std::string(256, 'n') + attribute_tail + exr.substr(8));
  EXPECT_NE(message(r).find("the attribute at byte 8 has a name longer than 255 bytes"), std::string::npos)
      << message(r);
  // A type of 256 bytes after a short name: the type is held to the same limit.
  r = compile_exr("too-long-type.exr", exr.substr(0, 8) + std::string("tag\0", 4) + std::string(256, 't') +
                                           std::string("\0\x02\x00\x00\x00xy", 7) + exr.substr(8));
  EXPECT_NE(message(r).find("the attribute at byte 8 has a type longer than 255 bytes"), std::string::npos)
      << message(r);
  // The same attribute at a size that fits is walked over, and Core reads the file.
  EXPECT_TRUE(compile_exr("fits.exr", with_attribute(std::string("\x02\x00\x00\x00", 4))).ok());
  r = compile_exr("cut.exr", exr.substr(0, 11));  // inside the first attribute's name
  EXPECT_NE(message(r).find("the OpenEXR header is cut short: the file ends at byte 11 inside it"), std::string::npos)
      << message(r);
  // A multipart file (version flag 0x1000): the walk goes on into the second part's header.
  const std::string multipart = std::string("v/1\x01\x02\x10\x00\x00", 8) +
                                std::string("name\0string\0\x01\x00\x00\x00" "a", 17) + std::string("\0", 1) +
                                std::string("big\0opaque\0\x00\x00\x00\x70", 15) + "zz";
  r = compile_exr("parts.exr", multipart);
  EXPECT_NE(message(r).find("its attribute 'big' at byte 26 claims 1879048192 bytes, and the file has 2 after its size"),
            std::string::npos)
      << message(r);
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

namespace {

compiler::CompileResult compile(const std::string& text) { return test::shipped_compiler().compile_text(text); }

std::string first_error(const compiler::CompileResult& r) {
  auto c = test::codes(r);
  return c.empty() ? "none" : c.front();
}

std::string message_of(const compiler::CompileResult& r) {
  for (const auto& d : r.diagnostics.all())
    if (d.severity == compiler::Severity::Error) return d.message + " | " + d.suggestion;
  return "";
}

// Roughness for a force, restated from Minsky 1995 Fig. 19: r = (F / 382 gf)^0.759593.
double roughness_for(double force_N) { return std::pow(force_N / (382 * 9.80665e-3), 0.759593); }

}  // namespace

// Every pixel type and channel count. Heights: a ramp along x, exact in the pixel type; a second
// ramp along y sits in the channels that must be ignored (alpha) or that luminance weighs, so the
// expected force is known from the weights alone.
class PixelTypes : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(PixelTypes, RampGivesTheExpectedConstantForce) {
  auto [type_index, channels] = GetParam();
  struct Type {
    OIIO::TypeDesc type;
    const char* ext;
    float step;  // per pixel, exact in the type: 5/255 and 1285/65535 are k/51; 1/4 is exact in half
    float offset;
  };
  const Type types[] = {{OIIO::TypeDesc::UINT8, "png", 1.0f / 51, 0},
                        {OIIO::TypeDesc::UINT16, "tif", 1.0f / 51, 0},
                        {OIIO::TypeDesc::HALF, "exr", 0.25f, 3.0f},  // heights 3..15.75: not 0..1
                        {OIIO::TypeDesc::FLOAT, "tif", 0.25f, -7.0f}};
  const Type& t = types[type_index];
  const int w = 52, h = 20;
  auto dir = test::temp_dir("px");
  std::string path = dir + "/ramp." + t.ext;
  // Channel roles: 1 = grey; 2 = grey + alpha; 3 = R, G, B; 4 = R, G, B, A.
  // Grey and R ramp along x; G ramps down the rows; alpha ramps along y steeply (must be ignored).
  write_image(path, w, h, t.type, [&](float x, float y, int c) {
    if (channels <= 2) return c == 0 ? t.offset + t.step * x : 5.0f * y / h;
    if (c == 0) return t.offset + t.step * x;
    if (c == 1) return t.offset + t.step * y;
    if (c == 2) return t.offset;
    return 5.0f * y / h;
  }, channels);
  auto r = compile("heightmap \"" + path + "\" size 52 mm x 20 mm amplitude 1 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& f = field_of(r);
  ASSERT_EQ(f.nx, 52u);
  ASSERT_EQ(f.ny, 20u);
  // Slope in image units per metre (1 mm pixels): x from the ramp; y (up = toward row 0) from G.
  double sx = channels <= 2 ? t.step / 1e-3 : 0.2126 * t.step / 1e-3;
  double sy = channels <= 2 ? 0.0 : -0.7152 * t.step / 1e-3;
  double k = 1.0 / std::hypot(sx, sy);  // amplitude 1 N over the largest slope, which is everywhere
  for (std::size_t i = 0; i < f.force_x_N.size(); ++i) {
    ASSERT_NEAR(f.force_x_N[i], -k * sx, 1e-4) << i;
    ASSERT_NEAR(f.force_y_N[i], -k * sy, 1e-4) << i;
  }
}

std::string pixel_type_name(const ::testing::TestParamInfo<std::tuple<int, int>>& p) {
  static const char* const kTypes[] = {"uint8", "uint16", "half", "float"};
  return std::string(kTypes[std::get<0>(p.param)]) + "_" + std::to_string(std::get<1>(p.param)) + "ch";
}

INSTANTIATE_TEST_SUITE_P(Heightmap, PixelTypes,
                         ::testing::Combine(::testing::Values(0, 1, 2, 3), ::testing::Values(1, 2, 3, 4)), pixel_type_name);

TEST(Heightmap, InvertFlipsTheForce) {
  auto dir = test::temp_dir("invert");
  // A ramp with a bump, so that inverting is not the same as mirroring.
  write_image(dir + "/bump.tif", 30, 30, OIIO::TypeDesc::FLOAT,
              [](float x, float y, int) { return 0.02f * x + std::exp(-((x - 12) * (x - 12) + (y - 15) * (y - 15)) / 20.0f); });
  auto plain = compile("heightmap \"" + dir + "/bump.tif\" size 30 mm amplitude 1 N");
  auto inv = compile("heightmap \"" + dir + "/bump.tif\" size 30 mm amplitude 1 N invert");
  ASSERT_TRUE(plain.ok() && inv.ok()) << compiler::format_diagnostics(inv.diagnostics);
  const auto &a = field_of(plain), &b = field_of(inv);
  for (std::size_t i = 0; i < a.force_x_N.size(); ++i) {
    ASSERT_NEAR(b.force_x_N[i], -a.force_x_N[i], 1e-5) << i;  // lo + hi - v rounds in float
    ASSERT_NEAR(b.force_y_N[i], -a.force_y_N[i], 1e-5) << i;
  }
}

TEST(Heightmap, DepthAndPressGiveTheStylusForce) {
  auto dir = test::temp_dir("stylus");
  // Grey 0..1 over 52 px (51 steps, exact in 16 bits) on a 104 mm patch: 2 mm pixels. The range
  // maps to 0..1.02 mm, so the slope is 1.02 mm / (51 x 2 mm) = 0.01 and F = 3 N x 0.01 = 0.03 N.
  write_image(dir + "/ramp.png", 52, 10, OIIO::TypeDesc::UINT16, [](float x, float, int) { return x / 51.0f; });
  auto r = compile("heightmap \"" + dir + "/ramp.png\" size 104 mm x 20 mm depth 1.02 mm press 3 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const double expected = 3.0 * 1.02e-3 / (51 * 2e-3);
  const auto& f = field_of(r);
  for (std::size_t i = 0; i < f.force_x_N.size(); ++i) {
    ASSERT_NEAR(f.force_x_N[i], -expected, 1e-6) << i;
    ASSERT_NEAR(f.force_y_N[i], 0.0, 1e-9) << i;
  }
  // The force is computed, not targeted, and reported with the roughness the map predicts for it.
  EXPECT_NEAR(r.program->max_lateral_force_N, expected, 1e-6);
  EXPECT_NEAR(r.program->roughness, roughness_for(expected), 1e-6);
  EXPECT_EQ(test::provenance(*r.program, "texture.press").value_si, 3.0);
  EXPECT_DOUBLE_EQ(test::provenance(*r.program, "texture.depth").value_si, 1.02e-3);
  EXPECT_EQ(test::codes(r, compiler::Severity::Error).size(), 0u);  // no E0308 "texture with no force"

  // Doubling the press doubles the force; the same image inverted pushes the other way.
  auto twice = compile("heightmap \"" + dir + "/ramp.png\" size 104 mm x 20 mm depth 1.02 mm press 6 N invert");
  ASSERT_TRUE(twice.ok());
  EXPECT_NEAR(field_of(twice).force_x_N[5 * 52 + 20], 2 * expected, 1e-6);
}

TEST(Heightmap, StylusForceAboveTheDeviceIsRefused) {
  auto dir = test::temp_dir("stylus-strong");
  write_image(dir + "/ramp.png", 10, 10, OIIO::TypeDesc::UINT8, [](float x, float, int) { return x / 9.0f; });
  // Slope 9 mm / 9 mm = 1: 50 N of press gives 50 N, above the sim's 10 N.
  auto r = compile("heightmap \"" + dir + "/ramp.png\" size 10 mm depth 9 mm press 50 N");
  EXPECT_EQ(first_error(r), "E0310");
  EXPECT_NE(message_of(r).find("lower press or depth"), std::string::npos) << message_of(r);
}

TEST(Heightmap, StylusConflictsAndHalves) {
  const std::string img = "heightmap \"library/images/brick.png\" size 90 mm ";
  EXPECT_EQ(first_error(compile(img + "depth 0.5 mm")), "E0407");
  EXPECT_EQ(first_error(compile(img + "press 1 N")), "E0407");
  auto both = compile(img + "amplitude 2 N depth 0.5 mm press 1 N");
  EXPECT_EQ(first_error(both), "E0302");
  EXPECT_NE(message_of(both).find("amplitude 2 N"), std::string::npos);
  EXPECT_NE(message_of(both).find("depth 0.5 mm"), std::string::npos);
  EXPECT_EQ(first_error(compile("roughness 0.5; " + img + "depth 0.5 mm press 1 N")), "E0302");
  EXPECT_EQ(first_error(compile(img + "depth 0 mm press 1 N")), "E0304");
  EXPECT_EQ(first_error(compile(img + "depth 1 mm press 1 N sampling -1 mm")), "E0304");
}

TEST(Heightmap, StylusBeatsAnInheritedRoughnessAndARoughnessBeatsAnInheritedStylus) {
  // library gravel says `roughness coarse`; this file's stylus reading replaces it.
  auto r = compile("like gravel; heightmap \"library/images/brick.png\" size 90 mm depth 0.5 mm press 1 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_GT(std::abs(r.program->max_lateral_force_N - test::expected_force_for_roughness(0.5598)), 0.01);
  for (const auto& pv : r.program->provenance) EXPECT_NE(pv.parameter, "texture.roughness_target");

  // A library entry that reads an image as a stylus relief, then a file that asks for a roughness.
  auto lib = test::temp_dir("stylus-lib");
  // The image inside the library: an entry may not reach outside it (E0314).
  std::filesystem::copy_file(std::string(SANDPAPER_SOURCE_DIR) + "/library/images/brick.png", lib + "/brick.png");
  std::ofstream(lib + "/relief.hmat") << "heightmap \"brick.png\" size 90 mm depth 0.5 mm press 1 N\n";
  compiler::CompileOptions o;
  o.library_dir = lib;
  o.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
  compiler::Compiler c(o);
  auto inherited = c.compile_text("like relief");
  ASSERT_TRUE(inherited.ok()) << compiler::format_diagnostics(inherited.diagnostics);
  EXPECT_EQ(test::provenance(*inherited.program, "texture.press").layer, "representative");
  auto targeted = c.compile_text("like relief; roughness 0.5");
  ASSERT_TRUE(targeted.ok()) << compiler::format_diagnostics(targeted.diagnostics);
  EXPECT_NEAR(targeted.program->max_lateral_force_N, test::expected_force_for_roughness(0.5), 1e-9);
  for (const auto& pv : targeted.program->provenance) EXPECT_NE(pv.parameter, "texture.press");
}

TEST(Heightmap, NamedChannel) {
  auto dir = test::temp_dir("channel");
  // R ramps along x, G down the rows, B is flat: `channel G` reads only G.
  write_image(dir + "/rgb.png", 20, 20, OIIO::TypeDesc::UINT8,
              [](float x, float y, int c) { return c == 0 ? x / 19.0f : c == 1 ? y / 19.0f : 0.5f; }, 3);
  auto g = compile("heightmap \"" + dir + "/rgb.png\" size 20 mm channel G amplitude 1 N");
  ASSERT_TRUE(g.ok()) << compiler::format_diagnostics(g.diagnostics);
  EXPECT_NEAR(field_of(g).force_x_N[210], 0.0, 1e-6);
  EXPECT_NEAR(field_of(g).force_y_N[210], 1.0, 1e-4);  // brighter toward the bottom: downhill is +y
  auto red = compile("heightmap \"" + dir + "/rgb.png\" size 20 mm channel \"R\" amplitude 1 N");
  ASSERT_TRUE(red.ok());
  EXPECT_NEAR(field_of(red).force_x_N[210], -1.0, 1e-4);
  EXPECT_NEAR(field_of(red).force_y_N[210], 0.0, 1e-6);

  auto missing = compile("heightmap \"" + dir + "/rgb.png\" size 20 mm channel Z amplitude 1 N");
  EXPECT_EQ(first_error(missing), "E0404");
  EXPECT_NE(message_of(missing).find("its channels are R, G, B"), std::string::npos) << message_of(missing);
  auto lower = compile("heightmap \"" + dir + "/rgb.png\" size 20 mm channel g amplitude 1 N");
  EXPECT_NE(message_of(lower).find("did you mean `channel G`?"), std::string::npos) << message_of(lower);
  // A flat channel of a varied image: no slope.
  EXPECT_EQ(first_error(compile("heightmap \"" + dir + "/rgb.png\" size 20 mm channel B amplitude 1 N")), "E0403");
}

TEST(Heightmap, SamplingResamplesTheGrid) {
  auto dir = test::temp_dir("sampling");
  // 41 x 21 px, grey 0..1 along x over 40 px steps, on 82 mm x 42 mm (2 mm pixels).
  write_image(dir + "/ramp.tif", 41, 21, OIIO::TypeDesc::FLOAT, [](float x, float, int) { return x / 40.0f; });
  const std::string head = "heightmap \"" + dir + "/ramp.tif\" size 82 mm x 42 mm depth 0.8 mm press 3 N ";
  // Slope of the surface: 0.8 mm over 40 x 2 mm, whatever the sampling.
  const double expected = 3.0 * 0.8e-3 / 80e-3;
  for (double s_mm : {0.5, 1.0, 3.0}) {
    std::ostringstream src;
    src << head << "sampling " << s_mm << " mm";
    auto r = compile(src.str());
    ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
    const auto& f = field_of(r);
    EXPECT_EQ(f.nx, static_cast<std::uint32_t>(std::lround(82 / s_mm))) << s_mm;
    EXPECT_EQ(f.ny, static_cast<std::uint32_t>(std::lround(42 / s_mm))) << s_mm;
    EXPECT_NEAR(f.spacing_m[0], 82e-3 / f.nx, 1e-12);
    // Away from the edges (where the resampling filter meets the clamped border) the slope holds.
    std::size_t mid = static_cast<std::size_t>(f.ny / 2) * f.nx + f.nx / 2;
    EXPECT_NEAR(f.force_x_N[mid], -expected, 0.01 * expected) << s_mm;
    EXPECT_NEAR(f.force_y_N[mid], 0.0, 0.01 * expected) << s_mm;
  }
  EXPECT_EQ(first_error(compile(head + "sampling 0.01 mm")), "E0402");  // 8200 x 4200 samples
  EXPECT_EQ(first_error(compile(head + "sampling 20 mm")), "E0402");    // 4 x 2 samples
}

TEST(Heightmap, DepthFilesReadAsHeights) {
  auto dir = test::temp_dir("depthfile");
  // Appendix B: row 0 at the top; values rise down the rows by 5 a row (0..255 over 52 rows), so
  // the surface falls toward +y and the force points to +y.
  schema::ArrayFile a;
  a.width = 12;
  a.height = 52;
  for (int y = 0; y < 52; ++y)
    for (int x = 0; x < 12; ++x) a.values.push_back(static_cast<std::uint8_t>(5 * y));
  schema::write_depth_file(dir + "/slope.depth", a);
  auto r = compile("heightmap \"" + dir + "/slope.depth\" size 12 mm x 52 mm depth 1.02 mm press 2 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  // 1.02 mm over 51 rows of 1 mm: slope 0.02, F = 2 N x 0.02.
  const auto& f = field_of(r);
  for (std::size_t i = 0; i < f.force_y_N.size(); ++i) ASSERT_NEAR(f.force_y_N[i], 0.04, 1e-6) << i;

  std::ofstream(dir + "/short.depth", std::ios::binary) << std::string("\x00\x0a\x00\x0a", 4) << std::string(99, 'a');
  auto wrong = compile("heightmap \"" + dir + "/short.depth\" size 10 mm amplitude 1 N");
  EXPECT_EQ(first_error(wrong), "E0405");
  EXPECT_NE(message_of(wrong).find("103 bytes"), std::string::npos) << message_of(wrong);
  EXPECT_NE(message_of(wrong).find("104 bytes"), std::string::npos) << message_of(wrong);
  EXPECT_EQ(first_error(compile("heightmap \"" + dir + "/none.depth\" size 10 mm amplitude 1 N")), "E0401");
  schema::write_shade_file(dir + "/slope.shade", a);
  EXPECT_EQ(first_error(compile("heightmap \"" + dir + "/slope.shade\" size 10 mm amplitude 1 N")), "E0406");
}

TEST(Heightmap, RealPhotographsCompileAsExamples) {
  for (const char* file : {"examples/brick-relief.hmat", "examples/grass.hmat"}) {
    auto r = test::shipped_compiler().compile_file(file);
    ASSERT_TRUE(r.ok()) << file << "\n" << compiler::format_diagnostics(r.diagnostics);
    EXPECT_GT(r.program->max_lateral_force_N, 0.1) << file;
    EXPECT_NEAR(r.program->roughness, roughness_for(r.program->max_lateral_force_N), 1e-9) << file;
  }
  auto brick = test::shipped_compiler().compile_file("examples/brick-relief.hmat");
  // sampling 0.2 mm over 90 mm: the grid is 450 x 450, not the photograph's 512 x 512.
  EXPECT_EQ(field_of(brick).nx, 450u);
}

// F42: a picture's channel names are the file's bytes. One that is not UTF-8 ("heig" then 0xFF 0xC0,
// the fuzzer's OpenEXR file) went as it was into the program's description, and the reader refused
// the program the compile had just written. Shown with U+FFFD for each bad byte, in the program and
// in diagnostics alike.
TEST(Heightmap, AChannelNameThatIsNotUtf8IsShownWithReplacementCharactersAndTheProgramReadsBack) {
  const std::string dir = test::temp_dir("heightmap-channel-bytes");
  const std::string path = dir + "/channels.exr";
  {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(16, 16, 4, OIIO::TypeDesc::HALF);
    spec.channelnames = {"R", "G", "B", "heig\xff\xc0"};
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    std::vector<float> px(16 * 16 * 4);
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<float>(i % 37) / 37.0f;
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    ASSERT_TRUE(out->close());
  }
  const std::string shown = "heig\xef\xbf\xbd\xef\xbf\xbd";
  auto r = test::shipped_compiler().compile_text("heightmap \"" + path + "\" size 20 mm amplitude 1 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  schema::PatchProgram back;
  ASSERT_NO_THROW(back = schema::deserialize(schema::serialize(*r.program)));
  bool named = false;
  for (const auto& p : back.provenance) named = named || p.stated.find(shown) != std::string::npos;
  EXPECT_TRUE(named) << "no provenance entry names the channel as " << shown;
  // The channels listed by E0404 for a channel the picture lacks.
  const auto d = refusal("heightmap \"" + path + "\" size 20 mm amplitude 1 N channel Z", "E0404");
  EXPECT_NE(d.message.find(shown), std::string::npos) << d.message;
  std::size_t bad = 0;
  EXPECT_TRUE(schema::is_valid_utf8(d.message, bad)) << d.message;
}
