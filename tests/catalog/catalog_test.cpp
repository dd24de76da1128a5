// The catalog's renderer, force plot and pages (curation/catalog/): the picture is the shading of the
// compiled field lit from the upper left, the plot is the evaluator's force, the index lists every
// entry with its compiled roughness, and a failed run leaves the previous catalog as it was.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <random>
#include <sys/stat.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/catalog/entry_page.hpp"
#include "sandpaper/catalog/html.hpp"
#include "sandpaper/catalog/index_page.hpp"
#include "sandpaper/catalog/plot.hpp"
#include "sandpaper/catalog/render.hpp"
#include "sandpaper/compiler/array_export.hpp"
#include "sandpaper/compiler/textures.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;

schema::PatchProgram with_terms(std::vector<schema::Term> terms) {
  schema::PatchProgram p;
  p.name = "test";
  p.terms = std::move(terms);
  return p;
}

schema::PatchProgram grating(double orientation_rad) {
  return with_terms({compiler::make_grating(2.5e-3, 0.5, orientation_rad, 2.5e-3 * compiler::kSeedSigmaPerPeriod, 1.5)});
}

// Luminance as the PNG shows it: 255 = white (the .shade array has 0 = white).
int lum(const catalog::Picture& pic, int col, int row) {
  return 255 - pic.shade.values[static_cast<std::size_t>(row) * pic.nx + col];
}

// The flat surface under a light at elevation 45 deg: 255 sin 45, rounded as the shading rounds.
const int kFlat = 255 - static_cast<int>(std::floor(255 * (1 - std::sqrt(0.5)) + 0.5));

