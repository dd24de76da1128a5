// Preview pictures: the catalog's shaded height field and force plot, plus a top view of the force
// field, each picture with a scale bar, written as files (`sandpaper preview`) or served (the studio).
#include "sandpaper/catalog/preview.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <type_traits>
#include <variant>
#include <unistd.h>

#include "png_file.hpp"

#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/schema/atomic_file.hpp"

namespace sandpaper::catalog {
namespace {

// A 3 x 5 pixel font for the scale bar's label: digits, '.', ' ' and a 5-wide 'm'. Rows top to bottom.
struct Glyph {
  char c;
  int width;
  const char* rows[5];
};
constexpr Glyph kGlyphs[] = {
    {'0', 3, {"###", "#.#", "#.#", "#.#", "###"}}, {'1', 3, {".#.", "##.", ".#.", ".#.", "###"}},
    {'2', 3, {"###", "..#", "###", "#..", "###"}}, {'3', 3, {"###", "..#", "###", "..#", "###"}},
    {'4', 3, {"#.#", "#.#", "###", "..#", "..#"}}, {'5', 3, {"###", "#..", "###", "..#", "###"}},
    {'6', 3, {"###", "#..", "###", "#.#", "###"}}, {'7', 3, {"###", "..#", "..#", "..#", "..#"}},
    {'8', 3, {"###", "#.#", "###", "#.#", "###"}}, {'9', 3, {"###", "#.#", "###", "..#", "###"}},
    {'.', 1, {".", ".", ".", ".", "#"}},           {' ', 2, {"..", "..", "..", "..", ".."}},
    {'m', 5, {".....", "####.", "#.#.#", "#.#.#", "#.#.#"}},
};

const Glyph* glyph(char c) {
  for (const auto& g : kGlyphs)
    if (g.c == c) return &g;
  return nullptr;
}

void put(Image& im, int x, int y, std::uint8_t v) {
  if (x < 0 || y < 0 || x >= im.nx || y >= im.ny) return;
  const std::size_t i = (static_cast<std::size_t>(y) * im.nx + x) * im.channels;
  for (int c = 0; c < im.channels; ++c) im.pixels[i + c] = v;
}

// A filled rectangle in `v` with a one-pixel border in `border`, so it reads on any background.
void box(Image& im, int x0, int y0, int w, int h, std::uint8_t v, std::uint8_t border) {
  for (int y = y0 - 1; y <= y0 + h; ++y)
    for (int x = x0 - 1; x <= x0 + w; ++x)
      put(im, x, y, (x < x0 || y < y0 || x >= x0 + w || y >= y0 + h) ? border : v);
}

std::string label_of(double mm) {
  std::string s = std::to_string(mm);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s + " mm";
}

double nice_length(double target) {
  const double mag = std::pow(10.0, std::floor(std::log10(target)));
  const double r = target / mag;
  return (r >= 5 ? 5 : r >= 2 ? 2 : 1) * mag;
}

// Hue (0..1) to an RGB triple at full saturation and value `v` (0..1).
void hsv(double h, double v, std::uint8_t out[3]) {
  const double k[3] = {5, 3, 1};
  for (int c = 0; c < 3; ++c) {
    const double kk = std::fmod(k[c] + h * 6, 6.0);
    const double f = v - v * std::max(0.0, std::min({kk, 4 - kk, 1.0}));
    out[c] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(f, 0.0, 1.0)));
  }
}

// The force a still hand feels at `p` (m) from the program's position-only terms, limited to the
// device's maximum force as the servo loop limits it (|F| scaled down, direction kept). Non-finite
// forces read as zero.
struct FieldSampler {
  explicit FieldSampler(const schema::PatchProgram& program)
      : drawn(position_only(program, left_out)), eval(drawn), limit_N(program.command.max_force_N) {}
  glm::dvec2 at(glm::dvec2 p) {
    runtime::HandState hand;
    hand.position_m = p;
    glm::dvec2 f = eval.force_rt(hand, 0.0);
    if (!std::isfinite(f.x) || !std::isfinite(f.y)) return {0, 0};
    const double mag = std::hypot(f.x, f.y);
    if (limit_N > 0 && mag > limit_N) f *= limit_N / mag;
    return f;
  }
  std::vector<std::string> left_out;
  schema::PatchProgram drawn;  // the evaluator reads it: declared before it
  runtime::PatchEvaluator eval;
  double limit_N;
};

