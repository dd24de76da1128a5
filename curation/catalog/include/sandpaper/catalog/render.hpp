#pragma once
// The catalog's picture of an entry: its compiled height field shaded as Sandpaper's .shade pictures
// were (Minsky 1995, Appendix B: Lambertian, lit from the upper left; compiler/array_export.hpp).
// The program keeps the field's gradient, not its heights (F = -k grad h, thesis 3.4), and shading
// needs only slopes, so the picture is drawn from the force field the runtime's evaluator plays.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sandpaper/schema/array_file.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::catalog {

// What a term adds to the picture. Height: a texture's relief (grating, height field, periodic,
// ridge). Potential: a position-only conservative field drawn as its potential energy U, F = -grad U
// (spring: 0.5 k p^2, a bowl; constant force: a tilted plane). None: forces of velocity or state
// (dampers, nap, point masses, followers, attractors, minus) or circulating fields, which no
// surface represents.
enum class PictureRole { Height, Potential, None };
PictureRole picture_role(const schema::Term& term);
// One line on why a term is left out of the picture ("the damper: F = -b v depends on velocity").
std::string why_not_pictured(const schema::Term& term);
// The term's kind in words: "grating", "height field", "spring", ...
std::string term_kind(const schema::Term& term);

struct Picture {
  int nx = 0, ny = 0;                  // pixels; 0 when there is nothing to draw
  schema::ArrayFile shade;             // the .shade picture (0 = white), nx x ny, row 0 at the top
  double pixel_m = 0;                  // one pixel's side, m
  double window_m[2] = {0, 0};         // width, height shown, m
  double centre_m[2] = {0, 0};         // the window's centre in patch coordinates, m (0, 0: the patch centre)
  bool finer_than_pixel = false;       // a texture's finest scale is under one pixel: the shading aliases
  double light_azimuth_deg = 135;      // where the light comes from, deg counter-clockwise from +x (light_azimuth_deg())
  std::string caption;                 // what the picture is, in words (plain text)
  std::vector<std::string> left_out;   // terms not drawn, each with its reason
  bool empty() const { return nx == 0; }
};

// The light's azimuth for a picture of `program`, whole degrees counter-clockwise from +x (135: the
// thesis' upper left): the one nearest 135 within 45 deg of every ridge normal (gratings, ridges,
// periodic terms), so that each ridge's two walls shade apart and no ridge is drawn at twice its
// frequency; if none is, the one lighting the worst ridge most across; ties toward 90 deg.
double light_azimuth_deg(const schema::PatchProgram& program);

// Shades the field of the program's Height and Potential terms over a window centred on the patch:
// the whole patch, or a smaller window when the texture's finest scale (a grating period over 64, a
// height field's sample spacing) would be below one pixel of `max_side` across the patch. Slopes are
// -F of those terms, from runtime::PatchEvaluator at rest (no velocity, no state advanced).
// An empty picture (with left_out filled) when no term has a surface.
Picture render_picture(const schema::PatchProgram& program, int max_side = 512);

// The same shading over a square window of `window_side_m` (m) around the patch centre at `side` pixels,
// whatever the material's own scale: pictures of different materials drawn this way compare at a glance
// (the catalog's thumbnails). Throws std::invalid_argument for a non-positive window or side.
Picture render_picture_window(const schema::PatchProgram& program, double window_side_m, int side);

// The finest detail of the program's textures, m: a grating's period / 64 (its walls), a height
// field's sample spacing; infinity without a texture. Under one pixel, a picture aliases.
double finest_detail_m(const schema::PatchProgram& program);

// The layout of a view: `window_m` (width, height, m) centred on `centre_m` (patch coordinates, m),
// `max_side` pixels on the longer side, square pixels, the window rounded to whole pixels; nothing is
// drawn (for render_force_field's `like`). Throws std::invalid_argument for a non-finite or
// non-positive window, a non-finite centre, or max_side < 1.
Picture picture_frame(const double centre_m[2], const double window_m[2], int max_side);

// The same shading over any window: `window_m` (width, height, m) centred on `centre_m` (patch
// coordinates, m), laid out as picture_frame lays it out. For zoom and pan over the whole patch
// (the studio's view); finer_than_pixel says when the texture is finer than a pixel there. Empty
// (left_out filled) when no term has a surface; throws as picture_frame does.
Picture render_picture_view(const schema::PatchProgram& program, const double centre_m[2], const double window_m[2],
                            int max_side);

// The picture as an 8-bit grey PNG (255 = white), via OpenImageIO; `side` > 0 resizes it so that its
// longer side is `side` pixels (a thumbnail). Throws std::runtime_error when the file cannot be written.
void write_png(const std::filesystem::path& file, const Picture& picture, int side = 0);

}  // namespace sandpaper::catalog
