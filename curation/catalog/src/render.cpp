// Picture of a compiled program's height field (render.hpp).
#include "sandpaper/catalog/render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "png_file.hpp"
#include "sandpaper/compiler/image_io.hpp"

#include "sandpaper/catalog/html.hpp"
#include "sandpaper/compiler/array_export.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/schema/term_kinds.hpp"

namespace sandpaper::catalog {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// The texture's finest length, m, that a pixel must resolve: 64 pixels a period (so that the version-2
// seed's edges, 12/256 of a period wide, span a few pixels), one pixel a sample.
double finest_scale(const schema::Term& term) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return std::visit(Overloaded{
                        [](const schema::GratingTerm& g) { return g.period_m / 64; },
                        [](const schema::HeightFieldTerm& h) { return std::min(h.spacing_m[0], h.spacing_m[1]); },
                        [](const schema::PeriodicTerm& p) { return p.period_m / 64; },
                        [](const schema::RidgeTerm& r) { return r.wavelength_m / 64; },
                        [&](const auto&) { return inf; },
                    },
                    term);
}

std::string mm(double m) { return format_number(m * 1e3, 3) + " mm"; }

}  // namespace

PictureRole picture_role(const schema::Term& term) {
  return std::visit(Overloaded{
                        [](const schema::GratingTerm&) { return PictureRole::Height; },
                        [](const schema::HeightFieldTerm&) { return PictureRole::Height; },
                        [](const schema::PeriodicTerm&) { return PictureRole::Height; },
                        [](const schema::RidgeTerm&) { return PictureRole::Height; },
                        [](const schema::SpringTerm&) { return PictureRole::Potential; },
                        [](const schema::ConstantForceTerm&) { return PictureRole::Potential; },
                        [](const schema::BowlTerm&) { return PictureRole::Potential; },
                        [](const schema::LinearSpringTerm&) { return PictureRole::Potential; },
                        [](const schema::LinearFieldTerm& f) {
                          return f.tangential_N_per_m == 0 ? PictureRole::Potential : PictureRole::None;
                        },
                        // Every other kind by name, no fallback: a new kind does not compile until
                        // it says whether and how it is drawn (here and in why_not_pictured).
                        [](const schema::DamperTerm&) { return PictureRole::None; },
                        [](const schema::NapTerm&) { return PictureRole::None; },
                        [](const schema::MinusTerm&) { return PictureRole::None; },
                        [](const schema::FollowerSpringTerm&) { return PictureRole::None; },
                        [](const schema::PointMassesTerm&) { return PictureRole::None; },
                        [](const schema::AttractorTerm&) { return PictureRole::None; },
                        [](const schema::FrictionTerm&) { return PictureRole::None; },
                        [](const schema::NapFrictionTerm&) { return PictureRole::None; },
                    },
                    term);
}

std::string term_kind(const schema::Term& term) {
  return std::string(schema::terms::visit_kind(term, [](const auto& kind, const auto&) { return kind.label; }));
}

std::string why_not_pictured(const schema::Term& term) {
  return std::visit(
      Overloaded{
          [](const schema::DamperTerm&) { return std::string("the damper: F = -b v depends on the hand's velocity, not its position"); },
          [](const schema::NapTerm&) { return std::string("the nap: its force depends on the hand's velocity"); },
          [](const schema::MinusTerm&) { return std::string("the minus mass: its force depends on velocity and acceleration"); },
          [](const schema::FollowerSpringTerm&) { return std::string("the follower spring: its force depends on where a lagging point has got to (state)"); },
          [](const schema::PointMassesTerm&) { return std::string("the point masses: their force depends on the masses' motion (state)"); },
          [](const schema::AttractorTerm&) { return std::string("the attractor: its force depends on time, as its target moves"); },
          [](const schema::FrictionTerm&) { return std::string("friction: its force depends on where the contact last stuck (state)"); },
          [](const schema::NapFrictionTerm&) { return std::string("nap friction: its force depends on where the contact last stuck (state)"); },
          [](const schema::LinearFieldTerm&) { return std::string("the circulating field: a tangential force has no potential surface"); },
          // The drawn kinds by name, no fallback (picture_role says why).
          [&](const schema::GratingTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::HeightFieldTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::PeriodicTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::RidgeTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::SpringTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::ConstantForceTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::BowlTerm&) { return term_kind(term) + ": drawn"; },
          [&](const schema::LinearSpringTerm&) { return term_kind(term) + ": drawn"; },
      },
      term);
}