// The strongest force on a (2k+1) x (2k+1) grid of `step` (m) around `p`, `p` itself included: a
// sample grid's best point refined toward the peak it lies beside, since a grating's wall (a Gaussian of
// sigma = period x 6/256) is narrower than the grids a picture or a page's arrows can afford.
struct Strongest {
  glm::dvec2 at{0, 0}, f{0, 0};
  double mag = 0;
};
Strongest strongest_near(FieldSampler& field, glm::dvec2 p, double step, int k) {
  Strongest best;
  for (int j = -k; j <= k; ++j)
    for (int i = -k; i <= k; ++i) {
      const glm::dvec2 q = p + glm::dvec2{i * step, j * step};
      const glm::dvec2 f = field.at(q);
      const double mag = std::hypot(f.x, f.y);
      if (mag > best.mag || (i == 0 && j == 0 && best.mag == 0)) best = {q, f, mag};
    }
  return best;
}

// The catalog's plot styles (assets/catalog.css), inside the file so that scan.svg stands alone.
constexpr const char* kStandalonePlotStyle =
    "<style>svg.force-plot{background:#fff}svg.force-plot text{font:13px system-ui,'DejaVu Sans',sans-serif;fill:#222}"
    ".frame,line{stroke:#888}line.grid{stroke:#ececec}line.grid.zero{stroke:#bbb}"
    ".force-along{stroke:#8a4b08;stroke-width:1.3}.force-across{stroke:#2f6fb3;stroke-width:1;stroke-dasharray:4 3}</style>\n";

}  // namespace

schema::PatchProgram position_only(const schema::PatchProgram& program, std::vector<std::string>& left_out) {
  schema::PatchProgram out = program;
  out.terms.clear();
  for (const auto& t : program.terms) {
    const bool of_position = std::visit(
        [](const auto& term) {
          using T = std::decay_t<decltype(term)>;
          return !(std::is_same_v<T, schema::DamperTerm> || std::is_same_v<T, schema::NapTerm> ||
                   std::is_same_v<T, schema::MinusTerm> || std::is_same_v<T, schema::FollowerSpringTerm> ||
                   std::is_same_v<T, schema::PointMassesTerm> || std::is_same_v<T, schema::AttractorTerm> ||
                   std::is_same_v<T, schema::FrictionTerm> || std::is_same_v<T, schema::NapFrictionTerm>);
        },
        t);
    if (of_position) out.terms.push_back(t);
    else left_out.push_back(why_not_pictured(t));
  }
  return out;
}

std::string standalone_plot_svg(const ForceScan& scan, const std::string& title) {
  std::string svg = force_plot_svg(scan, title);
  const auto at = svg.find("</title>\n");
  if (at != std::string::npos) svg.insert(at + 9, kStandalonePlotStyle);
  return svg;
}