std::string read(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The JSON inside one of the index's data files, checked to be a string literal in that statement.
nlohmann::json json_of_script(const std::string& script, const std::string& prefix, const std::string& suffix) {
  EXPECT_EQ(script.rfind(prefix, 0), 0u) << script.substr(0, 120);
  EXPECT_TRUE(script.size() > prefix.size() + suffix.size() && script.substr(script.size() - suffix.size()) == suffix);
  std::string text;  // the string literal's value: the JSON
  for (std::size_t i = prefix.size(); i + suffix.size() < script.size(); ++i) {
    if (script[i] == '\'') ADD_FAILURE() << "an unescaped ' ends the string literal at " << i;
    text += script[i] == '\\' ? script[++i] : script[i];
  }
  return nlohmann::json::parse(text);
}

// The entries of the index's data files (catalog-data.js and catalog-data/part-*.js, by relative
// path in `files`) in index_data's form, with the fields that the index shows or filters by. Checks
// that the head's counts and spans agree with the parts.
nlohmann::json entries_of_index(const std::map<std::string, std::string>& files) {
  const auto head = json_of_script(files.at(catalog::kIndexDataFile), "window.sandpaperCatalog = JSON.parse('", "');\n");
  EXPECT_EQ(head["format"], 3);
  nlohmann::json entries = nlohmann::json::array();
  std::vector<int> counts(head["families"].size(), 0);
  std::size_t unfiled = 0;
  for (std::size_t k = 0; k < head["parts"].size(); ++k) {
    const auto d = json_of_script(files.at(catalog::index_part_file(k)),
                                  "(window.sandpaperCatalogParts = window.sandpaperCatalogParts || []).push(JSON.parse('", "'));\n");
    EXPECT_EQ(d["format"], 3);
    EXPECT_EQ(d["part"], k);
    EXPECT_EQ(d["name"].size(), head["parts"][k]["rows"]);
    EXPECT_EQ(d["name"].front(), head["parts"][k]["first"]);
    EXPECT_EQ(d["name"].back(), head["parts"][k]["last"]);
    std::set<int> no_thumbnail(d["no_thumbnail"].begin(), d["no_thumbnail"].end());
    for (std::size_t i = 0; i < d["name"].size(); ++i) {
      const std::string name = d["name"][i], key = std::to_string(i);
      const int f = d["family"][i];
      if (f < 0) ++unfiled;
      else ++counts.at(static_cast<std::size_t>(f));
      entries.push_back({{"name", name},
                         {"family", f < 0 ? "" : head["families"][static_cast<std::size_t>(f)]["id"]},
                         {"family_title", f < 0 ? "" : head["families"][static_cast<std::size_t>(f)]["title"]},
                         {"aliases", d["aliases"].value(key, nlohmann::json::array())},
                         {"describes", d["describes"][i]},
                         {"roughness", d["roughness"][i]},
                         {"max_lateral_force_N", d["force_N"][i]},
                         {"period_m", d["period_m"][i]},
                         {"kind", d["kind"][i]},
                         {"source_kinds", d["sources"][i]},
                         {"root", d["root"].value(key, "")},
                         {"licence", d["licence"][i]},
                         {"deprecated_by", d["deprecated_by"].value(key, "")},
                         {"page", "entries/" + name + ".html"},
                         {"thumbnail", no_thumbnail.count(static_cast<int>(i)) ? nlohmann::json(nullptr)
                                                                               : nlohmann::json("entries/" + name + "-thumb.png")}});
    }
  }
  EXPECT_EQ(entries.size(), head["entries"]);
  EXPECT_EQ(unfiled, head["unfiled"]);
  for (std::size_t f = 0; f < counts.size(); ++f) EXPECT_EQ(counts[f], head["families"][f]["count"]) << "family " << f;
  EXPECT_FALSE(files.count(catalog::index_part_file(head["parts"].size()))) << "a part past the last";
  return entries;
}

// The index's data files of a catalog folder, by relative path.
std::map<std::string, std::string> index_files_in(const fs::path& dir) {
  std::map<std::string, std::string> files{{catalog::kIndexDataFile, read(dir / catalog::kIndexDataFile)}};
  if (fs::is_directory(dir / catalog::kIndexPartsFolder))
    for (const auto& f : fs::directory_iterator(dir / catalog::kIndexPartsFolder))
      files[std::string(catalog::kIndexPartsFolder) + "/" + f.path().filename().string()] = read(f.path());
  return files;
}

TEST(CatalogPicture, GratingAcrossXVariesAlongXOnlyAndFacesTheLightOnItsRisingEdge) {
  const auto p = grating(0);
  const auto pic = catalog::render_picture(p);
  ASSERT_FALSE(pic.empty());
  ASSERT_EQ(pic.nx, 512);
  // 64 pixels a period: 8 periods of 2.5 mm.
  EXPECT_NEAR(pic.window_m[0], 20e-3, 1e-9);
  int lo = 255, hi = 0;
  for (int col = 0; col < pic.nx; ++col) {
    for (int row = 1; row < pic.ny; ++row) ASSERT_EQ(lum(pic, col, row), lum(pic, col, 0)) << "column " << col;
    lo = std::min(lo, lum(pic, col, 0));
    hi = std::max(hi, lum(pic, col, 0));
  }
  EXPECT_GT(hi - lo, 100);
  // The rising edge (h increasing with x, so F = -k dh/dx < 0) faces left, toward the light: brighter
  // than the flat (at the steepest slope, drawn at 45 deg: 255 (0.5 sin 45 + sin 45) = 218, against 180);
  // the falling edge darker.
  runtime::PatchEvaluator eval(p);
  int rising = 0, falling = 0;
  for (int col = 0; col < pic.nx; ++col) {
    runtime::HandState h;
    h.position_m = {-0.5 * pic.window_m[0] + (col + 0.5) * pic.pixel_m, 0};
    const double f = eval.force_rt(h, 0).x;
    if (f < -0.9 * 1.5) {
      EXPECT_GT(lum(pic, col, 0), kFlat + 30) << "column " << col;
      ++rising;
    }
    if (f > 0.9 * 1.5) {
      EXPECT_LT(lum(pic, col, 0), kFlat - 30) << "column " << col;
      ++falling;
    }
    if (std::abs(f) < 1e-6) {
      EXPECT_NEAR(lum(pic, col, 0), kFlat, 1) << "column " << col;
    }
  }
  EXPECT_GE(rising, 8);
  EXPECT_GE(falling, 8);
}

TEST(CatalogPicture, GratingAcrossYVariesAlongYOnlyAndItsEdgeFacingUpIsBrighter) {
  const auto p = grating(std::numbers::pi / 2);
  const auto pic = catalog::render_picture(p);
  ASSERT_FALSE(pic.empty());
  for (int row = 0; row < pic.ny; ++row)
    for (int col = 1; col < pic.nx; ++col) ASSERT_EQ(lum(pic, col, row), lum(pic, 0, row)) << "row " << row;
  runtime::PatchEvaluator eval(p);
  for (int row = 0; row < pic.ny; ++row) {
    runtime::HandState h;
    h.position_m = {0, 0.5 * pic.window_m[1] - (row + 0.5) * pic.pixel_m};
    const double f = eval.force_rt(h, 0).y;
    // F_y > 0: h falls toward +y, the slope faces up (toward the light).
    if (f > 0.9 * 1.5) {
      EXPECT_GT(lum(pic, 0, row), kFlat + 30) << "row " << row;
    }
    if (f < -0.9 * 1.5) {
      EXPECT_LT(lum(pic, 0, row), kFlat - 30) << "row " << row;
    }
  }
}

TEST(CatalogPicture, ShadingIsTheArrayExportsAndTheUpperLeftSlopeIsBrightest) {
  // A slope facing up-left (h rising to the right and falling upward), one facing down-right.
  const std::vector<double> sx{1, -1, 0}, sy{-1, 1, 0};
  const auto a = compiler::shade_slopes(3, 1, sx, sy, 1.0);
  EXPECT_LT(a.values[0], a.values[2]);  // 0 = white: the lit slope is whiter than the flat
  EXPECT_GT(a.values[1], a.values[2]);
  EXPECT_EQ(255 - a.values[2], kFlat);
  // shade_relief now shades through shade_slopes: a ramp rising to the right faces left and is lit.
  compiler::HeightFieldImage img;
  img.nx = 4;
  img.ny = 2;
  img.values = {0, 1, 2, 3, 0, 1, 2, 3};
  const auto r = compiler::shade_relief(img, 1, 1, std::nullopt);
  EXPECT_LT(r.values[1], a.values[2]);
}

TEST(CatalogPicture, SpringIsDrawnAsItsPotentialBowlAndADamperNotAtAll) {
  schema::SpringTerm s;
  s.stiffness_N_per_m = 100;
  const auto pic = catalog::render_picture(with_terms({s}));
  ASSERT_FALSE(pic.empty());
  EXPECT_NE(pic.caption.find("spring"), std::string::npos) << pic.caption;
  EXPECT_NEAR(pic.window_m[0], 0.095, 1e-9);  // no texture: the whole patch
  const int mid = pic.ny / 2;
  EXPECT_GT(lum(pic, pic.nx - 2, mid), lum(pic, 1, mid));  // the bowl's right wall faces left, lit
  EXPECT_LT(lum(pic, pic.nx / 2, 1), lum(pic, pic.nx / 2, pic.ny - 2));  // its bottom wall faces up, lit
  EXPECT_NEAR(lum(pic, pic.nx / 2, mid), kFlat, 2);

  schema::DamperTerm d;
  d.damping_Ns_per_m = 2;
  const auto none = catalog::render_picture(with_terms({d}));
  EXPECT_TRUE(none.empty());
  ASSERT_EQ(none.left_out.size(), 1u);
  EXPECT_NE(none.left_out[0].find("velocity"), std::string::npos);
}

// The light falls across every ridge: within 45 deg of each ridge normal, as near the thesis' 135 deg
// (upper left) as that allows, ties toward 90. Worked by hand: a normal at 0 or 90 deg is 45 deg from
// 135 and keeps it; at 45 deg (a twill) 135 is 90 deg off, and 90 and 180 are the nearest within
// 45 deg, 90 by the tie; at 65 deg the normal's other sense, 245, is 110 from 135, the normal 70:
// 110 is 45 from 65; gratings at 0 and 60 deg need [135, 225] and [195, 285] (or the opposite
// senses), nearest 195. A lit picture of a 45 deg grating differs from its walls' mirror image.
TEST(CatalogPicture, TheLightFallsAcrossEveryRidge) {
  const double deg = std::numbers::pi / 180;
  EXPECT_EQ(catalog::light_azimuth_deg(grating(0)), 135);
  EXPECT_EQ(catalog::light_azimuth_deg(grating(90 * deg)), 135);
  EXPECT_EQ(catalog::light_azimuth_deg(grating(45 * deg)), 90);
  EXPECT_EQ(catalog::light_azimuth_deg(grating(65 * deg)), 110);
  EXPECT_EQ(catalog::light_azimuth_deg(grating(-45 * deg)), 135);
  auto crossed = grating(0);
  crossed.terms.push_back(grating(60 * deg).terms.front());
  EXPECT_EQ(catalog::light_azimuth_deg(crossed), 195);
  schema::DamperTerm d;
  d.damping_Ns_per_m = 1;
  EXPECT_EQ(catalog::light_azimuth_deg(with_terms({d})), 135);
  // A 45 deg grating: one wall lit, the other shaded, so along the normal the picture is not
  // symmetric under u -> -u about a ridge as the two walls' equal shading made it.
  const auto pic = catalog::render_picture(grating(45 * deg));
  ASSERT_FALSE(pic.empty());
  EXPECT_EQ(pic.light_azimuth_deg, 90);
  int lo = 255, hi = 0;
  for (int col = 0; col < pic.nx; ++col) lo = std::min(lo, lum(pic, col, pic.ny / 2)), hi = std::max(hi, lum(pic, col, pic.ny / 2));
  EXPECT_GT(hi, kFlat + 30);
  EXPECT_LT(lo, kFlat - 30);
  EXPECT_NE(pic.caption.find("across the ridges (azimuth 90"), std::string::npos) << pic.caption;
}

// The strongest frequency (cycles across the picture, 1..side/2) of a thumbnail's mean row, and
// its share of the row's power (mean removed): 0 when the row is flat.
std::pair<int, double> dominant_cycles(const catalog::Picture& pic) {
  const int n = pic.nx;
  std::vector<double> row(n, 0.0);
  for (int col = 0; col < n; ++col) {
    for (int r = 0; r < pic.ny; ++r) row[col] += pic.shade.values[static_cast<std::size_t>(r) * n + col];
    row[col] /= pic.ny;
  }
  double mean = 0;
  for (double v : row) mean += v / n;
  double total = 0, best = 0;
  int best_k = 0;
  for (int k = 1; k <= n / 2; ++k) {
    double re = 0, im = 0;
    for (int i = 0; i < n; ++i) {
      re += (row[i] - mean) * std::cos(2 * std::numbers::pi * k * i / n);
      im -= (row[i] - mean) * std::sin(2 * std::numbers::pi * k * i / n);
    }
    const double p = re * re + im * im;
    total += p;
    if (p > best) best = p, best_k = k;
  }
  return {best_k, total > 0 ? best / total : 0.0};
}

// Thumbnails share one scale (40 mm across 128 pixels, 0.3125 mm a pixel): a grating's picture must
// show its own period, or none when the period is under two pixels, never a beat between its walls
// and the pixels (pinwale's 1.6 mm looked coarser than corduroy's 3.2 mm). k0 = 40 mm / period.
TEST(CatalogPicture, AThumbnailShowsTheGratingsOwnPeriodOrNoneNeverAnAlias) {
  const auto& c = test::shipped_compiler();
  for (const double period_mm : {0.3, 0.5, 0.55, 0.7, 0.9, 1.1, 1.6, 2.2, 3.2, 5.0}) {
    std::ostringstream text;
    text << "grating period " << period_mm << " mm hill 60%; roughness 0.4";
    const auto r = c.compile_text(text.str());
    ASSERT_TRUE(r.ok()) << text.str();
    const auto pic = catalog::render_picture_window(*r.program, 0.04, 128);
    ASSERT_EQ(pic.nx, 128);
    const double k0 = 40.0 / period_mm;
    const auto [k, share] = dominant_cycles(pic);
    int lo = 255, hi = 0;
    for (auto v : pic.shade.values) lo = std::min<int>(lo, v), hi = std::max<int>(hi, v);
    if (k0 < 64) {  // below the pixels' Nyquist frequency: the period can be drawn, and must be
      EXPECT_NEAR(k, k0, 1.0) << period_mm << " mm: strongest at " << k << " cycles (share " << share << "), expected " << k0;
    } else {
      // Under two pixels a period the walls blur to grey: whatever remains must not be a strong
      // stripe of another period (within 24 grey levels of flat).
      EXPECT_LT(hi - lo, 24) << period_mm << " mm: contrast " << hi - lo << ", strongest at " << k << " cycles (share " << share << ")";
    }
  }
}

TEST(CatalogPlot, ScanIsTheEvaluatorsForceAtEachPoint) {
  const auto p = grating(std::numbers::pi / 4);
  const auto scan = catalog::scan_force(p, 0.01, 0.05, 801);
  EXPECT_EQ(scan.axis, "u");
  ASSERT_EQ(scan.s_m.size(), 801u);
  EXPECT_DOUBLE_EQ(scan.s_m.front(), -0.01);
  EXPECT_DOUBLE_EQ(scan.s_m.back(), 0.01);
  runtime::PatchEvaluator eval(p);
  const glm::dvec2 n{std::cos(std::numbers::pi / 4), std::sin(std::numbers::pi / 4)};
  double peak = 0;
  for (std::size_t i = 0; i < scan.s_m.size(); ++i) {
    runtime::HandState h;
    h.position_m = n * scan.s_m[i];
    const glm::dvec2 f = eval.force_rt(h, 0);
    EXPECT_NEAR(scan.along_N[i], f.x * n.x + f.y * n.y, 1e-12) << i;
    EXPECT_NEAR(scan.across_N[i], 0, 1e-9) << i;  // a grating pushes only along its normal
    peak = std::max(peak, std::abs(scan.along_N[i]));
  }
  EXPECT_NEAR(peak, 1.5, 0.05);
  // A damper acts on the moving hand: -b v along the scan.
  schema::DamperTerm d;
  d.damping_Ns_per_m = 4;
  const auto damped = catalog::scan_force(with_terms({d}), 0.02, 0.05, 11);
  for (double f : damped.along_N) EXPECT_NEAR(f, -4 * 0.05, 1e-12);
}

TEST(CatalogPlot, SvgCurveIsTheScanOnLabelledAxes) {
  const auto scan = catalog::scan_force(grating(0), 0.01, 0.05, 401);
  const std::string svg = catalog::force_plot_svg(scan, "a <title>");
  const auto axes = catalog::plot_axes(scan);
  EXPECT_NE(svg.find("a &lt;title&gt;"), std::string::npos);
  EXPECT_NE(svg.find(">position along the grating normal, u (mm)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">lateral force (N)</text>"), std::string::npos);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("class=\"force-along\" fill=\"none\" points=\"([^\"]*)\"")));
  // The drawn points are samples of the scan, in order, from the first to the last; every sample
  // left out lies within kPlotTolerancePx of the line drawn.
  std::istringstream pts(m[1].str());
  std::string pt;
  std::vector<std::size_t> drawn;  // sample indices
  std::size_t i = 0;
  while (pts >> pt) {
    const auto comma = pt.find(',');
    const double x = std::stod(pt.substr(0, comma)), y = std::stod(pt.substr(comma + 1));
    while (i < scan.s_m.size() && std::abs(axes.x_px(scan.s_m[i] * 1e3) - x) > 0.006) ++i;
    ASSERT_LT(i, scan.s_m.size()) << "point " << pt << " is not a sample";
    EXPECT_NEAR(y, axes.y_px(scan.along_N[i]), 0.006);
    drawn.push_back(i++);
  }
  ASSERT_GE(drawn.size(), 2u);
  EXPECT_EQ(drawn.front(), 0u);
  EXPECT_EQ(drawn.back(), scan.s_m.size() - 1);
  EXPECT_LT(drawn.size(), scan.s_m.size() / 2) << "a smooth grating needs far fewer points than samples";
  for (std::size_t k = 0; k + 1 < drawn.size(); ++k) {
    const double x0 = axes.x_px(scan.s_m[drawn[k]] * 1e3), y0 = axes.y_px(scan.along_N[drawn[k]]);
    const double x1 = axes.x_px(scan.s_m[drawn[k + 1]] * 1e3), y1 = axes.y_px(scan.along_N[drawn[k + 1]]);
    for (std::size_t j = drawn[k] + 1; j < drawn[k + 1]; ++j) {
      const double x = axes.x_px(scan.s_m[j] * 1e3), y = axes.y_px(scan.along_N[j]);
      const double d = std::abs((y1 - y0) * (x - x0) - (x1 - x0) * (y - y0)) / std::hypot(x1 - x0, y1 - y0);
      EXPECT_LE(d, catalog::kPlotTolerancePx + 1e-9) << "sample " << j;
    }
  }
  // The y range holds the curve; the x range is the scan.
  EXPECT_DOUBLE_EQ(axes.x_min_mm, -10);
  EXPECT_DOUBLE_EQ(axes.x_max_mm, 10);
  for (double f : scan.along_N) EXPECT_LE(std::abs(f), axes.y_max_N);
  EXPECT_EQ(catalog::nice_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(catalog::nice_ticks(-1.5, 1.5, 6), (std::vector<double>{-1.5, -1, -0.5, 0, 0.5, 1, 1.5}));
}

TEST(CatalogHtml, EscapesTextAndKeepsEntriesOutOfTheIndexPage) {
  EXPECT_EQ(catalog::html_escape("<a href=\"x\">&'"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;");
  EXPECT_EQ(catalog::url_segment("a b/c"), "a%20b%2Fc");
  catalog::IndexRow r;
  r.name = "x";
  r.describes = "</script><script>alert(1)</script> & <!-- it's 3 \xC2\xB5m \\ \"x\" \xE2\x80\xA8";
  r.page = "entries/x.html";
  const auto files = catalog::index_files(catalog::index_data({}, {r}));
  const std::string html = files.at("index.html");
  // The page holds no entry: the rows are made in the browser from the data files, head first.
  EXPECT_EQ(html.find("alert"), std::string::npos);
  EXPECT_EQ(html.find("<tr data-name"), std::string::npos);
  const auto head_tag = html.find("<script src=\"catalog-data.js\"></script>\n<script src=\"catalog-data/part-00000.js\"></script>");
  EXPECT_NE(head_tag, std::string::npos);
  EXPECT_LT(head_tag, html.find("<script src=\"assets/index.js\">"));
  EXPECT_NE(html.find("<noscript><p"), std::string::npos);
  for (const auto& name : {std::string(catalog::kIndexDataFile), catalog::index_part_file(0)}) {
    const std::string& script = files.at(name);
    EXPECT_EQ(script.find("<"), std::string::npos) << name << ": the data could be inlined in a <script> element";
    EXPECT_TRUE(std::all_of(script.begin(), script.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; }))
        << name << ": ASCII, whatever encoding the browser assumes";
  }
  EXPECT_EQ(entries_of_index(files)[0]["describes"], r.describes);
}

TEST(CatalogIndex, DataFileKeepsEveryFieldTheIndexShowsAndFiltersBy) {
  compiler::LibraryManifest manifest;
  manifest.name = "m";
  manifest.version = "1.2.3";
  manifest.families = {{"cloth", "Cloth", "woven things", false}, {"empty", "Empty", "", false}};
  std::vector<catalog::IndexRow> rows(4);
  rows[0].name = "rib";
  rows[0].family = "cloth";
  rows[0].roughness = 0.123456789;
  rows[0].aliases = {"ribbed", "rep"};
  rows[0].describes = "a rib";
  rows[0].max_lateral_force_N = 1.23456789;
  rows[0].period_m = 0.0016;
  rows[0].kind = "grating|grating+damper";
  rows[0].source_kinds = 1u << static_cast<unsigned>(compiler::SourceKind::Measurement) |
                         1u << static_cast<unsigned>(compiler::SourceKind::ByEar);
  rows[0].root = "lab";
  rows[1].name = "old-rib";
  rows[1].family = "cloth";
  rows[1].roughness = 0.5;
  rows[1].deprecated_by = "rib";
  rows[2].name = "spring";  // no family, no texture, no picture
  rows[3].name = "stone";   // a family the manifest lacks
  rows[3].family = "rocks";
  rows[3].roughness = 1.25;
  for (auto& r : rows) {
    r.page = "entries/" + r.name + ".html";
    if (r.name != "spring") r.thumbnail = "entries/" + r.name + "-thumb.png";
    r.licence = r.name == "stone" ? "CC-BY-SA-4.0 AND CC0-1.0" : "CC0-1.0";
  }
  const auto data = catalog::index_data(manifest, rows);
  auto want = data["entries"];
  want[0]["roughness"] = 0.123457;  // six significant digits
  want[0]["max_lateral_force_N"] = 1.23457;
  const auto files = catalog::index_files(data);
  EXPECT_EQ(entries_of_index(files), want);
  const std::string html = files.at("index.html");
  for (const char* s : {"<option value=\"cloth\">Cloth (2)</option>", "<option value=\"empty\">Empty (0)</option>",
                        "<option value=\"rocks\">rocks (1)</option>", "<option value=\"(none)\">no family</option>",
                        "<p id=\"count\" aria-live=\"polite\">4 entries</p>", "Version 1.2.3",
                        // The filters by licence (filled from the data), by source kind, and the order.
                        "<select id=\"licence\" name=\"licence\">", "<option value=\"measurement\">measured</option>",
                        "<option value=\"by-ear\">by ear</option>", "<option value=\"roughness\">roughness, smoothest first</option>",
                        "<a id=\"compare-go\" href=\"assets/compare.html\">"})
    EXPECT_NE(html.find(s), std::string::npos) << s;
  // The page finds pages and thumbnails by name; a row that says otherwise cannot be written.
  rows[2].page = "elsewhere/spring.html";
  EXPECT_THROW(catalog::index_files(catalog::index_data(manifest, rows)), std::invalid_argument);
}

TEST(CatalogIndex, PatchingRowsGivesTheSameFilesAsWritingThemWhole) {
  // The in-place update puts changed rows into the index's files (patch_index); it must give exactly
  // what index_files gives for the whole changed list, and with sorted names read only the parts
  // that hold the changed rows. 5,000 rows make three parts; "e10" sorts before "e2", so the names
  // written plainly are not in order (every part may be read), zero-padded they are.
  compiler::LibraryManifest manifest;
  manifest.name = "patch \"test\" <lib>";
  manifest.version = "1.2.3";
  manifest.families = {{"cloth", "Cloth", "", false}, {"stone", "Stone <hard>", "", false}};
  for (const bool padded : {false, true}) {
    SCOPED_TRACE(padded ? "sorted names" : "names out of order");
    std::mt19937 rng(7);
    auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
    const char* words[] = {"ribbed", "caf\xC3\xA9 <b>", "quote \" and \\ slash", "it's", "\xF0\x9F\x98\x80 grin", "plain"};
    auto name_of = [&](int i) {
      char buf[16];
      std::snprintf(buf, sizeof buf, padded ? "e%05d" : "e%d", i);
      return std::string(buf);
    };
    auto random_row = [&](const std::string& name) {
      catalog::IndexRow r;
      r.name = name;
      const int f = pick(4);
      r.family = f == 0 ? "" : f == 1 ? "cloth" : f == 2 ? "stone" : "extra";  // "extra": not in the manifest
      r.describes = std::string(words[pick(6)]) + " " + std::to_string(pick(1000));
      if (pick(3) == 0) r.aliases = {name + "-a", std::string(words[pick(6)])};
      if (pick(5) == 0) r.deprecated_by = "e" + std::to_string(pick(300));
      if (pick(4) != 0) r.roughness = pick(1000) / 997.0;
      r.page = "entries/" + name + ".html";
      if (pick(3) != 0) r.thumbnail = "entries/" + name + "-thumb.png";
      return r;
    };
    constexpr int kRows = 5000;
    std::vector<catalog::IndexRow> rows;
    for (int i = 0; i < kRows; ++i) rows.push_back(random_row(name_of(i)));
    rows[5].family = rows[6].family = "extra";  // the extra family keeps members below
    int patched = 0;
    for (int round = 0; round < 40; ++round) {
      const auto before = catalog::index_files(manifest, rows);
      ASSERT_EQ(before.size(), 2u + 3u);
      std::vector<catalog::IndexRow> changed;
      std::set<std::string> parts_changed;
      for (int k = 0; k < 1 + pick(5); ++k) {
        const int i = 10 + pick(kRows - 10);
        auto r = random_row(rows[static_cast<std::size_t>(i)].name);
        if (r.family == "extra") r.family = "cloth";  // keep the families list as it is
        rows[static_cast<std::size_t>(i)] = r;
        changed.push_back(r);
        parts_changed.insert(catalog::index_part_file(static_cast<std::size_t>(i) / catalog::kIndexPartRows));
      }
      std::set<std::string> read;
      const auto p = catalog::patch_index(
          [&](const std::string& f) -> std::optional<std::string> {
            read.insert(f);
            const auto it = before.find(f);
            return it == before.end() ? std::nullopt : std::optional<std::string>(it->second);
          },
          manifest, changed);
      ASSERT_TRUE(p.has_value()) << "round " << round;
      const auto after = catalog::index_files(manifest, rows);
      for (const auto& [f, text] : after) {
        if (p->count(f)) EXPECT_TRUE(p->at(f) == text) << "round " << round << ": " << f;
        else EXPECT_TRUE(before.at(f) == text) << "round " << round << ": " << f << " changed but was not patched";
      }
      for (const auto& [f, text] : *p) EXPECT_TRUE(after.count(f)) << f;
      if (padded) {
        parts_changed.insert(catalog::kIndexDataFile);
        EXPECT_EQ(read, parts_changed) << "round " << round << ": sorted names, only the changed rows' parts are read";
      }
      ++patched;
    }
    EXPECT_EQ(patched, 40);
    // What it cannot do, it declines (the files are written whole then).
    const auto now = catalog::index_files(manifest, rows);
    const auto from = [&](std::map<std::string, std::string> files) {
      return [files](const std::string& f) -> std::optional<std::string> {
        const auto it = files.find(f);
        return it == files.end() ? std::nullopt : std::optional<std::string>(it->second);
      };
    };
    auto stranger = random_row("not-there");
    EXPECT_FALSE(catalog::patch_index(from(now), manifest, {stranger}).has_value());
    auto moved = rows[5];
    moved.family = "new-family";
    EXPECT_FALSE(catalog::patch_index(from(now), manifest, {moved}).has_value());
    // A family only the manifest lacks, whose one member leaves it, would drop out of the list.
    std::vector<catalog::IndexRow> few(rows.begin(), rows.begin() + 3);
    few[0].family = "solo";
    few[1].family = few[2].family = "cloth";
    auto left = few[0];
    left.family = "cloth";
    EXPECT_FALSE(catalog::patch_index(from(catalog::index_files(manifest, few)), manifest, {left}).has_value());
    auto other = now;
    other[catalog::kIndexDataFile] = "window.x = 1;\n";
    EXPECT_FALSE(catalog::patch_index(from(other), manifest, {rows[20]}).has_value());
    other = now;
    other.erase(catalog::index_part_file(0));
    EXPECT_FALSE(catalog::patch_index(from(other), manifest, {rows[20]}).has_value()) << "a part missing";
    other = now;
    other[catalog::index_part_file(1)] = now.at(catalog::index_part_file(0));
    EXPECT_FALSE(catalog::patch_index(from(other), manifest, {rows[2100]}).has_value()) << "a part in another's place";
    // A head file edited into a deep nest is declined, not followed down the stack.
    other[catalog::kIndexDataFile] = "window.sandpaperCatalog = JSON.parse('{\"entries\":" + std::string(1000000, '[') + "');\n";
    EXPECT_FALSE(catalog::patch_index(from(other), manifest, {rows[20]}).has_value());
    // A count that is not a whole number is not this format (a float the reader took as an int would
    // be undefined past int's range: fuzz/regressions/catalog_data/).
    other = now;
    {
      std::string& head = other[catalog::kIndexDataFile];
      const auto at = head.find("\"count\":");
      ASSERT_NE(at, std::string::npos);
      head.insert(head.find_first_not_of("0123456789", at + 8), ".5");
    }
    EXPECT_FALSE(catalog::patch_index(from(other), manifest, {rows[20]}).has_value()) << "a count of N.5";
    auto renamed = manifest;
    renamed.version = "1.2.4";
    EXPECT_FALSE(catalog::patch_index(from(now), renamed, {rows[20]}).has_value()) << "the library's version is on the page";
  }
}

// An in-place update renames the changed parts in, then the head, then commits its record; a kill
// between the parts and the head leaves a head whose family counts are the old ones. The next run
// draws the same entries again (the record still has their old inputs) and patches the same rows:
// that must give the files of an uninterrupted update, counts included.
TEST(CatalogIndex, APatchCutOffBetweenItsPartsAndItsHeadIsPutRightByTheSamePatchAgain) {
  compiler::LibraryManifest manifest;
  manifest.name = "m";
  manifest.version = "1";
  manifest.families = {{"cloth", "Cloth", "", false}, {"stone", "Stone", "", false}};
  std::vector<catalog::IndexRow> rows;
  for (int i = 0; i < 5000; ++i) {
    catalog::IndexRow r;
    char name[16];
    std::snprintf(name, sizeof name, "e%05d", i);
    r.name = name;
    r.family = i % 3 == 0 ? "" : i % 3 == 1 ? "cloth" : "stone";
    r.describes = "row " + std::to_string(i);
    r.page = "entries/" + r.name + ".html";
    rows.push_back(r);
  }
  auto disk = catalog::index_files(manifest, rows);
  const auto reader = [&](const std::string& f) -> std::optional<std::string> {
    const auto it = disk.find(f);
    return it == disk.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
  // Two rows move family (cloth -> none, none -> stone), in two parts.
  std::vector<catalog::IndexRow> changed{rows[1], rows[3000]};
  changed[0].family = "";
  changed[1].family = "stone";
  rows[1] = changed[0];
  rows[3000] = changed[1];
  const auto uninterrupted = catalog::index_files(manifest, rows);
  const auto first = catalog::patch_index(reader, manifest, changed);
  ASSERT_TRUE(first.has_value());
  ASSERT_TRUE(first->count(catalog::index_part_file(0)) && first->count(catalog::index_part_file(1)));
  // Cut off: the parts are in, the head and the page are not.
  for (const auto& [f, text] : *first)
    if (f != catalog::kIndexDataFile && f != "index.html") disk[f] = text;
  ASSERT_NE(disk.at(catalog::kIndexDataFile), uninterrupted.at(catalog::kIndexDataFile)) << "the counts should differ";
  const auto again = catalog::patch_index(reader, manifest, changed);
  ASSERT_TRUE(again.has_value());
  for (const auto& [f, text] : *again) disk[f] = text;
  EXPECT_TRUE(disk == uninterrupted) << "the counts were not put right";
  EXPECT_NE(disk.at("index.html").find("<option value=\"stone\">Stone (1667)</option>"), std::string::npos)
      << disk.at("index.html");
}

TEST(Catalog, IndexListsEveryEntryWithItsCompiledRoughness) {
  const auto& c = test::shipped_compiler();
  const fs::path out = fs::path(test::temp_dir("catalog")) / "site";
  catalog::CatalogOptions o;
  o.output = out;
  const auto report = catalog::write_catalog(c, o);
  ASSERT_TRUE(report.failures.empty());
  ASSERT_EQ(report.entries, static_cast<int>(c.library().entries().size()));
  const auto entries = entries_of_index(index_files_in(out));
  std::vector<std::string> names;
  for (const auto& e : entries) {
    const std::string name = e["name"];
    names.push_back(name);
    const auto r = c.compile_file(c.library().entry(name)->file);
    ASSERT_TRUE(r.ok()) << name;
    if (r.program->max_lateral_force_N > 0) {
      EXPECT_NEAR(e["roughness"].get<double>(), r.program->roughness, 5e-6 * r.program->roughness) << name;
      EXPECT_TRUE(fs::is_regular_file(out / e["thumbnail"].get<std::string>())) << name;
    } else {
      EXPECT_TRUE(e["roughness"].is_null()) << name;
    }
    EXPECT_EQ(e["family"], c.library().entry(name)->family);
    EXPECT_TRUE(fs::is_regular_file(out / e["page"].get<std::string>())) << name;
  }
  EXPECT_EQ(names, c.library().names());
  // Array files only on request (--arrays).
  EXPECT_FALSE(fs::exists(out / "entries" / "gravel.shade"));
  EXPECT_EQ(read(out / "entries" / "gravel.html").find(".shade\""), std::string::npos);
  // An image texture's page gives the image's own licence, linked to its text, and its credit
  // (library/images/gravel.png.license).
  const auto gravel = read(out / "entries" / "gravel.html");
  EXPECT_NE(gravel.find("<th scope=\"row\">image licence</th><td colspan=\"4\"><a class=\"licence\" "
                        "href=\"https://spdx.org/licenses/CC0-1.0.html\">CC0-1.0</a> \xC2\xB7 scikit-image sample data"),
            std::string::npos)
      << gravel.substr(gravel.find("image licence") == std::string::npos ? 0 : gravel.find("image licence"), 400);
  EXPECT_TRUE(fs::is_regular_file(out / "assets" / "index.js"));
  EXPECT_TRUE(fs::is_regular_file(out / "assets" / "catalog.css"));
  fs::remove_all(out.parent_path());
}

TEST(Catalog, EntryPageShowsDeprecationLayersAndSourceNotes) {
  compiler::CompileOptions opts;
  opts.library_dir = SANDPAPER_SOURCE_DIR "/tests/compiler/data/library-small";
  compiler::Compiler c(opts);
  const fs::path out = fs::path(test::temp_dir("catalog-small")) / "site";
  catalog::CatalogOptions o;
  o.output = out;
  o.arrays = true;
  ASSERT_TRUE(catalog::write_catalog(c, o).failures.empty());
  // --arrays: the picture as a .shade file too, linked from the page.
  EXPECT_TRUE(fs::is_regular_file(out / "entries" / "rib.shade"));
  EXPECT_NE(read(out / "entries" / "rib.html").find("href=\"rib.shade\""), std::string::npos);
  const std::string old_page = read(out / "entries" / "old-rib.html");
  EXPECT_NE(old_page.find("class=\"deprecated\""), std::string::npos);
  EXPECT_NE(old_page.find("<a href=\"rib.html\">rib</a> instead"), std::string::npos);
  const std::string rib = read(out / "entries" / "rib.html");
  EXPECT_EQ(rib.find("class=\"deprecated\""), std::string::npos);
  for (const char* s : {"id=\"representative\"", "id=\"perceptual\"", "id=\"physical\"", "id=\"provenance\"", "CC0-1.0",
                        "ribbed-cloth", "kind-derived", "8 ribs per inch, 25.4 mm / 8 = 3.2 mm, rounded", "(mm)", "(N)"})
    EXPECT_NE(rib.find(s), std::string::npos) << s;
  // The provenance row of the period carries the grating statement's notes.
  const auto period = rib.find("<code>texture.period</code>");
  ASSERT_NE(period, std::string::npos);
  const auto row_end = rib.find("</tr>", period);
  EXPECT_NE(rib.substr(period, row_end - period).find("kind-by-ear"), std::string::npos);
  // An entry seen through `like` finds the notes in the entry that said the number.
  const auto notes = catalog::notes_for(c.library(), "library rib (" + c.library().entry("rib")->file.string() + ":8:3)");
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0].kind, compiler::SourceKind::Derived);
  // And by the name the compiler gives an inherited number's file ("library/" and the path in the
  // library's folder), whatever the folder is called (here library-small).
  EXPECT_EQ(catalog::notes_for(c.library(), "library rib (library/cloth/rib.hmat:8:3)").size(), 2u);
  // How to feel it: the commands, with the entry's name; and the similar entries, filled by a script.
  for (const char* s : {"<pre><code>sandpaper run -e rib --device sim</code></pre>", "sandpaper run -e rib --device usb",
                        "<code>sandpaper studio</code>", "<ol id=\"similar-list\">", "data-entry=\"rib\" data-weber=\"0.125\"",
                        "<script src=\"../assets/similar.js\"></script>"})
    EXPECT_NE(rib.find(s), std::string::npos) << s;
  // The index's data says which kinds of source the entry's own notes are (rib's file has a derived
  // and a by-ear note and no measurement), its period and kind for the similar entries.
  const auto entries = entries_of_index(index_files_in(out));
  const auto at = std::find_if(entries.begin(), entries.end(), [](const auto& e) { return e["name"] == "rib"; });
  ASSERT_NE(at, entries.end());
  const unsigned kinds = (*at)["source_kinds"];
  EXPECT_TRUE(kinds & (1u << static_cast<unsigned>(compiler::SourceKind::Derived)));
  EXPECT_TRUE(kinds & (1u << static_cast<unsigned>(compiler::SourceKind::ByEar)));
  EXPECT_FALSE(kinds & (1u << static_cast<unsigned>(compiler::SourceKind::Measurement)));
  EXPECT_NEAR((*at)["period_m"].get<double>(), 3e-3, 1e-12);  // "grating period 3 mm" in cloth/rib.hmat
  EXPECT_EQ((*at)["kind"], "grating|grating");
  EXPECT_EQ((*at)["root"], "");
  // Its compare data: the scan over the thumbnail's 40 mm square, the force as the program's.
  const std::string cmp = read(out / "entries" / "rib.compare.js");
  const auto d = json_of_script(cmp, "(window.sandpaperCompare = window.sandpaperCompare || []).push(JSON.parse('", "'));\n");
  EXPECT_EQ(d["name"], "rib");
  EXPECT_EQ(d["thumbnail"], "rib-thumb.png");
  EXPECT_DOUBLE_EQ(d["window_m"].get<double>(), 0.04);
  EXPECT_NEAR(d["scan"]["s_mm"].front().get<double>(), -20, 1e-9);
  EXPECT_NEAR(d["scan"]["s_mm"].back().get<double>(), 20, 1e-9);
  double peak = 0;
  for (const auto& f : d["scan"]["along_N"]) peak = std::max(peak, std::abs(f.get<double>()));
  const auto rib_program = c.compile_file(c.library().entry("rib")->file).program;
  EXPECT_NEAR(peak, rib_program->max_lateral_force_N, 0.02 * rib_program->max_lateral_force_N);
  EXPECT_EQ(d["sources"], nlohmann::json::array({"derived", "by-ear"}));
  fs::remove_all(out.parent_path());
}

// Every file of a catalog folder (bar the temp-free marker) by relative path, with its bytes.
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& f : fs::recursive_directory_iterator(dir))
    if (f.is_regular_file()) out[fs::relative(f.path(), dir).generic_string()] = read(f.path());
  return out;
}