namespace {

// The directions, rad, across which the program's ridges rise and fall: a grating's normal, a ridge
// term's x, a periodic term's x and y. Height fields and potentials have none.
std::vector<double> ridge_normals(const schema::PatchProgram& drawn) {
  std::vector<double> out;
  for (const auto& t : drawn.terms) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&t)) out.push_back(g->orientation_rad);
    else if (std::holds_alternative<schema::RidgeTerm>(t)) out.push_back(0);
    else if (const auto* p = std::get_if<schema::PeriodicTerm>(&t)) {
      if (p->on_x) out.push_back(0);
      if (p->on_y) out.push_back(std::numbers::pi / 2);
    }
  }
  return out;
}

}  // namespace

double light_azimuth_deg(const schema::PatchProgram& program) {
  // Lambertian shading tells a ridge's two walls apart by the light's component along the ridge
  // normal; a light along the ridges shades both walls alike, and the picture shows twice the
  // ridges' frequency. So: the whole degree nearest the thesis' 135 deg (upper left) within 45 deg
  // of every ridge normal (either sense); if none is, the one whose worst ridge is lit most
  // across. Equally near: the one nearer straight up (90 deg).
  const auto normals = ridge_normals(program);
  const auto worst = [&](int az) {
    double w = 1;
    for (const double n : normals) w = std::min(w, std::abs(std::cos(az * std::numbers::pi / 180 - n)));
    return w;
  };
  constexpr double across = 0.70710678118654752 - 1e-9;  // cos 45 deg, less rounding
  int best = 135;
  double best_worst = worst(135);
  if (best_worst >= across) return best;
  for (int d = 1; d <= 180; ++d)
    for (const int az : {135 - d, 135 + d}) {
      const double w = worst(az);
      if (w >= across) return (az + 360) % 360;
      if (w > best_worst + 1e-12) best = az, best_worst = w;
    }
  return (best + 360) % 360;
}

