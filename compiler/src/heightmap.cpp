// Image -> height field -> lateral-force gradient (thesis 3.2.2 "textures from real-world data",
// 3.4 EQ 12-13). Computed once, in float, here; the runtime only samples the result.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <OpenImageIO/imageio.h>

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

bool make_height_field(const ResolvedHeightmap& h, double max_force_N, schema::HeightFieldTerm& out,
                       Diagnostics& diags, std::string& summary) {
  auto in = OIIO::ImageInput::open(h.path);
  if (!in) {
    std::string why = OIIO::geterror();
    diags.error("E0401", h.location, "cannot read image '" + h.stated_path + "': " + (why.empty() ? "unreadable" : why),
                "check the path (relative to the material file's folder) and that the file is an image");
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  long long pixels = static_cast<long long>(spec.width) * spec.height;
  if (spec.width < 3 || spec.height < 3 || spec.nchannels < 1) {
    diags.error("E0402", h.location, "image '" + h.stated_path + "' is " + std::to_string(spec.width) + " x " +
                                         std::to_string(spec.height) + " px; a height map needs at least 3 x 3",
                "use a larger image");
    return false;
  }
  if (pixels > kMaxImagePixels) {
    diags.error("E0402", h.location, "image '" + h.stated_path + "' has " + std::to_string(pixels) +
                                         " px, more than the limit of 4096 x 4096",
                "scale the image down before using it");
    return false;
  }
  const int nx = spec.width, ny = spec.height, nc = spec.nchannels;
  std::vector<float> raw(static_cast<std::size_t>(pixels) * static_cast<std::size_t>(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data())) {
    diags.error("E0401", h.location, "cannot read image '" + h.stated_path + "': " + in->geterror(),
                "the file may be truncated or corrupt");
    return false;
  }
  in->close();

  // Grey level is height. Colour images: Rec. 709 luminance of R, G, B; alpha is ignored.
  // Image row 0 is the top edge, which is +y in patch coordinates, so rows are flipped.
  std::vector<float> height(static_cast<std::size_t>(pixels));
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const float* p = &raw[(static_cast<std::size_t>(y) * nx + x) * static_cast<std::size_t>(nc)];
      float v = nc >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
      height[static_cast<std::size_t>(ny - 1 - y) * nx + x] = v;
    }
  auto [lo, hi] = std::minmax_element(height.begin(), height.end());
  if (!std::isfinite(*lo) || !std::isfinite(*hi)) {
    diags.error("E0403", h.location, "image '" + h.stated_path + "' holds non-finite values (NaN or infinity)",
                "replace them before using the image as a height map");
    return false;
  }
  if (*hi - *lo <= 0) {
    diags.error("E0403", h.location, "image '" + h.stated_path + "' is all one value: it has no slope, so no lateral force",
                "use an image with some variation in grey level");
    return false;
  }

  const double dx = h.width.si / nx, dy = h.height.si / ny;  // m per pixel
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
    return false;
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
    return false;
  }
  const double gain = max_force_N / peak;  // k in F = -k grad h, N per unit slope
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
  os << nx << " x " << ny << " px, " << nc << " channel" << (nc > 1 ? "s" : "") << " (" << spec.format.c_str()
     << "), " << dx * 1e3 << " mm per pixel";
  summary = os.str();
  return true;
}

}  // namespace sandpaper::compiler