// A copy of tests/compiler/data/library-small in a fresh folder, and its catalog drawn into site/
// by write_catalog over the whole library.
struct SmallCatalog {
  fs::path root, lib, out;
  explicit SmallCatalog(const std::string& name)
      : root(test::temp_dir(name)), lib(root / "lib"), out(root / "site") {
    fs::copy(SANDPAPER_SOURCE_DIR "/tests/compiler/data/library-small", lib, fs::copy_options::recursive);
  }
  ~SmallCatalog() { fs::remove_all(root); }
  catalog::CatalogReport run() const {
    compiler::CompileOptions opts;
    opts.library_dir = lib;
    compiler::Compiler c(opts);
    catalog::CatalogOptions o;
    o.output = out;
    return catalog::write_catalog(c, o);
  }
};

TEST(Catalog, ARebuildDrawsOnlyWhatChangedAndKeepsEveryOtherFileByteIdentical) {
  const SmallCatalog small("catalog-incremental");
  const fs::path &lib = small.lib, &out = small.out;
  auto run = [&] { return small.run(); };
  auto r = run();
  ASSERT_TRUE(r.failures.empty());
  EXPECT_EQ(r.rendered, 4);
  const auto first = files_of(out);
  r = run();  // nothing changed: nothing drawn, every byte as it was
  EXPECT_EQ(r.rendered, 0);
  EXPECT_EQ(r.reused, 4);
  EXPECT_TRUE(files_of(out) == first) << "a run with nothing changed rewrote a file";
  // A data file emptied by hand is written again, even with nothing to draw.
  std::ofstream(out / catalog::kIndexDataFile, std::ios::trunc).close();
  r = run();
  EXPECT_EQ(r.rendered, 0);
  EXPECT_TRUE(files_of(out) == first) << "the emptied data file was not written again";
  // One entry changed, that nothing is built on: its page and pictures, its index row, nothing else.
  {
    std::string text = read(lib / "ref.hmat");
    const auto at = text.find("period ");
    ASSERT_NE(at, std::string::npos) << text;
    text.insert(at + 7, "1");  // 2.5 mm -> 12.5 mm (the same force: the index row changes by its words)
    text.replace(text.find("the reference grating"), 21, "the coarser reference grating");
    std::ofstream(lib / "ref.hmat") << text;
  }
  struct stat folder_before {};
  ASSERT_EQ(::stat(out.c_str(), &folder_before), 0);
  r = run();
  ASSERT_TRUE(r.failures.empty());
  EXPECT_EQ(r.rendered, 1);
  EXPECT_EQ(r.reused, 3);
  // Updated in the catalog itself: the same folder, not a new one swapped in.
  EXPECT_TRUE(r.in_place);
  struct stat folder_after {};
  ASSERT_EQ(::stat(out.c_str(), &folder_after), 0);
  EXPECT_EQ(folder_after.st_ino, folder_before.st_ino);
  const auto second = files_of(out);
  for (const auto& [path, bytes] : first) {
    const bool ref = path.rfind("entries/ref", 0) == 0;
    // ref.png may stay as it was: a grating too fine for the patch's pixels is drawn over 384 px /
    // 64 px a period = 6 periods whatever the period (render_picture), and its page says the window.
    if (path == catalog::index_part_file(0) || path == "inputs.sqlite" || path == "entries/ref.html" ||
        path == "entries/ref-thumb.png") {
      EXPECT_TRUE(second.at(path) != bytes) << path << " should have changed";
    } else if (!ref) {
      EXPECT_TRUE(second.at(path) == bytes) << path << " changed, though its entry did not";
    }
  }
  // The index's data differs in ref's row only (index.html, which holds no entry, and the head file,
  // whose counts and spans are as they were, are unchanged: checked above).
  const auto d1 = entries_of_index(first);
  const auto d2 = entries_of_index(second);
  ASSERT_EQ(d1.size(), d2.size());
  for (std::size_t i = 0; i < d1.size(); ++i) {
    if (d1[i]["name"] == "ref") EXPECT_NE(d1[i], d2[i]);
    else EXPECT_EQ(d1[i], d2[i]) << d1[i]["name"];
  }
  // An entry others are built on: it and they are drawn again.
  {
    std::string text = read(lib / "cloth/rib.hmat");
    const auto at = text.find("roughness 0.4");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 13, "roughness 0.45");
    std::ofstream(lib / "cloth/rib.hmat") << text;
  }
  r = run();
  EXPECT_GE(r.rendered, 2);  // rib and old-rib (like rib), and fine-rib if it names rib's alias
  EXPECT_EQ(r.rendered + r.reused, 4);
}