namespace {

// Shades slopes as compiler::shade_slopes does, with the light at `azimuth_deg` instead of its fixed
// 135 deg: Lambertian shading depends only on the slope's size and its angle to the light, so
// turning every slope by (135 deg - azimuth) about the vertical is the same picture.
schema::ArrayFile shade_lit(const Picture& pic, std::vector<double>& sx, std::vector<double>& sy, double azimuth_deg,
                            std::optional<double> height_per_unit) {
  if (azimuth_deg != 135) {
    const double turn = (135 - azimuth_deg) * std::numbers::pi / 180, c = std::cos(turn), s = std::sin(turn);
    for (std::size_t i = 0; i < sx.size(); ++i) {
      const double x = sx[i], y = sy[i];
      sx[i] = c * x - s * y;
      sy[i] = s * x + c * y;
    }
  }
  return compiler::shade_slopes(pic.nx, pic.ny, sx, sy, height_per_unit);
}

// Shades `drawn` (only terms with a surface) over pic's window at pic's pixel size.
void shade_window(const schema::PatchProgram& drawn, Picture& pic) {
  const double ps = pic.pixel_m;
  runtime::PatchEvaluator eval(drawn);
  const std::size_t n = static_cast<std::size_t>(pic.nx) * pic.ny;
  std::vector<double> sx(n), sy(n);
  runtime::HandState hand;
  for (int row = 0; row < pic.ny; ++row)
    for (int col = 0; col < pic.nx; ++col) {
      // Pixel centres; row 0 is the top of the picture, +y in patch coordinates.
      hand.position_m = {pic.centre_m[0] - 0.5 * pic.window_m[0] + (col + 0.5) * ps,
                         pic.centre_m[1] + 0.5 * pic.window_m[1] - (row + 0.5) * ps};
      const glm::dvec2 f = eval.force_rt(hand, 0.0);
      const std::size_t i = static_cast<std::size_t>(row) * pic.nx + col;
      sx[i] = -f.x;  // F = -grad U: the surface rises against the force
      sy[i] = -f.y;
    }
  pic.light_azimuth_deg = light_azimuth_deg(drawn);
  pic.shade = shade_lit(pic, sx, sy, pic.light_azimuth_deg, std::nullopt);
}

// Shades `drawn` over pic's window from its height field low-pass filtered at the pixel's scale, for
// a texture finer than a pixel (`finest_m`: its finest length). Sampling the force at pixel centres
// beats a fine grating's walls against the pixels (at 0.3125 mm a pixel, a 3.2 mm grating's strongest
// stripes came out 0.8 mm apart). Here each pixel's slope is the mean slope of the height field under a Gaussian
// footprint of sigma 0.7 pixel (frequency response exp(-2 pi^2 sigma^2 f^2)): a period of four pixels
// keeps 55 % of its contrast, one of two pixels 9 %, one of 1.6 pixels 2 %. The footprint is a sum
// over sub-cells half a pixel wide; a sub-cell's slope along x is the force along x integrated across
// it (the height difference over its width, however sharp a wall is: steps of at most the finest
// length, 16 at most), along y likewise. A 128-pixel thumbnail of the finest grating takes about
// 2 million force evaluations.
void shade_window_filtered(const schema::PatchProgram& drawn, double finest_m, Picture& pic) {
  constexpr int m = 2;              // sub-cells a pixel side
  constexpr double sigma_px = 0.7;  // the footprint
  constexpr int max_steps = 16;     // force samples across a sub-cell
  const double ps = pic.pixel_m, cell = ps / m;
  const int steps = std::clamp(static_cast<int>(std::ceil(cell / finest_m)), 1, max_steps);
  const double step = cell / steps;
  const double sigma = sigma_px * m;  // in sub-cells
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  const int cx = pic.nx * m + 2 * radius, cy = pic.ny * m + 2 * radius;  // the sub-grid, with a rim for the footprint
  // Sub-cell (i, j)'s lower-left corner; row j = 0 at the top of the picture.
  const double x0 = pic.centre_m[0] - 0.5 * pic.window_m[0] - radius * cell;
  const double y0 = pic.centre_m[1] + 0.5 * pic.window_m[1] + radius * cell;
  runtime::PatchEvaluator eval(drawn);
  runtime::HandState hand;
  std::vector<double> gx(static_cast<std::size_t>(cx) * cy), gy(gx.size());
  double peak = 0;  // the steepest slope before filtering
  for (int j = 0; j < cy; ++j)
    for (int i = 0; i < cx; ++i) {
      const double left = x0 + i * cell, top = y0 - j * cell;
      double fx = 0, fy = 0;
      for (int k = 0; k < steps; ++k) {
        hand.position_m = {left + (k + 0.5) * step, top - 0.5 * cell};
        const double ax = eval.force_rt(hand, 0.0).x;
        hand.position_m = {left + 0.5 * cell, top - (k + 0.5) * step};
        const double ay = eval.force_rt(hand, 0.0).y;
        fx += ax;
        fy += ay;
        peak = std::max({peak, std::abs(ax), std::abs(ay)});
      }
      // F = -grad h (k folded in): the surface rises against the force.
      gx[static_cast<std::size_t>(j) * cx + i] = -fx / steps;
      gy[static_cast<std::size_t>(j) * cx + i] = -fy / steps;
    }
  // The footprint's weights over sub-cells around a pixel centre (which falls between sub-cells m/2 - 1 and m/2).
  std::vector<double> w(2 * radius + m);
  double sum = 0;
  for (int d = 0; d < static_cast<int>(w.size()); ++d) {
    const double off = (d - radius) + 0.5 - 0.5 * m;  // sub-cell centre minus pixel centre, in sub-cells
    sum += w[d] = std::exp(-0.5 * off * off / (sigma * sigma));
  }
  for (auto& x : w) x /= sum;
  const std::size_t n = static_cast<std::size_t>(pic.nx) * pic.ny;
  std::vector<double> sx(n, 0.0), sy(n, 0.0), rows_x(static_cast<std::size_t>(cy) * pic.nx), rows_y(rows_x.size());
  // Separable: along x for every sub-row, then along y at each pixel.
  for (int j = 0; j < cy; ++j)
    for (int col = 0; col < pic.nx; ++col) {
      double ax = 0, ay = 0;
      for (int d = 0; d < static_cast<int>(w.size()); ++d) {
        const std::size_t at = static_cast<std::size_t>(j) * cx + col * m + d;
        ax += w[d] * gx[at];
        ay += w[d] * gy[at];
      }
      rows_x[static_cast<std::size_t>(j) * pic.nx + col] = ax;
      rows_y[static_cast<std::size_t>(j) * pic.nx + col] = ay;
    }
  for (int row = 0; row < pic.ny; ++row)
    for (int col = 0; col < pic.nx; ++col) {
      double ax = 0, ay = 0;
      for (int d = 0; d < static_cast<int>(w.size()); ++d) {
        const std::size_t at = static_cast<std::size_t>(row * m + d) * pic.nx + col;
        ax += w[d] * rows_x[at];
        ay += w[d] * rows_y[at];
      }
      sx[static_cast<std::size_t>(row) * pic.nx + col] = ax;
      sy[static_cast<std::size_t>(row) * pic.nx + col] = ay;
    }
  // The steepest filtered slope is drawn at 45 deg, unless under a quarter of the steepest before
  // filtering: what is left of a grating too fine for the pixels is drawn as faint as it is, not
  // stretched back to full contrast. (A resolvable grating's walls keep about a quarter or more.)
  double steepest = 0;
  for (std::size_t i = 0; i < n; ++i) steepest = std::max(steepest, std::hypot(sx[i], sy[i]));
  const double reference = std::max(steepest, 0.25 * peak);
  pic.light_azimuth_deg = light_azimuth_deg(drawn);
  pic.shade = shade_lit(pic, sx, sy, pic.light_azimuth_deg, reference > 0 ? std::optional<double>(1 / reference) : std::nullopt);
}

// The program with only the terms that have a surface; the others' reasons appended to `left_out`.
schema::PatchProgram surface_terms(const schema::PatchProgram& program, std::vector<std::string>& left_out) {
  schema::PatchProgram drawn = program;
  drawn.terms.clear();
  for (const auto& t : program.terms)
    if (picture_role(t) != PictureRole::None) drawn.terms.push_back(t);
    else left_out.push_back(why_not_pictured(t));
  return drawn;
}

}  // namespace