Image grey_image(const Picture& picture) {
  Image im;
  im.nx = picture.nx;
  im.ny = picture.ny;
  im.channels = 1;
  im.pixel_m = picture.pixel_m;
  im.window_m[0] = picture.window_m[0];
  im.window_m[1] = picture.window_m[1];
  im.pixels.resize(picture.shade.values.size());
  for (std::size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = static_cast<std::uint8_t>(255 - picture.shade.values[i]);
  return im;
}

Image render_force_field(const schema::PatchProgram& program, const Picture& like, double& max_force_N) {
  Image im;
  im.nx = like.nx;
  im.ny = like.ny;
  im.channels = 3;
  im.pixel_m = like.pixel_m;
  im.window_m[0] = like.window_m[0];
  im.window_m[1] = like.window_m[1];
  max_force_N = 0;
  if (like.empty()) return im;
  FieldSampler field(program);
  const std::size_t n = static_cast<std::size_t>(im.nx) * im.ny;
  std::vector<glm::dvec2> f(n);
  for (int row = 0; row < im.ny; ++row)
    for (int col = 0; col < im.nx; ++col) {
      const glm::dvec2 p{like.centre_m[0] - 0.5 * im.window_m[0] + (col + 0.5) * im.pixel_m,
                         like.centre_m[1] + 0.5 * im.window_m[1] - (row + 0.5) * im.pixel_m};
      const glm::dvec2 v = field.at(p);
      f[static_cast<std::size_t>(row) * im.nx + col] = v;
      max_force_N = std::max(max_force_N, std::hypot(v.x, v.y));
    }
  // The brightest pixel may sit beside a wall's peak rather than on it: the scale is the peak's.
  if (max_force_N > 0) {
    std::size_t top = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (std::hypot(f[i].x, f[i].y) > std::hypot(f[top].x, f[top].y)) top = i;
    const int row = static_cast<int>(top / im.nx), col = static_cast<int>(top % im.nx);
    const glm::dvec2 p{like.centre_m[0] - 0.5 * im.window_m[0] + (col + 0.5) * im.pixel_m,
                       like.centre_m[1] + 0.5 * im.window_m[1] - (row + 0.5) * im.pixel_m};
    max_force_N = std::max(max_force_N, strongest_near(field, p, im.pixel_m / 8, 8).mag);
  }
  im.pixels.assign(n * 3, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double mag = std::hypot(f[i].x, f[i].y);
    if (!(max_force_N > 0) || mag == 0) continue;
    double hue = std::atan2(f[i].y, f[i].x) / (2 * M_PI);
    if (hue < 0) hue += 1;
    hsv(hue, mag / max_force_N, &im.pixels[i * 3]);
  }
  return im;
}

double draw_scale_bar(Image& im) {
  if (im.nx < 24 || im.ny < 16 || !(im.pixel_m > 0)) return 0;
  const double width_mm = im.nx * im.pixel_m * 1e3;
  const double bar_mm = nice_length(width_mm / 4);
  const int bar_px = std::max(1, static_cast<int>(std::lround(bar_mm / (im.pixel_m * 1e3))));
  const int scale = im.nx >= 256 ? 2 : 1;  // font pixel size
  const int margin = 4 * scale, bar_h = 3 * scale;
  const int x0 = margin, y_bar = im.ny - margin - bar_h;
  box(im, x0, y_bar, bar_px, bar_h, 0, 255);
  // The label above the bar, black on a white box.
  const std::string text = label_of(bar_mm);
  int text_w = 0;
  for (char c : text)
    if (const Glyph* g = glyph(c)) text_w += (g->width + 1) * scale;
  const int y_text = y_bar - 4 * scale - 5 * scale;
  box(im, x0, y_text - scale, text_w + scale, 7 * scale, 255, 255);
  int x = x0 + scale;
  for (char c : text) {
    const Glyph* g = glyph(c);
    if (!g) continue;
    for (int r = 0; r < 5; ++r)
      for (int col = 0; col < g->width; ++col)
        if (g->rows[r][col] == '#')
          for (int dy = 0; dy < scale; ++dy)
            for (int dx = 0; dx < scale; ++dx) put(im, x + col * scale + dx, y_text + r * scale + dy, 0);
    x += (g->width + 1) * scale;
  }
  return bar_mm;
}

void write_image_png(const std::filesystem::path& file, const Image& image) {
  if (image.nx <= 0 || image.ny <= 0) throw std::invalid_argument("write_image_png: the image is empty");
  // Written beside `file` and renamed over it once complete.
  const auto tmp = file.parent_path() / ("." + file.stem().string() + ".tmp-" + std::to_string(::getpid()) + ".png");
  std::string why;
  if (!write_png_file(tmp, image.nx, image.ny, image.channels, image.pixels.data(), why)) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + file.string() + ": " + why);
  }
  std::filesystem::rename(tmp, file);
}

