// Image -> height field -> lateral-force gradient (thesis 3.2.2 "textures from real-world data",
// 3.4 EQ 12-13). Computed once, in float, here; the runtime only samples the result.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "sandpaper/compiler/textures.hpp"
#include "sandpaper/schema/no_coverage.hpp"

namespace sandpaper::compiler {
namespace {

// Rows are independent in every pass below, so they are spread over the cores (up to 8 threads,
// each taking the next row). Each output value is summed in the same order as a single thread
// would, so the result does not depend on the number of threads. Small grids stay on this thread.
// f(y, scratch) gets `scratch_size` values of T of its thread's own, reused from row to row and not
// cleared: one allocation a thread, not one a row (under ASan, whose quarantine hands out fresh
// pages for each, those made a fifth of the image fuzz target's time).
template <class T, class F>
void for_each_row(int rows, std::size_t scratch_size, F&& f) {
  const int threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 8);
  auto work = [&](std::atomic<int>& next) {
    std::vector<T> scratch(scratch_size);
    for (int y = next++; y < rows; y = next++) f(y, scratch.data());
  };
  std::atomic<int> next{0};
  if (threads == 1 || rows < 64) {
    work(next);
    return;
  }
  std::vector<std::jthread> helpers;
  for (int t = 1; t < threads; ++t) helpers.emplace_back(work, std::ref(next));
  work(next);
}

template <class F>
void for_each_row(int rows, F&& f) {
  for_each_row<char>(rows, 0, [&](int y, char*) { f(y); });
}

std::vector<double> gaussian_kernel(double sigma_px, int& radius) {
  radius = static_cast<int>(std::ceil(3.0 * sigma_px));
  std::vector<double> k(static_cast<std::size_t>(2 * radius + 1));
  double sum = 0;
  for (int i = -radius; i <= radius; ++i) sum += k[static_cast<std::size_t>(i + radius)] = std::exp(-0.5 * i * i / (sigma_px * sigma_px));
  for (auto& w : k) w /= sum;
  return k;
}

SANDPAPER_NO_COVERAGE int edge(int q, int n, bool wrap) { return wrap ? ((q % n) + n) % n : std::clamp(q, 0, n - 1); }

// The per-sample kernels of the passes below, apart so that the fuzzing build leaves their loops
// uninstrumented (no_coverage.hpp, F36); each computes exactly what the pass did inline.

// One image row into its height row: to_height * (value - base).
SANDPAPER_NO_COVERAGE void height_row(const float* image_row, float* height_row, int nx, double to_height, double base) {
  for (int x = 0; x < nx; ++x) height_row[x] = static_cast<float>(to_height * (image_row[x] - base));
}

// Where the whole kernel lies inside the row no edge rule applies: the same sum in the same order,
// without edge()'s modulo on every tap (the bits are those of the edge-ruled sum).
SANDPAPER_NO_COVERAGE void blur_row_x(const float* row, float* line, int nx, const std::vector<double>& k, int radius, bool wrap) {
  const double* w = k.data();
  for (int i = 0; i < nx; ++i) {
    double s = 0;
    if (i >= radius && i + radius < nx) {
      const float* from = row + (i - radius);
      for (int t = 0; t <= 2 * radius; ++t) s += w[t] * from[t];
    } else {
      for (int j = -radius; j <= radius; ++j) s += w[j + radius] * row[edge(i + j, nx, wrap)];
    }
    line[i] = static_cast<float>(s);
  }
}

SANDPAPER_NO_COVERAGE void add_weighted_row(double* acc, const float* in, double w, int nx) {
  for (int x = 0; x < nx; ++x) acc[x] += w * in[x];
}

SANDPAPER_NO_COVERAGE void store_row(float* out, const double* acc, int nx) {
  for (int x = 0; x < nx; ++x) out[x] = static_cast<float>(acc[x]);
}

// Central differences of the interior samples 1 .. nx - 2 of a row, from the rows below and above.
SANDPAPER_NO_COVERAGE void interior_gradients(const float* row, const float* down, const float* up, int nx, double span_dx,
                                              double span_dy, double* gx, double* gy) {
  for (int x = 1; x < nx - 1; ++x) {
    gx[x] = (static_cast<double>(row[x + 1]) - static_cast<double>(row[x - 1])) / span_dx;
    gy[x] = (static_cast<double>(up[x]) - static_cast<double>(down[x])) / span_dy;
  }
}

// Central differences of a whole row of a tile, wrapping at every edge.
SANDPAPER_NO_COVERAGE void wrapped_gradients(const float* height, int nx, int ny, int y, double dx, double dy, double* gx,
                                             double* gy) {
  const float* row = height + static_cast<std::size_t>(y) * nx;
  const float* down = height + static_cast<std::size_t>((y - 1 + ny) % ny) * nx;
  const float* up = height + static_cast<std::size_t>((y + 1) % ny) * nx;
  for (int x = 0; x < nx; ++x) {
    const int xl = (x - 1 + nx) % nx, xr = (x + 1) % nx;
    gx[x] = (static_cast<double>(row[xr]) - static_cast<double>(row[xl])) / (2 * dx);
    gy[x] = (static_cast<double>(up[x]) - static_cast<double>(down[x])) / (2 * dy);
  }
}

SANDPAPER_NO_COVERAGE double largest_square(const double* gx, const double* gy, int from, int to) {
  double m = 0;
  for (int x = from; x < to; ++x) m = std::max(m, gx[x] * gx[x] + gy[x] * gy[x]);
  return m;
}

SANDPAPER_NO_COVERAGE void force_row(const double* gx, const double* gy, int nx, double gain, float* fx, float* fy) {
  for (int x = 0; x < nx; ++x) {
    fx[x] = static_cast<float>(-gain * gx[x]);
    fy[x] = static_cast<float>(-gain * gy[x]);
  }
}

std::string mm_text(double m) {
  std::ostringstream os;
  os.precision(3);
  os << m * 1e3 << " mm";
  return os.str();
}

// E0304 for smoothing past kMaxImageSmoothingOps, suggesting the finest `sampling` (over the same
// width x height, at least 3 x 3 and within kMaxImagePixels, its resize of the source's
// source_nx x source_ny px within the resize limits) or the largest smoothing that fits. Coarser
// sampling lowers both counts, and less smoothing lowers the blur's, to 0 taps at last; a sampling
// is named only if one fits before 3 samples a side.
void refuse_slow_smoothing(const ResolvedHeightmap& h, int nx, int ny, int source_nx, int source_ny, double ops,
                           Diagnostics& diags) {
  const double w = h.width.si, hh = h.height.si, sigma = h.smoothing->si;
  double s = std::min(w / nx, hh / ny);
  const auto fits_at = [&](double sampling) {
    const double fx = std::max(1.0, std::round(w / sampling)), fy = std::max(1.0, std::round(hh / sampling));
    return fx >= 3 && fy >= 3 && fx * fy <= static_cast<double>(kMaxImagePixels) &&
           smoothing_ops(fx, fy, w / fx, hh / fy, sigma) <= kMaxImageSmoothingOps &&
           resample_within_limits(source_nx, source_ny, static_cast<int>(fx), static_cast<int>(fy));
  };
  while (s < std::min(w, hh) / 3 && !fits_at(s)) s *= 1.02;
  double fits = sigma;
  while (smoothing_ops(nx, ny, w / nx, hh / ny, fits) > kMaxImageSmoothingOps) fits *= 0.98;
  std::ostringstream msg;
  msg.precision(3);
  msg << "smoothing " << mm_text(sigma) << " over the image's " << nx << " x " << ny << " samples (" << mm_text(w / nx) << " x "
      << mm_text(hh / ny) << " each) would take " << ops << " multiply-adds, more than the limit of " << kMaxImageSmoothingOps;
  const std::string less = "use a smoothing of at most " + mm_text(fits * 0.995);
  diags.error("E0304", h.location, msg.str(),
              fits_at(s * 1.005) ? "resample the image with `sampling " + mm_text(s * 1.005) + "` or more, or " + less : less);
}

// Without `repeat` the peak slope is taken inside a rim of 3 sigma plus the outermost two samples
// (make_height_field). A field under 5 samples a side has nothing inside even unsmoothed: E0402,
// naming a `sampling` that gives 5 a side where its resize fits. Otherwise the smoothing is too wide:
// E0304, naming the widest that leaves a sample inside, from ceil(3 sigma / d) <= floor((n - 1) / 2) - 2.
void refuse_empty_inside_rim(const ResolvedHeightmap& h, int nx, int ny, int source_nx, int source_ny, double sigma,
                             Diagnostics& diags) {
  const double w = h.width.si, hh = h.height.si;
  std::ostringstream shape;
  shape << nx << " x " << ny << " samples (" << mm_text(w / nx) << " x " << mm_text(hh / ny) << " each)";
  constexpr int kSmallest = 5;
  if (nx < kSmallest || ny < kSmallest) {
    const double s = std::min(w, hh) / kSmallest * 0.999;
    const double fx = std::round(w / s), fy = std::round(hh / s);
    const bool sampling_fits = fx * fy <= static_cast<double>(kMaxImagePixels) &&
                               resample_within_limits(source_nx, source_ny, static_cast<int>(fx), static_cast<int>(fy));
    const std::string tiles = "or add `repeat` if the picture tiles";
    diags.error("E0402", h.location,
                "the height field is " + shape.str() + ": without `repeat` its slope is taken away from the outermost two "
                "samples on each side, so it needs at least 5 x 5 samples",
                sampling_fits ? "resample it with `sampling " + mm_text(s) + "` or finer, " + tiles : "use a larger picture, " + tiles);
    return;
  }
  const auto widest = [](int n, double d) { return (std::floor((n - 1) / 2.0) - 2) * d / 3; };
  const double fits = std::min(widest(nx, w / nx), widest(ny, hh / ny)) * 0.995;
  diags.error("E0304", h.location,
              "smoothing " + mm_text(sigma) + " is too wide for the image's " + shape.str() +
                  ": without `repeat` its slope is taken 3 smoothings plus two samples in from each edge, and nothing is left",
              fits > 0 ? "use a smoothing of at most " + mm_text(fits) + ", or add `repeat` if the picture tiles"
                       : "remove the smoothing, or add `repeat` if the picture tiles");
}

// Separable Gaussian blur; `wrap` treats the image as a tile, else edges are clamped. Along x each
// row is blurred in place; along y each output row sums whole input rows (cache-friendly), into
// a second image.
void blur_x(std::vector<float>& img, int nx, int ny, double sigma_px, bool wrap) {
  if (sigma_px < 0.3) return;  // narrower than a third of a pixel changes nothing measurable
  int radius = 0;
  const auto k = gaussian_kernel(sigma_px, radius);
  for_each_row<float>(ny, static_cast<std::size_t>(nx), [&](int y, float* line) {
    float* row = img.data() + static_cast<std::size_t>(y) * nx;
    blur_row_x(row, line, nx, k, radius, wrap);
    std::copy(line, line + nx, row);
  });
}

void blur_y(std::vector<float>& img, int nx, int ny, double sigma_px, bool wrap) {
  if (sigma_px < 0.3) return;
  int radius = 0;
  const auto k = gaussian_kernel(sigma_px, radius);
  std::vector<float> out(img.size());
  for_each_row<double>(ny, static_cast<std::size_t>(nx), [&](int y, double* acc) {
    std::fill(acc, acc + nx, 0.0);
    for (int j = -radius; j <= radius; ++j) {
      const float* in = img.data() + static_cast<std::size_t>(edge(y + j, ny, wrap)) * nx;
      add_weighted_row(acc, in, k[static_cast<std::size_t>(j + radius)], nx);
    }
    store_row(out.data() + static_cast<std::size_t>(y) * nx, acc, nx);
  });
  img.swap(out);
}

}  // namespace