Picture render_picture(const schema::PatchProgram& program, int max_side) {
  Picture pic;
  schema::PatchProgram drawn = program;  // only the terms with a surface, evaluated as the runtime would
  drawn.terms.clear();
  bool heights = false, potentials = false;
  std::vector<std::string> potential_kinds;
  double scale = std::numeric_limits<double>::infinity();
  for (const auto& t : program.terms) {
    const PictureRole role = picture_role(t);
    if (role == PictureRole::None) {
      pic.left_out.push_back(why_not_pictured(t));
      continue;
    }
    drawn.terms.push_back(t);
    heights = heights || role == PictureRole::Height;
    if (role == PictureRole::Potential) {
      potentials = true;
      potential_kinds.push_back(term_kind(t));
    }
    scale = std::min(scale, finest_scale(t));
  }
  if (drawn.terms.empty()) return pic;

  const double pw = program.size_m[0], ph = program.size_m[1];
  const double ps = std::min(scale, std::max(pw, ph) / max_side);
  pic.nx = std::clamp(static_cast<int>(std::ceil(pw / ps - 1e-9)), 1, max_side);
  pic.ny = std::clamp(static_cast<int>(std::ceil(ph / ps - 1e-9)), 1, max_side);
  // A non-repeating height field smaller than the patch: show the field, not the flat rim around it.
  for (const auto& t : drawn.terms)
    if (const auto* h = std::get_if<schema::HeightFieldTerm>(&t); h && !h->repeat && drawn.terms.size() == 1) {
      pic.nx = std::min(pic.nx, static_cast<int>(std::lround(h->nx * h->spacing_m[0] / ps)));
      pic.ny = std::min(pic.ny, static_cast<int>(std::lround(h->ny * h->spacing_m[1] / ps)));
    }
  pic.pixel_m = ps;
  pic.window_m[0] = pic.nx * ps;
  pic.window_m[1] = pic.ny * ps;

  shade_window(drawn, pic);

  std::string what;
  if (heights && !potentials)
    what = "Height field of the compiled texture";
  else if (!heights)
    what = "Potential energy U of the " + potential_kinds.front() +
           (potential_kinds.front() == "spring" ? " (U = k p\xC2\xB2 / 2, a bowl)" : "") + ", drawn as a surface (F = -grad U)";
  else
    what = "Texture height field plus the potential energy of the " + potential_kinds.front() +
           " (F = -grad U), drawn as one surface";
  pic.caption = what + ", " + mm(pic.window_m[0]) + " \xC3\x97 " + mm(pic.window_m[1]) + " around the patch centre" +
                (pic.window_m[0] < pw - 1e-9 || pic.window_m[1] < ph - 1e-9
                     ? " (the patch is " + mm(pw) + " \xC3\x97 " + mm(ph) + ")"
                     : "") +
                ". Slopes are the program's force field as the runtime evaluates it (F = -k grad h), shaded as "
                "Sandpaper's .shade pictures: Lambertian, lit " +
                (pic.light_azimuth_deg == 135 ? std::string("from the upper left (azimuth 135\xC2\xB0")
                                              : "across the ridges (azimuth " + std::to_string(static_cast<int>(pic.light_azimuth_deg)) + "\xC2\xB0") +
                ", elevation 45\xC2\xB0), the steepest slope drawn at 45\xC2\xB0.";
  return pic;
}

