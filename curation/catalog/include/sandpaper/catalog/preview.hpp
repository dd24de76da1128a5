#pragma once
// Preview pictures of one compiled material (`sandpaper preview`, the studio's preview pane, the
// catalog's thumbnails): the shaded height field (render.hpp's renderer), a top view of the lateral
// force field, and the force along a scan line (plot.hpp), each picture with a scale bar in mm.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/catalog/plot.hpp"
#include "sandpaper/catalog/render.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::catalog {

// An 8-bit image, row 0 at the top, `channels` interleaved (1 grey, 3 RGB).
struct Image {
  int nx = 0, ny = 0, channels = 1;
  std::vector<std::uint8_t> pixels;
  double pixel_m = 0;               // one pixel's side, m
  double window_m[2] = {0, 0};      // width, height shown, m, centred on the patch centre
};

// The shaded picture as a grey image (255 = white).
Image grey_image(const Picture& picture);
// The program with only the terms whose force is a function of the hand's position alone: what a
// slow hand feels at each place. Terms of velocity, state or time (dampers, nap, friction, masses,
// followers, attractors, minus) are left out, each with its reason appended to `left_out`.
schema::PatchProgram position_only(const schema::PatchProgram& program, std::vector<std::string>& left_out);
// The lateral force at rest of position_only(program) over the same window and pixels as `like`,
// each |F| limited to the device's maximum force (program.command.max_force_N) as the servo loop
// limits it: hue gives the force's direction (red along +x, then anticlockwise), brightness its
// magnitude from black (0 N) to full (`max_force_N`, the largest |F| drawn, returned).
Image render_force_field(const schema::PatchProgram& program, const Picture& like, double& max_force_N);
// Draws a scale bar of a round length (1, 2 or 5 x 10^k mm, about a quarter of the width) with its
// label in the lower left corner; returns its length, mm. Images narrower than 24 px get none (returns 0).
double draw_scale_bar(Image& image);
// Writes `image` as PNG via OpenImageIO, through a temporary file renamed into place.
// Throws std::runtime_error when it cannot be written.
void write_image_png(const std::filesystem::path& file, const Image& image);

// The force field of render_force_field as `n` x `n` arrows over `like`'s window, for a page to draw:
// each cell's strongest force (N) and where in the cell it is (mm, patch coordinates), so that a wall
// narrower than the cell is found, not stepped over. {"window_mm": [w, h], "n": n, "cell_mm": [w, h],
// "max_N": the largest |F| (the arrows' scale), "x_mm", "y_mm", "fx_N", "fy_N": [...] (row 0 at the top)}.
nlohmann::json force_field_json(const schema::PatchProgram& program, const Picture& like, int n);

// force_plot_svg with the catalog's styles inside it, for an .svg file or page of its own.
std::string standalone_plot_svg(const ForceScan& scan, const std::string& title);

// What write_preview wrote.
struct PreviewFiles {
  std::vector<std::filesystem::path> written;  // in `dir`
  nlohmann::json summary;                      // the contents of preview.json
};
// Writes height.png (shaded height field), field.png (force field top view), both `max_side` pixels on
// their longer side at most, with scale bars; scan.svg (lateral force along a scan line, axes in mm and
// N); and preview.json (pixel size, scale bars, window, scan direction, what was left out). Creates
// `dir`. A material with no position-dependent force writes scan.svg and preview.json only.
// `field_arrows` > 0 also writes field.json, force_field_json on that many points a side (the studio's arrows).
PreviewFiles write_preview(const schema::PatchProgram& program, const std::filesystem::path& dir, int max_side = 512,
                           int field_arrows = 0);

}  // namespace sandpaper::catalog