TEST(Catalog, AnInPlaceUpdateCutOffBeforeItsRecordIsFinishedByTheNextRun) {
  // A kill during an in-place update leaves the drawn files renamed in and the record as it was
  // (it is committed last). Made here without a kill: the update runs, then the old record is put
  // back. The next run must see those entries as changed, draw them again and end as the update did.
  const SmallCatalog small("catalog-cut-off");
  const fs::path &lib = small.lib, &out = small.out;
  auto run = [&] { return small.run(); };
  ASSERT_TRUE(run().failures.empty());
  const std::string old_record = read(out / "inputs.sqlite");
  {
    std::string text = read(lib / "ref.hmat");
    text.replace(text.find("the reference grating"), 21, "the coarser reference grating");
    std::ofstream(lib / "ref.hmat") << text;
  }
  auto r = run();
  ASSERT_TRUE(r.in_place);
  ASSERT_EQ(r.rendered, 1);
  const auto done = files_of(out);
  std::ofstream(out / "inputs.sqlite", std::ios::binary | std::ios::trunc) << old_record;
  r = run();
  EXPECT_TRUE(r.in_place);
  EXPECT_EQ(r.rendered, 1);  // ref again: the record still had its old inputs
  EXPECT_TRUE(files_of(out) == done) << "the finished update differs from the uninterrupted one";
  r = run();
  EXPECT_EQ(r.rendered, 0);
}

