// Version-2 grating (thesis 3.5.2): square wave, Gaussian-smoothed, scaled to the period.
#include <algorithm>
#include <cmath>

#include "sandpaper/compiler/textures.hpp"

namespace sandpaper::compiler {

schema::GratingTerm make_grating(double period_m, double hill, double orientation_rad, double sigma_m,
                                 double max_force_N) {
  // h = square wave (1 on the hill, 0 in the valley) convolved with a Gaussian, so
  // dh/du = sum over periods of [phi((u - a)/sigma) - phi((u - b)/sigma)] / sigma, a and b the
  // hill's rising and falling edges. Evaluated in closed form: no sampling of the square wave.
  const double a = -0.5 * hill * period_m;
  const double b = 0.5 * hill * period_m;
  const int reach = static_cast<int>(std::ceil(8.0 * sigma_m / period_m)) + 1;
  auto gauss = [&](double x) { return std::exp(-0.5 * (x / sigma_m) * (x / sigma_m)); };
  std::vector<double> slope(kGratingSamples);
  double peak = 0;
  for (int i = 0; i < kGratingSamples; ++i) {
    double u = period_m * i / kGratingSamples;
    double s = 0;
    for (int k = -reach; k <= reach; ++k) s += gauss(u - a + k * period_m) - gauss(u - b + k * period_m);
    slope[static_cast<std::size_t>(i)] = s;
    peak = std::max(peak, std::abs(s));
  }
  schema::GratingTerm g;
  g.period_m = period_m;
  g.orientation_rad = orientation_rad;
  g.force_N.resize(kGratingSamples);
  // F = -k dh/du: downhill, toward the valley (thesis 3.4). k is chosen for the target maximum.
  const double gain = peak > 0 ? max_force_N / peak : 0;
  for (std::size_t i = 0; i < slope.size(); ++i) g.force_N[i] = static_cast<float>(-gain * slope[i]);
  return g;
}

}  // namespace sandpaper::compiler
