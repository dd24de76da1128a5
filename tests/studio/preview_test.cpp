// `sandpaper preview`'s pictures (catalog/preview.hpp) on every shipped example: the files exist, the
// pictures have the size preview.json states, and a grating's picture repeats at its period.
#include <cmath>
#include <fstream>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sandpaper/catalog/preview.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;

std::vector<fs::path> example_materials() {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(SANDPAPER_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".hmat") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

struct Grey {
  int nx = 0, ny = 0, channels = 0;
  std::vector<unsigned char> pixels;
};

Grey read_png(const fs::path& file) {
  Grey g;
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return g;
  const auto& spec = in->spec();
  g.nx = spec.width;
  g.ny = spec.height;
  g.channels = spec.nchannels;
  g.pixels.resize(static_cast<std::size_t>(g.nx) * g.ny * g.channels);
  if (!in->read_image(0, 0, 0, g.channels, OIIO::TypeDesc::UINT8, g.pixels.data())) g.nx = 0;
  return g;
}

// The lag (pixels, >= 2) of the highest autocorrelation of one row, mean removed: the picture's period.
int dominant_lag(const Grey& g, int row) {
  std::vector<double> v(static_cast<std::size_t>(g.nx));
  double mean = 0;
  for (int x = 0; x < g.nx; ++x) mean += v[x] = g.pixels[(static_cast<std::size_t>(row) * g.nx + x) * g.channels];
  mean /= g.nx;
  for (auto& x : v) x -= mean;
  int best = 0;
  double best_c = -1e300;
  for (int lag = 2; lag < g.nx / 2; ++lag) {
    double c = 0;
    for (int x = 0; x + lag < g.nx; ++x) c += v[x] * v[x + lag];
    c /= g.nx - lag;
    if (c > best_c * 1.05) {  // the first of near-equal peaks: the period, not a multiple of it
      best_c = c;
      best = lag;
    }
  }
  return best;
}

TEST(Preview, EveryExampleGetsItsPicturesAtTheStatedSize) {
  const auto examples = example_materials();
  ASSERT_GE(examples.size(), 10u);
  int gratings = 0;
  for (const auto& file : examples) {
    SCOPED_TRACE(file.string());
    const auto r = test::shipped_compiler().compile_file(file);
    ASSERT_TRUE(r.ok());
    const fs::path dir = fs::path(test::temp_dir("preview")) / file.stem();
    const auto written = catalog::write_preview(*r.program, dir, 256);
    const auto& s = written.summary;
    std::ifstream json(dir / "preview.json");
    EXPECT_EQ(nlohmann::json::parse(json), s);
    std::ifstream svg(dir / "scan.svg");
    std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("lateral force (N)"), std::string::npos);
    EXPECT_NE(text.find("(mm)"), std::string::npos);
    EXPECT_NE(text.find("<style>"), std::string::npos);  // stands alone
    if (!s.contains("pixels")) {
      EXPECT_FALSE(s["left_out"].empty()) << "no picture, and no reason given";
      continue;
    }
    const int nx = s["pixels"][0], ny = s["pixels"][1];
    EXPECT_LE(std::max(nx, ny), 256);
    const Grey height = read_png(dir / "height.png"), field = read_png(dir / "field.png");
    EXPECT_EQ(height.nx, nx);
    EXPECT_EQ(height.ny, ny);
    EXPECT_EQ(height.channels, 1);
    EXPECT_EQ(field.nx, nx);
    EXPECT_EQ(field.channels, 3);
    EXPECT_NEAR(s["pixel_mm"].get<double>() * nx, s["window_mm"][0].get<double>(), 1e-9);
    const double bar = s["scale_bar_mm"];
    EXPECT_GT(bar, 0);
    EXPECT_LE(bar, s["window_mm"][0].get<double>() / 2);

    // A grating across x: its picture's rows repeat at the period.
    for (const auto& t : r.program->terms)
      if (const auto* g = std::get_if<schema::GratingTerm>(&t); g && g->orientation_rad == 0 && r.program->terms.size() == 1) {
        const double px_mm = s["pixel_mm"];
        const double period_px = g->period_m * 1e3 / px_mm;
        if (period_px < 4 || period_px > nx / 3.0) continue;
        ++gratings;
        const int lag = dominant_lag(height, ny / 4);  // above the scale bar
        EXPECT_NEAR(lag * px_mm, g->period_m * 1e3, 1.5 * px_mm) << "lag " << lag << " px";
      }
  }
  EXPECT_GE(gratings, 1) << "no example is a plain grating whose period the picture could show";
}