// The record (inputs.sqlite) lists each entry's files, which a run deletes when the entry goes or
// stops drawing them, and links into a rebuilt folder. A record from elsewhere (a catalog folder
// copied or downloaded) naming "../../x" must not reach outside entries/: its lists are not trusted.
TEST(Catalog, ARecordNamingFilesOutsideTheCatalogNeitherDeletesNorLinksThem) {
  const SmallCatalog small("catalog-hostile-record");
  const fs::path &root = small.root, &lib = small.lib, &out = small.out;
  auto run = [&] { return small.run(); };
  ASSERT_TRUE(run().failures.empty());
  std::ofstream(root / "outside.txt") << "not the catalog's\n";
  auto set_files = [&](const std::string& name, const std::string& files) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((out / "inputs.sqlite").c_str(), &db), SQLITE_OK);
    const std::string sql = "UPDATE entries SET files = '" + files + "' WHERE name = '" + name + "'";
    EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    EXPECT_EQ(sqlite3_changes(db), 1);
    sqlite3_close(db);
  };
  // In place: ref removed from the library; its recorded files include one outside the catalog.
  set_files("ref", R"(["ref.html","ref.png","../../outside.txt"])");
  set_files("rib", "not JSON");
  fs::remove(lib / "ref.hmat");
  {
    std::string text = read(lib / "library.toml");
    const std::string from = "reference = \"ref\"";
    text.replace(text.find(from), from.size(), "reference = \"rib\"");
    std::ofstream(lib / "library.toml") << text;
  }
  auto r = run();
  ASSERT_TRUE(r.failures.empty());
  EXPECT_TRUE(r.in_place);
  EXPECT_TRUE(fs::exists(root / "outside.txt")) << "a recorded \"../../outside.txt\" was deleted";
  // The files it would have written for that name go instead.
  EXPECT_FALSE(fs::exists(out / "entries" / "ref.html"));
  EXPECT_FALSE(fs::exists(out / "entries" / "ref-thumb.png"));
  // Rebuilt whole (a new folder, the unchanged entries' files linked in): a list reaching outside
  // is not linked, its entry is drawn again.
  set_files("old-rib", R"(["old-rib.html","../../outside.txt"])");
  fs::remove(out / catalog::kIndexDataFile);  // no data file: the whole folder is rebuilt
  r = run();
  ASSERT_TRUE(r.failures.empty());
  EXPECT_FALSE(r.in_place);
  EXPECT_GE(r.rendered, 1);
  for (const auto& f : fs::recursive_directory_iterator(out))
    EXPECT_NE(f.path().filename(), "outside.txt") << "a file outside the catalog was published: " << f.path();
  EXPECT_TRUE(fs::exists(root / "outside.txt"));
}