nlohmann::json force_field_json(const schema::PatchProgram& program, const Picture& like, int n) {
  nlohmann::json j{{"window_mm", {like.window_m[0] * 1e3, like.window_m[1] * 1e3}}, {"n", n}};
  std::vector<double> x, y, fx, fy;
  double max_n = 0;
  if (!like.empty() && n >= 1) {
    FieldSampler field(program);
    // Each cell is searched on a grid as fine as the picture's pixels, then about its best point.
    const int sub = std::max(2, (std::max(like.nx, like.ny) + n - 1) / n);
    const double cw = like.window_m[0] / n, ch = like.window_m[1] / n;
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        const double x0 = like.centre_m[0] - 0.5 * like.window_m[0] + col * cw;
        const double y0 = like.centre_m[1] + 0.5 * like.window_m[1] - row * ch;
        Strongest best;
        for (int b = 0; b < sub; ++b)
          for (int a = 0; a < sub; ++a) {
            const glm::dvec2 p{x0 + (a + 0.5) * cw / sub, y0 - (b + 0.5) * ch / sub};
            const glm::dvec2 f = field.at(p);
            const double mag = std::hypot(f.x, f.y);
            if (mag > best.mag || (a == 0 && b == 0)) best = {p, f, mag};
          }
        if (best.mag > 0) {
          const Strongest fine = strongest_near(field, best.at, std::min(cw, ch) / sub / 4, 4);
          // The refined point stays in its cell, so that each cell's arrow is its own.
          if (fine.at.x >= x0 && fine.at.x <= x0 + cw && fine.at.y <= y0 && fine.at.y >= y0 - ch) best = fine;
        }
        x.push_back(best.at.x * 1e3);
        y.push_back(best.at.y * 1e3);
        fx.push_back(best.f.x);
        fy.push_back(best.f.y);
        max_n = std::max(max_n, best.mag);
      }
  }
  j["cell_mm"] = {n >= 1 ? like.window_m[0] * 1e3 / n : 0.0, n >= 1 ? like.window_m[1] * 1e3 / n : 0.0};
  j["max_N"] = max_n;
  j["x_mm"] = x;
  j["y_mm"] = y;
  j["fx_N"] = fx;
  j["fy_N"] = fy;
  return j;
}

PreviewFiles write_preview(const schema::PatchProgram& program, const std::filesystem::path& dir, int max_side,
                           int field_arrows) {
  std::filesystem::create_directories(dir);
  PreviewFiles out;
  const Picture picture = render_picture(program, max_side);
  nlohmann::json& s = out.summary;
  s["material"] = program.name;
  s["left_out"] = picture.left_out;
  if (!picture.empty()) {
    Image height = grey_image(picture);
    const double bar = draw_scale_bar(height);
    write_image_png(dir / "height.png", height);
    double max_f = 0;
    Image field = render_force_field(program, picture, max_f);
    draw_scale_bar(field);
    write_image_png(dir / "field.png", field);
    out.written = {dir / "height.png", dir / "field.png"};
    s["pictures"] = {{"height", "height.png"}, {"field", "field.png"}};
    s["pixels"] = {picture.nx, picture.ny};
    s["pixel_mm"] = picture.pixel_m * 1e3;
    s["window_mm"] = {picture.window_m[0] * 1e3, picture.window_m[1] * 1e3};
    s["scale_bar_mm"] = bar;
    s["field_max_N"] = max_f;
    // What the force-field picture leaves out, and the limit it draws forces to (the device's).
    std::vector<std::string> field_left_out;
    position_only(program, field_left_out);
    s["field_left_out"] = field_left_out;
    s["field_limit_N"] = program.command.max_force_N;
    s["caption"] = picture.caption;
  } else {
    s["pictures"] = nlohmann::json::object();
  }
  double dir_v[2];
  std::string axis, description;
  scan_direction(program, dir_v, axis, description);
  const double half = half_length_inside(dir_v, program.size_m[0], program.size_m[1]);
  const ForceScan scan = scan_force(program, half);
  schema::write_file_atomically(dir / "scan.svg", standalone_plot_svg(scan, "Lateral force of " + program.name + ", " + description));
  out.written.push_back(dir / "scan.svg");
  s["scan"] = {{"file", "scan.svg"}, {"axis", scan.axis}, {"description", scan.description},
               {"speed_mm_s", scan.speed_m_s * 1e3}, {"half_length_mm", half * 1e3}};
  if (field_arrows > 0) {
    schema::write_file_atomically(dir / "field.json", force_field_json(program, picture, field_arrows).dump());
    out.written.push_back(dir / "field.json");
  }
  schema::write_file_atomically(dir / "preview.json", s.dump(2) + "\n");
  out.written.push_back(dir / "preview.json");
  return out;
}

}  // namespace sandpaper::catalog
