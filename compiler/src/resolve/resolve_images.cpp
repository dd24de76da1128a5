// Height-map pictures: where a material file may read them from, and their shape.
#include "resolver_impl.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sandpaper/schema/confined_path.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/compiler/height_field_image.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/force_laws.hpp"
#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/compiler/thesis_stimuli.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler::resolve_detail {

void Resolver::heightmap(const HeightmapStmt& h, ResolvedMaterial& m) {
  bool ok = positive(h.width, "image width");
  if (h.height) ok = positive(*h.height, "image height") && ok;
  if (h.smoothing) ok = non_negative(*h.smoothing, "smoothing", "") && ok;
  if (h.amplitude) ok = non_negative(*h.amplitude, "force amplitude", "") && ok;
  if (h.sampling) ok = positive(*h.sampling, "sampling") && ok;
  if (h.depth) ok = positive(*h.depth, "relief depth") && ok;
  if (h.press) ok = positive(*h.press, "downward force (press)") && ok;
  if (h.amplitude && (h.depth || h.press)) {
    const Quantity& other = h.depth ? *h.depth : *h.press;
    auto& d = diags_.error("E0302", h.amplitude->location,
                           "`amplitude " + h.amplitude->text() + "` and `" + std::string(h.depth ? "depth " : "press ") +
                               other.text() + "` both set the maximum lateral force of this height map",
                           "keep amplitude (a target force) or depth and press (the stylus reading), not both");
    d.notes.push_back({other.location, "the stylus reading sets the force here"});
    ok = false;
  } else if (h.depth.has_value() != h.press.has_value()) {
    const Quantity& given = h.depth ? *h.depth : *h.press;
    diags_.error("E0407", given.location,
                 h.depth ? "`depth " + given.text() + "` without `press`: the relief alone gives no force"
                         : "`press " + given.text() + "` without `depth`: the force needs the relief's height",
                 "give both, e.g. depth 0.5 mm press 1 N (lateral force = press x slope, thesis 3.4), "
                 "or a target force with roughness or amplitude");
    ok = false;
  }
  if (!ok) return;
  ResolvedHeightmap r;
  std::filesystem::path p(h.path);
  // A library entry reaches only inside its library: the library is shared, and an entry that
  // named "/srv/x.exr" or "../../x.exr" would read whatever the machine it is compiled on has there.
  const auto in_library = syn_.file ? ctx_.library.source_file(syn_.file->name) : std::nullopt;
  if (in_library) {
    const auto inside = (std::filesystem::path(in_library->second).parent_path() / p).lexically_normal();
    bool leaves = p.is_absolute() || inside.empty() || *inside.begin() == "..";
    // A symbolic link inside the library that leads out leaves it as surely as "..".
    if (!leaves) try {
        schema::confined_path(in_library->first, inside.generic_string(), "the library");
      } catch (const schema::OutsideFolder&) {
        leaves = true;
      }
    if (leaves) {
      diags_.error("E0314", h.path_location,
                   "library entry's image '" + h.path + "' is outside the library (symbolic links followed)",
                   "put the image in the library (library/images/) and name it relative to the entry's folder");
      return;
    }
  }
  if (p.is_relative() && syn_.file) {
    // Relative to the material file's folder; for -e text, to the working directory.
    std::filesystem::path dir;
    if (in_library) dir = (in_library->first / in_library->second).parent_path();
    else if (syn_.file->name != "<-e>") dir = std::filesystem::path(syn_.file->name).parent_path();
    p = dir / p;
  }
  r.path = p.string();
  r.stated_path = h.path;
  r.width = stated_param(h.width, Layer::Physical);
  r.height = h.height ? stated_param(*h.height, Layer::Physical) : r.width;
  image_shape(h, r);
  if (h.smoothing) r.smoothing = stated_param(*h.smoothing, Layer::Physical);
  if (h.sampling) r.sampling = stated_param(*h.sampling, Layer::Physical);
  if (h.depth) r.depth = stated_param(*h.depth, Layer::Physical);
  if (h.press) r.press = stated_param(*h.press, Layer::Physical);
  r.channel = h.channel;
  r.repeat = h.repeat;
  r.invert = h.invert;
  r.source = h.path_location.str();
  r.location = h.path_location;
  m.texture = r;
  if (h.amplitude) m.max_lateral_force = stated_param(*h.amplitude, Layer::Physical);
  if (r.stylus()) {
    // The file's stylus reading beats an inherited roughness or amplitude.
    m.max_lateral_force.reset();
    m.roughness.reset();
  }
}

void Resolver::image_shape(const HeightmapStmt& h, ResolvedHeightmap& r) {
  const auto px = height_field_image_size(r.path);
  if (!px || px->first < 1 || px->second < 1) return;
  const auto [nx, ny] = *px;
  const std::string shape = std::to_string(nx) + " x " + std::to_string(ny) + " px";
  if (!h.height) {
    r.height.si = r.width.si * ny / nx;
    r.height.stated = fmt_num(r.height.si * 1e3) + " mm (" + h.width.text() + " across the picture's " + shape + ")";
    return;
  }
  const double dx = r.width.si / nx, dy = r.height.si / ny;
  if (std::abs(dx / dy - 1) <= 0.01) return;
  diags_.warning("W0307", h.height->location,
                 "the picture is stretched: " + shape + " over " + h.width.text() + " x " + h.height->text() + " is " +
                     fmt_num(dx * 1e3) + " mm per px across and " + fmt_num(dy * 1e3) + " mm per px down",
                 "write `size " + h.width.text() + "` alone to keep the picture's shape (" + h.width.text() + " x " +
                     fmt_num(r.width.si * ny / nx * 1e3) + " mm), or crop the picture to the patch's shape");
}

}  // namespace sandpaper::compiler::resolve_detail
