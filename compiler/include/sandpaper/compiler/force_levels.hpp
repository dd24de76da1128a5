#pragma once
// How many distinct forces a patch's tables hold: thesis 3.6.1's measure of force quantization
// ("the textures are displayed with only 5 to 8 different levels of force").
#include <cstddef>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

struct ForceLevels {
  std::size_t tables = 0;       // grating and height-field force tables counted (a height field has two: x, y)
  std::size_t samples = 0;      // samples in them
  std::size_t magnitudes = 0;   // distinct |F| of the samples, zero excluded: the levels a hand can feel
  std::size_t signed_values = 0;  // distinct signed values, zero included (a level in both directions counts twice)
};

// Pools every grating table and both axis tables of every height field; exact float duplicates
// are one level. Terms without tables (springs, dampers, ...) add nothing.
ForceLevels count_force_levels(const schema::PatchProgram& p);

}  // namespace sandpaper::compiler
