#pragma once
// Perlin's solid noise as the thesis describes it (Minsky 1995, 3.5.1, after Perlin 1985): a cubic
// lattice of control values in [0, 1], interpolated in each of the three axes by Perlin's cubic
// blend s(t) = 3t^2 - 2t^3 ("tricubic interpolation"). The blend weights of the 8 surrounding control
// values are non-negative and sum to 1, so densities stay in [0, 1] and equal the control values
// at the lattice points. Deterministic on every platform: the control values come from
// std::mt19937_64 (fully specified by the C++ standard) through unit_interval(), not through a
// standard distribution, whose algorithm the standard leaves open.
#include <cstdint>
#include <vector>

namespace sandpaper::compiler {

// A 64-bit generator output mapped to [0, 1): its top 53 bits times 2^-53.
double unit_interval(std::uint64_t raw);

class PerlinLattice {
 public:
  // nx * ny * nz control values (each >= 2), drawn in order k, j, i (i fastest) from
  // std::mt19937_64(seed). Throws std::invalid_argument for a side below 2.
  PerlinLattice(int nx, int ny, int nz, std::uint64_t seed);

  double control(int i, int j, int k) const;
  // Density at lattice coordinates (x, y, z), each clamped to [0, side - 1].
  double density(double x, double y, double z) const;

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }

 private:
  int nx_, ny_, nz_;
  std::vector<double> control_;
};

// Perlin's cubic blend, s(0) = 0, s(1) = 1, s'(0) = s'(1) = 0.
constexpr double perlin_blend(double t) { return t * t * (3.0 - 2.0 * t); }

}  // namespace sandpaper::compiler