// A record whose hashes read but one of whose rows does not (a damaged file: found by fuzzing, F16)
// is not half-read: the index would lose the rows past the damage, or every kept row. The run
// draws every entry again, as with no record, and writes a good record.
TEST(Catalog, ARecordWithAnUnreadableRowIsDrawnAgainWholeAndTheIndexKeepsEveryEntry) {
  const SmallCatalog small("catalog-unreadable-record");
  const fs::path &lib = small.lib, &out = small.out;
  auto run = [&] { return small.run(); };
  ASSERT_TRUE(run().failures.empty());
  auto damage_rib = [&] {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((out / "inputs.sqlite").c_str(), &db), SQLITE_OK);
    EXPECT_EQ(sqlite3_exec(db, "UPDATE entries SET aliases = 'not JSON' WHERE name = 'rib'", nullptr, nullptr, nullptr), SQLITE_OK);
    EXPECT_EQ(sqlite3_changes(db), 1);
    sqlite3_close(db);
  };
  damage_rib();
  // fine-rib, which nothing is built on, removed: an in-place update with nothing to draw, which
  // writes the index whole from the record's rows, rib's among them.
  fs::remove(lib / "cloth" / "fine-rib.hmat");
  auto r = run();
  ASSERT_TRUE(r.failures.empty());
  EXPECT_TRUE(r.record_unreadable);
  EXPECT_FALSE(r.in_place);
  EXPECT_EQ(r.rendered, 3);
  std::set<std::string> names;
  for (const auto& e : entries_of_index(index_files_in(out))) names.insert(e["name"].get<std::string>());
  EXPECT_EQ(names, (std::set<std::string>{"old-rib", "ref", "rib"}));
  EXPECT_FALSE(fs::exists(out / "entries" / "fine-rib.html"));
  r = run();  // the record written is whole again
  EXPECT_FALSE(r.record_unreadable);
  EXPECT_EQ(r.rendered, 0);
  EXPECT_EQ(r.reused, 3);
  // Rebuilt whole (no data file), the same damage is reported the same way.
  damage_rib();
  fs::remove(out / catalog::kIndexDataFile);
  r = run();
  ASSERT_TRUE(r.failures.empty());
  EXPECT_TRUE(r.record_unreadable);
  EXPECT_EQ(r.rendered, 3);
}

