#pragma once
// Height images -> Sandpaper's array files (Appendix B; schema/array_file.hpp): the 8-bit height
// array (.depth) and the shaded picture Sandpaper's Normal display drew (.shade).
#include <optional>
#include <vector>

#include "sandpaper/compiler/height_field_image.hpp"
#include "sandpaper/schema/array_file.hpp"

namespace sandpaper::compiler {

// 8-bit heights: the image's lowest sample -> 0, its highest -> 255, each sample to the nearest
// step, halves up: q = floor(255 (v - lo) / (hi - lo) + 0.5). Throws std::invalid_argument if a
// side exceeds 65535 (the format's 2-byte header).
schema::ArrayFile quantize_depth(const HeightFieldImage& img);

// Lambertian shading of the height field lit from the upper left, as the thesis' Normal display
// (Appendix B: "a light source that projects to the upper left of the screen"). Reading: light at
// azimuth 135 deg (up and left) and elevation 45 deg, no ambient term; value = round(255 (1 - L)),
// 0 = white. Sample spacing dx_m, dy_m (m); heights span depth_m (m) if given, else the relief is
// scaled so that the steepest slope is 1 (45 deg). Slopes by central differences, one-sided at edges.
// Throws std::invalid_argument as quantize_depth.
schema::ArrayFile shade_relief(const HeightFieldImage& img, double dx_m, double dy_m, std::optional<double> depth_m);

// The same shading from the height field's slopes (used where only the gradient is kept, e.g. a
// compiled program's F = -k grad h): slope_x, slope_y = dh/dx and dh/dy (+x right, +y up the
// picture), nx * ny row-major, row 0 at the top, in any one unit. `height_per_unit` converts them to
// m/m; without it the steepest slope is drawn at 45 deg. Throws std::invalid_argument as
// quantize_depth, or if the vectors are not nx * ny long.
schema::ArrayFile shade_slopes(int nx, int ny, const std::vector<double>& slope_x, const std::vector<double>& slope_y,
                               std::optional<double> height_per_unit);

}  // namespace sandpaper::compiler
