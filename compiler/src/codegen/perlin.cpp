// Perlin solid noise (thesis 3.5.1; Perlin 1985), seedable and the same on every platform.
#include "sandpaper/compiler/perlin.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "sandpaper/schema/no_coverage.hpp"

namespace sandpaper::compiler {

double unit_interval(std::uint64_t raw) { return static_cast<double>(raw >> 11) * 0x1.0p-53; }

PerlinLattice::PerlinLattice(int nx, int ny, int nz, std::uint64_t seed) : nx_(nx), ny_(ny), nz_(nz) {
  if (nx < 2 || ny < 2 || nz < 2) throw std::invalid_argument("PerlinLattice: each side needs at least 2 control points");
  std::mt19937_64 gen(seed);
  control_.resize(static_cast<std::size_t>(nx) * ny * nz);
  for (auto& c : control_) c = unit_interval(gen());
}

SANDPAPER_NO_COVERAGE double PerlinLattice::control(int i, int j, int k) const {
  return control_[(static_cast<std::size_t>(k) * ny_ + j) * nx_ + i];
}

namespace {

// Cell and fraction along one axis; the last lattice point belongs to the cell before it.
// Uninstrumented, as density() below: they run once per pixel of a Perlin pattern (no_coverage.hpp).
SANDPAPER_NO_COVERAGE void split(double v, int n, int& cell, double& t) {
  v = std::clamp(v, 0.0, static_cast<double>(n - 1));
  cell = std::min(static_cast<int>(std::floor(v)), n - 2);
  t = perlin_blend(v - cell);
}

// (1 - t) a + t b: exactly a at t = 0 and b at t = 1, so lattice points keep their values.
SANDPAPER_NO_COVERAGE double lerp(double a, double b, double t) { return (1 - t) * a + t * b; }

}  // namespace

SANDPAPER_NO_COVERAGE double PerlinLattice::density(double x, double y, double z) const {
  int i = 0, j = 0, k = 0;
  double tx = 0, ty = 0, tz = 0;
  split(x, nx_, i, tx);
  split(y, ny_, j, ty);
  split(z, nz_, k, tz);
  double plane[2];
  for (int p = 0; p < 2; ++p) {
    const double bottom = lerp(control(i, j, k + p), control(i + 1, j, k + p), tx);
    const double top = lerp(control(i, j + 1, k + p), control(i + 1, j + 1, k + p), tx);
    plane[p] = lerp(bottom, top, ty);
  }
  return lerp(plane[0], plane[1], tz);
}

}  // namespace sandpaper::compiler
