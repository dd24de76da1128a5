#include "sandpaper/compiler/array_export.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace sandpaper::compiler {
namespace {

schema::ArrayFile sized(int nx, int ny) {
  if (nx > schema::kMaxArraySide || ny > schema::kMaxArraySide || nx < 1 || ny < 1)
    throw std::invalid_argument("an array file holds 1 to 65535 items a side; this one would be " +
                                std::to_string(nx) + " x " + std::to_string(ny));
  schema::ArrayFile a;
  a.width = static_cast<std::uint16_t>(nx);
  a.height = static_cast<std::uint16_t>(ny);
  a.values.resize(static_cast<std::size_t>(nx) * ny);
  return a;
}

std::uint8_t to_byte(double v) { return static_cast<std::uint8_t>(std::clamp(std::floor(v + 0.5), 0.0, 255.0)); }

}  // namespace

schema::ArrayFile quantize_depth(const HeightFieldImage& img) {
  schema::ArrayFile a = sized(img.nx, img.ny);
  // The range of these samples (resampling may reach a little past the source's range).
  auto [lo, hi] = std::minmax_element(img.values.begin(), img.values.end());
  double l = *lo, span = static_cast<double>(*hi) - l;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    a.values[i] = span > 0 ? to_byte(255.0 * (img.values[i] - l) / span) : 0;
  return a;
}

schema::ArrayFile shade_relief(const HeightFieldImage& img, double dx_m, double dy_m, std::optional<double> depth_m) {
  sized(img.nx, img.ny);  // checks the sides before the slopes are allocated
  const int nx = img.nx, ny = img.ny;
  auto [lo, hi] = std::minmax_element(img.values.begin(), img.values.end());
  double span = static_cast<double>(*hi) - *lo;
  // Slopes per unit of the image's values; +y is up the picture (row 0 is the top).
  std::vector<double> sx(img.values.size()), sy(img.values.size());
  auto v = [&](int x, int y) { return static_cast<double>(img.values[static_cast<std::size_t>(y) * nx + x]); };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      int xl = std::max(x - 1, 0), xr = std::min(x + 1, nx - 1), yt = std::max(y - 1, 0), yb = std::min(y + 1, ny - 1);
      std::size_t i = static_cast<std::size_t>(y) * nx + x;
      sx[i] = xr > xl ? (v(xr, y) - v(xl, y)) / ((xr - xl) * dx_m) : 0;
      sy[i] = yb > yt ? (v(x, yt) - v(x, yb)) / ((yb - yt) * dy_m) : 0;
    }
  std::optional<double> scale;  // metres of height per unit of value
  if (depth_m && span > 0) scale = *depth_m / span;
  return shade_slopes(nx, ny, sx, sy, scale);
}

schema::ArrayFile shade_slopes(int nx, int ny, const std::vector<double>& slope_x, const std::vector<double>& slope_y,
                               std::optional<double> height_per_unit) {
  schema::ArrayFile a = sized(nx, ny);
  if (slope_x.size() != a.values.size() || slope_y.size() != a.values.size())
    throw std::invalid_argument("shade_slopes: the slopes are not nx * ny long");
  double scale = 0;
  if (height_per_unit) {
    scale = *height_per_unit;
  } else {
    double steepest = 0;
    for (std::size_t i = 0; i < slope_x.size(); ++i) steepest = std::max(steepest, std::hypot(slope_x[i], slope_y[i]));
    if (steepest > 0) scale = 1.0 / steepest;
  }
  const double lx = -0.5, ly = 0.5, lz = std::sqrt(0.5);  // azimuth 135 deg, elevation 45 deg
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    double gx = scale * slope_x[i], gy = scale * slope_y[i];
    // Surface normal of z = h(x, y): (-h_x, -h_y, 1) / |.|.
    double lit = std::max(0.0, (-gx * lx - gy * ly + lz) / std::sqrt(gx * gx + gy * gy + 1.0));
    a.values[i] = to_byte(255.0 * (1.0 - lit));
  }
  return a;
}

}  // namespace sandpaper::compiler
