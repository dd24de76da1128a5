#pragma once
// The ridges of a grating's force table: what "a ridge" means wherever a felt peak is measured or
// predicted (explain's felt at speed, run's felt_peak_N; docs/TEXTURES.md "Felt at speed").
#include <vector>

namespace sandpaper::schema {

// A run of force samples of one sign around the periodic table. `first` and `last` are sample
// indices; `last` may pass the table's size when the run wraps. The ridge's force lives strictly
// between first - 1 and last + 1 (the zero-or-opposite samples either side, read linearly).
struct GratingRidge {
  double first = 0, last = 0;
  double sign = 0;  // +1 or -1: the sign of the force along the grating normal
  double peak = 0;  // largest |F| of its samples, N
};

// The ridges of a periodic force table `t` (N per sample), in order from the first. Zero samples do
// not end a run: an 8-bit table with wide walls has zeros between small steps of one wall, which is
// one ridge to the hand. A table of one sign is one ridge spanning it; an all-zero table has none.
std::vector<GratingRidge> grating_ridges(const std::vector<float>& t);

}  // namespace sandpaper::schema
