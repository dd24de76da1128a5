#include "sandpaper/schema/grating_ridges.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sandpaper::schema {

std::vector<GratingRidge> grating_ridges(const std::vector<float>& t) {
  const std::size_t n = t.size();
  std::vector<GratingRidge> out;
  auto sign_at = [&](std::size_t i) { return t[i % n] > 0 ? 1.0 : t[i % n] < 0 ? -1.0 : 0.0; };
  std::vector<std::size_t> nonzero;
  for (std::size_t i = 0; i < n; ++i)
    if (sign_at(i) != 0) nonzero.push_back(i);
  if (nonzero.empty()) return out;
  // Start at a nonzero sample whose previous nonzero sample (cyclically) has the other sign, so that
  // no run is split by the wrap; if every nonzero sample has one sign, the table is one ridge.
  std::size_t start = 0;
  const std::size_t m = nonzero.size();
  while (start < m && sign_at(nonzero[start]) == sign_at(nonzero[(start + m - 1) % m])) ++start;
  if (start == m) {
    float peak = 0;
    for (float f : t) peak = std::max(peak, std::abs(f));
    out.push_back({0, static_cast<double>(n), sign_at(nonzero[0]), peak});
    return out;
  }
  for (std::size_t k = 0; k < m;) {
    const std::size_t first = nonzero[(start + k) % m];
    const double s = sign_at(first);
    std::size_t last = first;
    float peak = 0;
    while (k < m && sign_at(nonzero[(start + k) % m]) == s) {
      const std::size_t i = nonzero[(start + k) % m];
      peak = std::max(peak, std::abs(t[i]));
      last = i;
      ++k;
    }
    // Unwrapped: the run's last sample comes after its first.
    const double last_unwrapped = last >= first ? static_cast<double>(last) : static_cast<double>(last + n);
    out.push_back({static_cast<double>(first), last_unwrapped, s, peak});
  }
  return out;
}

}  // namespace sandpaper::schema