Picture render_picture_window(const schema::PatchProgram& program, double window_side_m, int side) {
  if (!(window_side_m > 0) || side < 1) throw std::invalid_argument("render_picture_window: window and side must be positive");
  Picture pic;
  const schema::PatchProgram drawn = surface_terms(program, pic.left_out);
  if (drawn.terms.empty()) return pic;
  pic.nx = pic.ny = side;
  pic.pixel_m = window_side_m / side;
  pic.window_m[0] = pic.window_m[1] = window_side_m;
  pic.finer_than_pixel = finest_detail_m(drawn) < pic.pixel_m;
  if (pic.finer_than_pixel) shade_window_filtered(drawn, finest_detail_m(drawn), pic);
  else shade_window(drawn, pic);
  pic.caption = "Height field, " + mm(window_side_m) + " square around the patch centre (common scale)";
  return pic;
}

double finest_detail_m(const schema::PatchProgram& program) {
  double scale = std::numeric_limits<double>::infinity();
  for (const auto& t : program.terms) scale = std::min(scale, finest_scale(t));
  return scale;
}

Picture picture_frame(const double centre_m[2], const double window_m[2], int max_side) {
  if (!(std::isfinite(window_m[0]) && std::isfinite(window_m[1]) && window_m[0] > 0 && window_m[1] > 0) ||
      !(std::isfinite(centre_m[0]) && std::isfinite(centre_m[1])) || max_side < 1)
    throw std::invalid_argument("picture_frame: the window must be positive and finite, the centre finite, max_side >= 1");
  Picture pic;
  const double ps = std::max(window_m[0], window_m[1]) / max_side;
  pic.nx = std::clamp(static_cast<int>(std::lround(window_m[0] / ps)), 1, max_side);
  pic.ny = std::clamp(static_cast<int>(std::lround(window_m[1] / ps)), 1, max_side);
  pic.pixel_m = ps;
  pic.window_m[0] = pic.nx * ps;
  pic.window_m[1] = pic.ny * ps;
  pic.centre_m[0] = centre_m[0];
  pic.centre_m[1] = centre_m[1];
  return pic;
}

Picture render_picture_view(const schema::PatchProgram& program, const double centre_m[2], const double window_m[2],
                            int max_side) {
  Picture pic = picture_frame(centre_m, window_m, max_side);
  const schema::PatchProgram drawn = surface_terms(program, pic.left_out);
  if (drawn.terms.empty()) {
    pic.nx = pic.ny = 0;
    return pic;
  }
  pic.finer_than_pixel = finest_detail_m(drawn) < pic.pixel_m;
  if (pic.finer_than_pixel) shade_window_filtered(drawn, finest_detail_m(drawn), pic);
  else shade_window(drawn, pic);
  pic.caption = "Height field, " + mm(pic.window_m[0]) + " \xC3\x97 " + mm(pic.window_m[1]) + " around (" +
                mm(centre_m[0]) + ", " + mm(centre_m[1]) + ")" +
                (pic.finer_than_pixel ? "; the texture's finest detail is under a pixel (" + mm(pic.pixel_m) + ") here: zoom in for it"
                                      : "");
  return pic;
}

void write_png(const std::filesystem::path& file, const Picture& picture, int side) {
  if (picture.empty()) throw std::invalid_argument("write_png: the picture is empty");
  std::vector<std::uint8_t> grey(picture.shade.values.size());
  for (std::size_t i = 0; i < grey.size(); ++i) grey[i] = static_cast<std::uint8_t>(255 - picture.shade.values[i]);
  int w = picture.nx, h = picture.ny;
  if (side > 0 && std::max(picture.nx, picture.ny) > side) {
    const double f = static_cast<double>(side) / std::max(picture.nx, picture.ny);
    w = std::max(1, static_cast<int>(std::lround(picture.nx * f)));
    h = std::max(1, static_cast<int>(std::lround(picture.ny * f)));
  }
  std::string why;
  // Resampling is OpenImageIO's; a picture drawn at its size (the catalog's) is written by libpng alone.
  const bool written = w == picture.nx && h == picture.ny
                           ? write_png_file(file, picture.nx, picture.ny, 1, grey.data(), why)
                           : compiler::image_io::api().write_png8(file.string(), picture.nx, picture.ny, 1, grey.data(), w, h, why);
  if (!written) throw std::runtime_error("cannot write " + file.string() + ": " + why);
}

}  // namespace sandpaper::catalog