// The force-field picture shows what a still hand feels at each place: friction's adhesion point
// sits wherever the contact last stuck, so it is left out and said to be, not drawn as a spring to
// the picture's centre (which drew 22-29 N on a 10 N device).
TEST(Preview, TheForceFieldLeavesOutFrictionAndSaysSo) {
  const auto plain = test::shipped_compiler().compile_text("roughness 0.8");
  const auto rubbed = test::shipped_compiler().compile_text("roughness 0.8; physics Friction static 0.6 kinetic 0.4 press 1 N");
  ASSERT_TRUE(plain.ok() && rubbed.ok()) << compiler::format_diagnostics(rubbed.diagnostics);
  const auto a = catalog::write_preview(*plain.program, fs::path(test::temp_dir("field-plain")), 256, 8).summary;
  const auto b = catalog::write_preview(*rubbed.program, fs::path(test::temp_dir("field-friction")), 256, 8).summary;
  EXPECT_DOUBLE_EQ(b["field_max_N"].get<double>(), a["field_max_N"].get<double>());
  // The grating's own force, as far as the picture's pixels find its ridges' peaks (not 22-29 N).
  EXPECT_LE(b["field_max_N"].get<double>(), plain.program->max_lateral_force_N * (1 + 1e-6));
  EXPECT_GT(b["field_max_N"].get<double>(), 0.9 * plain.program->max_lateral_force_N);
  ASSERT_EQ(b["field_left_out"].size(), 1u);
  EXPECT_NE(b["field_left_out"][0].get<std::string>().find("friction"), std::string::npos) << b["field_left_out"];
  EXPECT_TRUE(a["field_left_out"].empty());
}

// A field stronger than the device gives is drawn at the device's limit, as the servo loop plays it:
// 200 N/m at the 95 mm patch's corner (67 mm out) is 13.4 N, and the sim gives 10 N.
TEST(Preview, TheForceFieldNeverShowsMoreThanTheDeviceGives) {
  const auto r = test::shipped_compiler().compile_text("spring 200 N/m");
  ASSERT_TRUE(r.ok());
  ASSERT_DOUBLE_EQ(r.program->command.max_force_N, 10.0);
  const auto s = catalog::write_preview(*r.program, fs::path(test::temp_dir("field-spring")), 256, 8).summary;
  EXPECT_DOUBLE_EQ(s["field_max_N"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(s["field_limit_N"].get<double>(), 10.0);
  const auto window = s["window_mm"];
  ASSERT_GT(std::hypot(window[0].get<double>(), window[1].get<double>()) / 2 * 1e-3 * 200, 10.0)
      << "the window must reach past the 10 N circle (50 mm) for the limit to show";
}

TEST(Preview, TheScaleBarIsDrawnAtItsLength) {
  catalog::Image im;
  im.nx = 400;
  im.ny = 100;
  im.channels = 1;
  im.pixel_m = 0.1e-3;  // 40 mm wide: a 10 mm bar, 100 px
  im.pixels.assign(400 * 100, 128);
  EXPECT_DOUBLE_EQ(catalog::draw_scale_bar(im), 10);
  int black = 0;
  const int row = 100 - 8 - 3;  // inside the bar (margin 8, height 6 at scale 2)
  for (int x = 0; x < 400; ++x) black += im.pixels[static_cast<std::size_t>(row) * 400 + x] == 0;
  EXPECT_EQ(black, 100);
}

}  // namespace
}  // namespace sandpaper