TEST(Catalog, AFailedRunLeavesThePreviousCatalogAndNamesTheEntry) {
  const fs::path root = test::temp_dir("catalog-fail");
  const fs::path lib = root / "lib";
  fs::create_directories(lib);
  std::ofstream(lib / "good.hmat") << "material \"good\" {\n  grating period 2 mm\n  roughness 0.4\n}\n";
  const fs::path out = root / "site";
  {
    compiler::CompileOptions opts;
    opts.library_dir = lib;
    compiler::Compiler c(opts);
    catalog::CatalogOptions o;
    o.output = out;
    ASSERT_EQ(catalog::write_catalog(c, o).entries, 1);
  }
  const std::string before = read(out / "index.html");
  std::ofstream(lib / "bad.hmat") << "material \"bad\" {\n  grating period -2 mm\n}\n";
  compiler::CompileOptions opts;
  opts.library_dir = lib;
  compiler::Compiler c(opts);
  catalog::CatalogOptions o;
  o.output = out;
  const auto report = catalog::write_catalog(c, o);
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_EQ(report.failures[0].name, "bad");
  EXPECT_FALSE(report.failures[0].diagnostics.empty());
  EXPECT_EQ(read(out / "index.html"), before);
  EXPECT_FALSE(fs::exists(out / "entries" / "bad.html"));
  for (const auto& e : fs::directory_iterator(root))  // no temporary folder left behind
    EXPECT_TRUE(e.path().filename() == "lib" || e.path().filename() == "site") << e.path();

  // A folder that is not a catalog is not replaced.
  const fs::path mine = root / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "keep me";
  o.output = mine;
  fs::remove(lib / "bad.hmat");
  compiler::Compiler c2(opts);
  EXPECT_THROW(catalog::write_catalog(c2, o), std::invalid_argument);
  EXPECT_EQ(read(mine / "notes.txt"), "keep me");
  fs::remove_all(root);
}

}  // namespace
}  // namespace sandpaper
