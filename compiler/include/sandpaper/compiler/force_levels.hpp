#pragma once
// How many distinct forces a patch's tables hold: thesis 3.6.1's measure of force quantization
// ("the textures are displayed with only 5 to 8 different levels of force").
#include <cstddef>
#include <string>
#include <vector>

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

// What an emulated device's quantisation leaves of one force table (explain --device sandpaper-1995):
// the hand's positions fall on encoder counts of `position_step_m`, tables are read by
// sample-and-hold (Appendix B 2.1) and forces are sent in whole command units of `force_step_N`
// (at most `command_max`). SI units.
struct QuantizedTable {
  std::string kind;                  // "grating" or "height field"
  double spacing_m = 0;              // grating: its period; height field: its sample spacing (x)
  double positions_per_spacing = 0;  // encoder counts per period / per table sample
  std::size_t table_levels = 0;      // distinct |F| in the table, zero excluded (as count_force_levels)
  std::size_t device_levels = 0;     // distinct nonzero |command| the device sends crossing it
  double largest_N = 0;              // the largest force sent, after rounding and clamping
};
// One entry per grating and height-field term. A grating is crossed at every encoder count along its
// normal over 64 periods (so incommensurate steps reach every phase they can); a height field's
// samples are all reachable when the step is under the spacing and are taken as they are.
std::vector<QuantizedTable> quantize_tables(const schema::PatchProgram& p, double position_step_m, double force_step_N,
                                            long command_max);

}  // namespace sandpaper::compiler
