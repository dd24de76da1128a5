// Version-1 height maps (thesis 3.5.1, Ch. 4) -> lateral-force field (3.4, EQ 12-13).
// Heights are kept in height steps: 0 .. 2^bits - 1 when quantized (so gradients are whole numbers
// and equal gradients give bit-identical forces), 0 .. 1 otherwise.
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/perlin.hpp"
#include "sandpaper/schema/no_coverage.hpp"

namespace sandpaper::compiler {
namespace {

struct Heights {
  int nx = 0, ny = 0;
  bool wrap = false;  // a tile: smoothing and differences wrap around
  std::vector<double> h;
  double& at(int x, int y) { return h[static_cast<std::size_t>(y) * nx + x]; }
  double at(int x, int y) const { return h[static_cast<std::size_t>(y) * nx + x]; }
};

// Radius of the discrete Gaussian: 3 sigma, as the image path (height_field.cpp) uses.
// Callers bound sigma (kMaxPatternKernel); the clamp keeps the cast defined whatever they pass.
int blur_radius(double sigma_px) {
  return sigma_px > 0 ? static_cast<int>(std::min(std::ceil(3.0 * sigma_px), 1e6)) : 0;
}

// One pass of a separable blur with normalised weights `w` (2r + 1 of them), along x or y.
SANDPAPER_NO_COVERAGE void blur_pass(Heights& a, bool along_x, const std::vector<double>& w, int r) {
  const int n = along_x ? a.nx : a.ny;
  const int lines = along_x ? a.ny : a.nx;
  // Each line is copied out contiguous: a column read in place strides a whole row per tap, and
  // that cache miss, not the arithmetic, was most of a large tile's time.
  std::vector<double> in(static_cast<std::size_t>(n)), line(static_cast<std::size_t>(n));
  // A tile narrower than the kernel: the kernel folded onto the tile gives the same sums with n
  // taps instead of 2r + 1 (a 98 px grid under a 3,700 px sigma took 29 s).
  std::vector<double> folded;
  if (a.wrap && 2 * r + 1 > n) {
    folded.assign(static_cast<std::size_t>(n), 0.0);
    for (int j = -r; j <= r; ++j) folded[static_cast<std::size_t>(((j % n) + n) % n)] += w[static_cast<std::size_t>(j + r)];
  }
  for (int l = 0; l < lines; ++l) {
    for (int i = 0; i < n; ++i) in[static_cast<std::size_t>(i)] = along_x ? a.at(i, l) : a.at(l, i);
    const double* v = in.data();
    for (int i = 0; i < n; ++i) {
      double s = 0;
      if (!folded.empty()) {
        // Taps k = 0 .. n-1 read q = i + k wrapped: two runs without a wrap test, same order of sums.
        const double* f = folded.data();
        for (int k = 0; k < n - i; ++k) s += f[k] * v[i + k];
        for (int k = n - i; k < n; ++k) s += f[k] * v[i + k - n];
      } else {
        for (int j = -r; j <= r; ++j) {
          int q = i + j;
          q = a.wrap ? ((q % n) + n) % n : std::clamp(q, 0, n - 1);
          s += w[static_cast<std::size_t>(j + r)] * v[q];
        }
      }
      line[static_cast<std::size_t>(i)] = s;
    }
    for (int i = 0; i < n; ++i) (along_x ? a.at(i, l) : a.at(l, i)) = line[static_cast<std::size_t>(i)];
  }
}

// Separable Gaussian of `sigma_px`, normalised discrete weights; edges wrap (tiles) or clamp.
void blur(Heights& a, double sigma_px) {
  const int r = blur_radius(sigma_px);
  if (r == 0) return;
  std::vector<double> w(static_cast<std::size_t>(2 * r + 1));
  double sum = 0;
  for (int i = -r; i <= r; ++i) sum += w[static_cast<std::size_t>(i + r)] = std::exp(-0.5 * i * i / (sigma_px * sigma_px));
  for (auto& x : w) x /= sum;
  blur_pass(a, true, w, r);
  blur_pass(a, false, w, r);
}

// Multiply-adds the smoothing of an nx x ny image with these sigmas would take (blur above).
double smoothing_ops(int nx, int ny, bool wrap, double sigma1, double sigma2) {
  double ops = 0;
  for (double sigma : {sigma1, sigma2}) {
    const double taps = 2.0 * blur_radius(sigma) + 1;
    if (sigma > 0) ops += double(nx) * ny * ((wrap ? std::min<double>(taps, nx) : taps) + (wrap ? std::min<double>(taps, ny) : taps));
  }
  return ops;
}

SANDPAPER_NO_COVERAGE void round_heights(Heights& a, bool quantized) {
  if (!quantized) return;
  for (auto& v : a.h) v = std::round(v);
}

// A bars or grid tile: hills `top` high where the position within its period is past the valley;
// a grid's alternate rows of cells shifted by `offset` px.
SANDPAPER_NO_COVERAGE void fill_raised(Heights& a, bool bars, int period, int valley, int offset, double top) {
  for (int y = 0; y < a.ny; ++y) {
    const int shift = (y / period) % 2 ? offset : 0;
    const int ty = ((y % period) + period) % period;
    for (int x = 0; x < a.nx; ++x) {
      const int tx = (((x - (bars ? 0 : shift)) % period) + period) % period;
      const bool up = tx >= valley && (bars || ty >= valley);
      a.at(x, y) = up ? top : 0.0;
    }
  }
}

SANDPAPER_NO_COVERAGE void fill_perlin(Heights& a, const PerlinLattice& noise, double lattice, double top) {
  for (int y = 0; y < a.ny; ++y)
    for (int x = 0; x < a.nx; ++x) a.at(x, y) = top * noise.density(x / lattice, y / lattice, 0.5);
}

// Central differences in height steps over the nx x ny samples from (ox, oy) (EQ 12-13: two
// pixels apart), wrapping on a tile; returns the largest gradient's length.
SANDPAPER_NO_COVERAGE double central_gradients(const Heights& a, int ox, int oy, int nx, int ny, std::vector<double>& gx,
                                               std::vector<double>& gy) {
  double peak = 0;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const int X = x + ox, Y = y + oy;
      auto h = [&](int i, int j) { return a.wrap ? a.at((i + a.nx) % a.nx, (j + a.ny) % a.ny) : a.at(i, j); };
      const std::size_t i = static_cast<std::size_t>(y) * nx + x;
      gx[i] = h(X + 1, Y) - h(X - 1, Y);
      gy[i] = h(X, Y + 1) - h(X, Y - 1);
      peak = std::max(peak, std::hypot(gx[i], gy[i]));
    }
  return peak;
}

int pixels_of(const std::optional<Param>& p, double pixel_m) {
  return p ? static_cast<int>(std::lround(p->si / pixel_m)) : 0;
}

std::string num(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

}  // namespace

bool make_pattern_field(const ResolvedPattern& p, double patch_width_m, double patch_height_m, int bits,
                        double max_force_N, schema::HeightFieldTerm& out, Diagnostics& diags, std::string& summary,
                        double* peak_gradient_steps) {
  const double pixel = p.pixel.si;
  const bool quantized = bits > 0;
  const double top = quantized ? std::ldexp(1.0, bits) - 1 : 1.0;  // the hill's height in height steps
  const double sigma1 = p.kernel ? kernel_sigma_px(p.kernel->si) : 0;
  const double sigma2 = p.refilter ? kernel_sigma_px(p.refilter->si) : 0;
  const bool tile = p.kind == PatternKind::Bars || p.kind == PatternKind::Grid;

  // Patterns that cover the patch are generated with a margin, so that every sample inside the
  // patch has a true central difference and smoothing never meets a clamped edge inside it.
  const int n_x = static_cast<int>(std::lround(patch_width_m / pixel));
  const int n_y = static_cast<int>(std::lround(patch_height_m / pixel));
  const int margin = tile ? 0 : blur_radius(sigma1) + blur_radius(sigma2) + 1;
  if (!tile && (n_x < 1 || n_y < 1 || n_x > kMaxPatternPixels || n_y > kMaxPatternPixels)) {
    diags.error("E0304", p.location,
                "the patch is " + std::to_string(n_x) + " x " + std::to_string(n_y) + " pixels of " + num(pixel * 1e3) +
                    " mm; a " + pattern_kind_name(p.kind) + " pattern needs 1 to " + std::to_string(kMaxPatternPixels) +
                    " pixels a side",
                "use a larger pixel or a smaller patch");
    return false;
  }

  Heights a;
  std::ostringstream os;
  os << pattern_kind_name(p.kind);
  const int valley = pixels_of(p.valley, pixel), hill = pixels_of(p.hill, pixel);
  if (tile) {
    // Bars: valley then hill along x, the same on every row. Grid (reading, docs/TEXTURES.md):
    // square plateaus hill x hill px on valley streets valley px wide; with `offset`, every other
    // row of plateaus is shifted along x.
    const int period = valley + hill;
    const int offset = pixels_of(p.offset, pixel) % period;
    a.wrap = true;
    a.nx = period;
    a.ny = p.kind == PatternKind::Bars ? 1 : (offset ? 2 * period : period);
    if (a.nx > kMaxPatternPixels) {
      diags.error("E0304", p.location, "the pattern's period is " + std::to_string(period) + " pixels",
                  "use at most " + std::to_string(kMaxPatternPixels) + " pixels of valley and hill together");
      return false;
    }
    if (double(a.nx) * a.ny > kMaxPatternArea) {
      diags.error("E0304", p.location,
                  "the pattern's tile would be " + std::to_string(a.nx) + " x " + std::to_string(a.ny) + " px, over " +
                      std::to_string(static_cast<long>(kMaxPatternArea)) + " px in all",
                  "use a larger pixel, or fewer pixels of valley and hill");
      return false;
    }
    if (smoothing_ops(a.nx, a.ny, true, sigma1, sigma2) > kMaxSmoothingOps) {
      diags.error("E0304", p.location, "smoothing the pattern's " + std::to_string(a.nx) + " x " + std::to_string(a.ny) + " px tile with kernel " +
                                           num(p.kernel ? p.kernel->si : 0) + " would take too long",
                  "use a smaller kernel or fewer pixels of valley and hill");
      return false;
    }
    a.h.assign(static_cast<std::size_t>(a.nx) * a.ny, 0.0);
    fill_raised(a, p.kind == PatternKind::Bars, period, valley, offset, top);
    os << ", valley " << valley << " px, hill " << hill << " px";
    if (offset) os << ", alternate rows offset " << offset << " px";
    os << ", tile " << a.nx << " x " << a.ny << " px repeated";
  } else {
    a.wrap = false;
    a.nx = n_x + 2 * margin;
    a.ny = n_y + 2 * margin;
    // The margin grows with the kernel: bound the image and its smoothing before allocating.
    if (double(a.nx) * a.ny > kMaxPatternArea) {
      diags.error("E0304", p.location,
                  "the pattern's array would be " + std::to_string(a.nx) + " x " + std::to_string(a.ny) + " px (kernel margin " +
                      std::to_string(margin) + " px), over " + std::to_string(static_cast<long>(kMaxPatternArea)) + " px in all",
                  "use a larger pixel, a smaller patch or a smaller kernel");
      return false;
    }
    if (a.nx > 4 * kMaxPatternPixels || a.ny > 4 * kMaxPatternPixels ||
        smoothing_ops(a.nx, a.ny, false, sigma1, sigma2) > kMaxSmoothingOps) {
      diags.error("E0304", p.location, "smoothing the pattern (" + std::to_string(n_x) + " x " + std::to_string(n_y) +
                                           " px, kernel margin " + std::to_string(margin) + " px) would take too long",
                  "use a smaller kernel or a larger pixel");
      return false;
    }
    a.h.assign(static_cast<std::size_t>(a.nx) * a.ny, 0.0);
    if (p.kind == PatternKind::Perlin) {
      // Lattice size = feature size (3.5.1); the slice z = 0.5 lies between the lattice planes 0 and 1.
      const double lattice = p.feature->si / pixel;
      const int lx = static_cast<int>(std::floor((a.nx - 1) / lattice)) + 2;
      const int ly = static_cast<int>(std::floor((a.ny - 1) / lattice)) + 2;
      PerlinLattice noise(lx, ly, 2, static_cast<std::uint64_t>(p.seed->si));
      fill_perlin(a, noise, lattice, top);
      os << ", lattice " << num(lattice) << " px, seed " << p.seed->si;
    } else if (p.kind == PatternKind::Noise) {
      // One uniform random height per feature cell, drawn row by row (4.3's jitter stimuli).
      const int cell = pixels_of(p.feature, pixel);
      const int cx = (a.nx + cell - 1) / cell, cy = (a.ny + cell - 1) / cell;
      std::mt19937_64 gen(static_cast<std::uint64_t>(p.seed->si));
      std::vector<double> v(static_cast<std::size_t>(cx) * cy);
      for (auto& x : v) x = unit_interval(gen());
      for (int y = 0; y < a.ny; ++y)
        for (int x = 0; x < a.nx; ++x) a.at(x, y) = top * v[static_cast<std::size_t>(y / cell) * cx + x / cell];
      os << ", cell " << cell << " px, seed " << p.seed->si;
    } else {
      // Stripes (reading): `count` hills across the patch width, at k / (count + 1) of it, each half
      // a spacing wide; 2 stripes on the thesis' 256 px patch are 85 px apart (4.5.2: feature size 85).
      const int count = static_cast<int>(p.count->si);
      const double spacing = static_cast<double>(n_x) / (count + 1);
      for (int y = 0; y < a.ny; ++y)
        for (int x = 0; x < a.nx; ++x) {
          const double centre = x - margin + 0.5;
          bool up = false;
          for (int k = 1; k <= count; ++k) up = up || std::abs(centre - k * spacing) < spacing / 4;
          a.at(x, y) = up ? top : 0.0;
        }
      os << ", " << count << " hill" << (count == 1 ? "" : "s") << " " << num(spacing) << " px apart";
    }
    os << ", " << n_x << " x " << n_y << " px";
  }
  round_heights(a, quantized);
  if (sigma1 > 0) {
    blur(a, sigma1);
    round_heights(a, quantized);
    os << ", kernel " << num(p.kernel->si) << " (sigma " << num(sigma1) << " px)";
  }
  if (sigma2 > 0) {
    blur(a, sigma2);
    round_heights(a, quantized);
    os << ", refiltered with kernel " << num(p.refilter->si);
  }
  os << ", " << num(pixel * 1e3) << " mm per pixel, " << (quantized ? std::to_string(bits) + "-bit" : "float")
     << " heights";

  // Lateral-force gradient in height steps per two pixels (EQ 12-13): f = -k (h(i+1) - h(i-1)).
  const int ox = tile ? 0 : margin, oy = tile ? 0 : margin;
  const int nx = tile ? a.nx : n_x, ny = tile ? a.ny : n_y;
  std::vector<double> gx(static_cast<std::size_t>(nx) * ny), gy(gx.size());
  const double peak = central_gradients(a, ox, oy, nx, ny, gx, gy);
  if (!(peak > 0)) {
    diags.error("E0304", p.location, "the pattern has no slope, so no lateral force (" + os.str() + ")",
                "use more height bits, less smoothing or a larger feature");
    return false;
  }
  const double gain = max_force_N / peak;
  if (peak_gradient_steps) *peak_gradient_steps = peak;
  out = {};
  out.nx = static_cast<std::uint32_t>(nx);
  out.ny = static_cast<std::uint32_t>(ny);
  out.spacing_m[0] = out.spacing_m[1] = pixel;
  out.origin_m[0] = -0.5 * nx * pixel + 0.5 * pixel;
  out.origin_m[1] = -0.5 * ny * pixel + 0.5 * pixel;
  out.repeat = tile;
  out.force_x_N.resize(gx.size());
  out.force_y_N.resize(gy.size());
  for (std::size_t i = 0; i < gx.size(); ++i) {
    out.force_x_N[i] = static_cast<float>(-gain * gx[i]);
    out.force_y_N[i] = static_cast<float>(-gain * gy[i]);
  }
  summary = os.str();
  return true;
}

schema::GratingTerm make_seed_grating(double period_m, double hill, double orientation_rad, double sigma_seed_px,
                                      int bits, double max_force_N) {
  const int n = kSeedPixels;
  const double top = bits > 0 ? std::ldexp(1.0, bits) - 1 : 1.0;
  // Hill pixels centred on u = 0: i in [-hill_px / 2, hill_px - hill_px / 2), wrapped.
  const int hill_px = std::clamp(static_cast<int>(std::lround(hill * n)), 1, n - 1);
  Heights a;
  a.nx = n;
  a.ny = 1;  // the thesis' seed is 32 rows thick, all alike: one row holds it
  a.wrap = true;
  a.h.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = -hill_px / 2; i < hill_px - hill_px / 2; ++i) a.h[static_cast<std::size_t>((i + n) % n)] = top;
  blur(a, sigma_seed_px);
  round_heights(a, bits > 0);
  std::vector<double> d(static_cast<std::size_t>(n));
  double peak = 0;
  for (int i = 0; i < n; ++i) {
    d[static_cast<std::size_t>(i)] = a.h[static_cast<std::size_t>((i + 1) % n)] - a.h[static_cast<std::size_t>((i + n - 1) % n)];
    peak = std::max(peak, std::abs(d[static_cast<std::size_t>(i)]));
  }
  schema::GratingTerm g;
  g.period_m = period_m;
  g.orientation_rad = orientation_rad;
  g.force_N.resize(static_cast<std::size_t>(n));
  const double gain = peak > 0 ? max_force_N / peak : 0;
  for (std::size_t i = 0; i < d.size(); ++i) g.force_N[i] = static_cast<float>(-gain * d[i]);
  return g;
}

}  // namespace sandpaper::compiler
