// Image -> height field -> lateral-force gradient (thesis 3.2.2 "textures from real-world data",
// 3.4 EQ 12-13). Computed once, in float, here; the runtime only samples the result.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "sandpaper/compiler/textures.hpp"

namespace sandpaper::compiler {
namespace {

// Separable Gaussian blur of one axis; `wrap` treats the image as a tile, else edges are clamped.
void blur_axis(std::vector<float>& img, int nx, int ny, double sigma_px, bool along_x, bool wrap) {
  if (sigma_px < 0.3) return;  // narrower than a third of a pixel changes nothing measurable
  int radius = static_cast<int>(std::ceil(3.0 * sigma_px));
  std::vector<double> k(static_cast<std::size_t>(2 * radius + 1));
  double sum = 0;
  for (int i = -radius; i <= radius; ++i) sum += k[static_cast<std::size_t>(i + radius)] = std::exp(-0.5 * i * i / (sigma_px * sigma_px));
  for (auto& w : k) w /= sum;
  int n = along_x ? nx : ny;
  int lines = along_x ? ny : nx;
  std::vector<float> line(static_cast<std::size_t>(n));
  for (int l = 0; l < lines; ++l) {
    auto at = [&](int i) -> float& {
      return along_x ? img[static_cast<std::size_t>(l) * nx + i] : img[static_cast<std::size_t>(i) * nx + l];
    };
    for (int i = 0; i < n; ++i) {
      double s = 0;
      for (int j = -radius; j <= radius; ++j) {
        int q = i + j;
        q = wrap ? ((q % n) + n) % n : std::clamp(q, 0, n - 1);
        s += k[static_cast<std::size_t>(j + radius)] * at(q);
      }
      line[static_cast<std::size_t>(i)] = static_cast<float>(s);
    }
    for (int i = 0; i < n; ++i) at(i) = line[static_cast<std::size_t>(i)];
  }
}

}  // namespace

std::optional<HeightFieldBuild> make_height_field(const ResolvedHeightmap& h, std::optional<double> target_force_N,
                                                  Diagnostics& diags) {
  if (!target_force_N && !h.stylus()) throw InternalError("make_height_field: neither a target force nor depth + press");
  HeightImageRequest req;
  req.path = h.path;
  req.shown_path = h.stated_path;
  req.channel = h.channel;
  req.invert = h.invert;
  if (h.sampling) req.sampling_m = h.sampling->si;
  req.width_m = h.width.si;
  req.height_m = h.height.si;
  HeightImageError err;
  auto img = load_height_image(req, err);
  if (!img) {
    diags.error(err.code, h.location, err.message, err.suggestion);
    return std::nullopt;
  }
  const int nx = img->nx, ny = img->ny;
  // Image row 0 is the top edge, which is +y in patch coordinates, so rows are flipped. The stylus
  // reading maps the source's height range to 0..depth metres; otherwise heights keep the image's
  // unit, and the gain below absorbs it.
  const double to_height = h.stylus() ? h.depth->si / (static_cast<double>(img->hi) - img->lo) : 1.0;
  const double base = h.stylus() ? img->lo : 0.0;
  std::vector<float> height(img->values.size());
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      height[static_cast<std::size_t>(ny - 1 - y) * nx + x] =
          static_cast<float>(to_height * (img->values[static_cast<std::size_t>(y) * nx + x] - base));

  const double dx = h.width.si / nx, dy = h.height.si / ny;  // m per sample
  const double sigma = h.smoothing ? h.smoothing->si : 0.0;
  blur_axis(height, nx, ny, sigma / dx, true, h.repeat);
  blur_axis(height, nx, ny, sigma / dy, false, h.repeat);

  // Central differences (EQ 12-13), one-sided at clamped edges, wrapped for tiles; per metre.
  std::vector<double> gx(height.size()), gy(height.size());
  auto H = [&](int x, int y) { return static_cast<double>(height[static_cast<std::size_t>(y) * nx + x]); };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      int xl, xr, yd, yu;
      if (h.repeat) {
        xl = (x - 1 + nx) % nx, xr = (x + 1) % nx, yd = (y - 1 + ny) % ny, yu = (y + 1) % ny;
      } else {
        xl = std::max(x - 1, 0), xr = std::min(x + 1, nx - 1), yd = std::max(y - 1, 0), yu = std::min(y + 1, ny - 1);
      }
      // Distance between the two samples: two pixels, or one at a clamped edge.
      int span_x = h.repeat ? 2 : xr - xl, span_y = h.repeat ? 2 : yu - yd;
      std::size_t i = static_cast<std::size_t>(y) * nx + x;
      gx[i] = (H(xr, y) - H(xl, y)) / (span_x * dx);
      gy[i] = (H(x, yu) - H(x, yd)) / (span_y * dy);
    }

  // The maximum is taken inside a rim (as the thesis measured gratings away from the edges):
  // 3 sigma of smoothing plus the two outermost pixels, whose differences touch the clamped edge
  // (photographs often have a border row or column). Tiles wrap, so they have no rim.
  int rim_x = h.repeat ? 0 : static_cast<int>(std::ceil(3 * sigma / dx)) + 2;
  int rim_y = h.repeat ? 0 : static_cast<int>(std::ceil(3 * sigma / dy)) + 2;
  if (2 * rim_x >= nx || 2 * rim_y >= ny) {
    diags.error("E0304", h.location, "the smoothing is too wide for the image: nothing is left inside its rim",
                "use a smoothing below a sixth of the image size");
    return std::nullopt;
  }
  double peak = 0;
  for (int y = rim_y; y < ny - rim_y; ++y)
    for (int x = rim_x; x < nx - rim_x; ++x) {
      std::size_t i = static_cast<std::size_t>(y) * nx + x;
      peak = std::max(peak, std::hypot(gx[i], gy[i]));
    }
  if (!(peak > 0)) {
    diags.error("E0403", h.location, "image '" + h.stated_path + "' has no slope inside its rim, so no lateral force",
                "use an image with variation away from its edges, or less smoothing");
    return std::nullopt;
  }
  // k in F = -k grad h: N per unit slope. The stylus: F = press tan(theta) (EQ 5-11).
  const double gain = target_force_N ? *target_force_N / peak : h.press->si;
  HeightFieldBuild b;
  b.max_lateral_force_N = gain * peak;
  if (!target_force_N) b.steepest_slope = peak;
  auto& out = b.term;
  out.nx = static_cast<std::uint32_t>(nx);
  out.ny = static_cast<std::uint32_t>(ny);
  out.spacing_m[0] = dx;
  out.spacing_m[1] = dy;
  out.origin_m[0] = -0.5 * h.width.si + 0.5 * dx;
  out.origin_m[1] = -0.5 * h.height.si + 0.5 * dy;
  out.repeat = h.repeat;
  out.force_x_N.resize(height.size());
  out.force_y_N.resize(height.size());
  for (std::size_t i = 0; i < height.size(); ++i) {
    out.force_x_N[i] = static_cast<float>(-gain * gx[i]);
    out.force_y_N[i] = static_cast<float>(-gain * gy[i]);
  }
  std::ostringstream os;
  os << img->description << ", " << dx * 1e3 << " mm per sample";
  b.summary = os.str();
  return b;
}

}  // namespace sandpaper::compiler