std::optional<HeightFieldBuild> make_height_field(const ResolvedHeightmap& h, std::optional<double> target_force_N,
                                                  Diagnostics& diags, bool keep_heights) {
  if (!target_force_N && !h.stylus()) throw InternalError("make_height_field: neither a target force nor depth + press");
  HeightFieldImageRequest req;
  req.path = h.path;
  req.shown_path = h.stated_path;
  req.channel = h.channel;
  req.invert = h.invert;
  if (h.sampling) req.sampling_m = h.sampling->si;
  req.width_m = h.width.si;
  req.height_m = h.height.si;
  if (h.smoothing) req.smoothing_m = h.smoothing->si;
  HeightFieldImageError err;
  auto img = load_height_field_image(req, err);
  if (!img) {
    diags.error(schema::Code::of(err.code), h.location, err.message, err.suggestion);
    return std::nullopt;
  }
  const int nx = img->nx, ny = img->ny;
  if (h.smoothing) {
    const double ops = smoothing_ops(nx, ny, h.width.si / nx, h.height.si / ny, h.smoothing->si);
    if (ops > kMaxImageSmoothingOps) {
      refuse_slow_smoothing(h, nx, ny, img->source_nx, img->source_ny, ops, diags);
      return std::nullopt;
    }
  }
  // Image row 0 is the top edge, which is +y in patch coordinates, so rows are flipped. The stylus
  // reading maps the source's height range to 0..depth metres; otherwise heights keep the image's
  // unit, and the gain below absorbs it.
  const double to_height = h.stylus() ? h.depth->si / (static_cast<double>(img->hi) - img->lo) : 1.0;
  const double base = h.stylus() ? img->lo : 0.0;
  std::vector<float> height(img->values.size());
  for_each_row(ny, [&](int y) {
    height_row(img->values.data() + static_cast<std::size_t>(y) * nx, height.data() + static_cast<std::size_t>(ny - 1 - y) * nx,
               nx, to_height, base);
  });
  std::vector<float>().swap(img->values);  // the image is not needed again: give its memory back now

  const double dx = h.width.si / nx, dy = h.height.si / ny;  // m per sample
  const double sigma = h.smoothing ? h.smoothing->si : 0.0;
  blur_x(height, nx, ny, sigma / dx, h.repeat);
  blur_y(height, nx, ny, sigma / dy, h.repeat);

  // Central differences (EQ 12-13), one-sided at clamped edges, wrapped for tiles; per metre.
  // Computed where needed (twice: for the peak, then for the forces) rather than kept: two grids
  // of doubles would be four times the patch's size.
  auto H = [&](int x, int y) { return static_cast<double>(height[static_cast<std::size_t>(y) * nx + x]); };
  const auto gradient = [&](int x, int y) {
    int xl, xr, yd, yu;
    if (h.repeat) {
      xl = (x - 1 + nx) % nx, xr = (x + 1) % nx, yd = (y - 1 + ny) % ny, yu = (y + 1) % ny;
    } else {
      xl = std::max(x - 1, 0), xr = std::min(x + 1, nx - 1), yd = std::max(y - 1, 0), yu = std::min(y + 1, ny - 1);
    }
    // Distance between the two samples: two pixels, or one at a clamped edge.
    const int span_x = h.repeat ? 2 : xr - xl, span_y = h.repeat ? 2 : yu - yd;
    return std::pair<double, double>{(H(xr, y) - H(xl, y)) / (span_x * dx), (H(x, yu) - H(x, yd)) / (span_y * dy)};
  };
  // One row of gradients into gx, gy: the edges through `gradient`, the interior (the same
  // arithmetic, without the per-pixel edge logic) straight from the three rows it reads.
  const auto gradient_row = [&](int y, double* gx, double* gy) {
    if (h.repeat) {
      wrapped_gradients(height.data(), nx, ny, y, dx, dy, gx, gy);
      return;
    }
    if (y == 0 || y == ny - 1 || nx < 3) {
      for (int x = 0; x < nx; ++x) std::tie(gx[x], gy[x]) = gradient(x, y);
      return;
    }
    const float* row = height.data() + static_cast<std::size_t>(y) * nx;
    const float* down = row - nx;
    const float* up = row + nx;
    const double span_dx = 2 * dx, span_dy = 2 * dy;
    std::tie(gx[0], gy[0]) = gradient(0, y);
    interior_gradients(row, down, up, nx, span_dx, span_dy, gx, gy);
    std::tie(gx[nx - 1], gy[nx - 1]) = gradient(nx - 1, y);
  };

  // The maximum is taken inside a rim (as the thesis measured gratings away from the edges):
  // 3 sigma of smoothing plus the two outermost pixels, whose differences touch the clamped edge
  // (photographs often have a border row or column). Tiles wrap, so they have no rim.
  int rim_x = h.repeat ? 0 : static_cast<int>(std::ceil(3 * sigma / dx)) + 2;
  int rim_y = h.repeat ? 0 : static_cast<int>(std::ceil(3 * sigma / dy)) + 2;
  if (2 * rim_x >= nx || 2 * rim_y >= ny) {
    refuse_empty_inside_rim(h, nx, ny, img->source_nx, img->source_ny, sigma, diags);
    return std::nullopt;
  }
  // The peak |grad h|: rows find their largest squared magnitude (cheap), then hypot (as before,
  // so the result is bit for bit the single-threaded one) is taken only of the values that can be it.
  std::vector<double> row_peak_sq(static_cast<std::size_t>(ny), 0.0);
  const int inner_rows = ny - 2 * rim_y;
  // gradient_row writes every sample of gx and gy, so the reused scratch needs no clearing.
  for_each_row<double>(inner_rows, 2 * static_cast<std::size_t>(nx), [&](int r, double* g) {
    const int y = r + rim_y;
    double *gx = g, *gy = g + nx;
    gradient_row(y, gx, gy);
    row_peak_sq[static_cast<std::size_t>(y)] = largest_square(gx, gy, rim_x, nx - rim_x);
  });
  const double peak_sq = *std::max_element(row_peak_sq.begin(), row_peak_sq.end());
  const double candidate_sq = peak_sq * (1 - 1e-9);  // far wider than the rounding of x^2 + y^2
  double peak = 0;
  for (int y = rim_y; y < ny - rim_y; ++y) {
    if (!(row_peak_sq[static_cast<std::size_t>(y)] >= candidate_sq) || peak_sq == 0) continue;
    for (int x = rim_x; x < nx - rim_x; ++x) {
      const auto [gx, gy] = gradient(x, y);
      if (gx * gx + gy * gy >= candidate_sq) peak = std::max(peak, std::hypot(gx, gy));
    }
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
  for_each_row<double>(ny, 2 * static_cast<std::size_t>(nx), [&](int y, double* g) {
    double *gx = g, *gy = g + nx;
    gradient_row(y, gx, gy);
    force_row(gx, gy, nx, gain, out.force_x_N.data() + static_cast<std::size_t>(y) * nx,
              out.force_y_N.data() + static_cast<std::size_t>(y) * nx);
  });
  std::ostringstream os;
  os << img->description << ", " << dx * 1e3 << " mm per sample";
  b.summary = os.str();
  if (keep_heights) {
    b.heights = std::move(height);
    b.gain = gain;
  }
  return b;
}

}  // namespace sandpaper::compiler
