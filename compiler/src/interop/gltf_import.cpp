// glTF 2.0 + MPEG_haptic_material -> patch programs (docs/GLTF.md, "Import"). Outside input: the
// first problem found ends the read with one diagnostic naming the JSON place, and no size is
// trusted before it is checked against a limit.
#include "sandpaper/compiler/gltf_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_support.hpp"
#include "sandpaper/compiler/height_field_image.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {
namespace {

using nlohmann::json;

// One refusal: the code, what, how to fix it (gltf_document.hpp). Thrown inside the reader, caught
// once at its top.
using Refusal = GltfRefusal;
[[noreturn]] void refuse(schema::Code code, std::string message, std::string suggestion = {}) {
  refuse_gltf(code, std::move(message), std::move(suggestion));
}

std::string num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// JSON access that names the place of anything missing or mistyped (gltf_document.hpp).
const json& member(const json& j, const char* key, const std::string& where, schema::Code code = "E0712") {
  return gltf_member(j, key, where, code);
}
const json* optional_member(const json& j, const char* key) { return gltf_optional_member(j, key); }
std::size_t index_into(const json& j, const json& array, const std::string& where, schema::Code code) {
  return gltf_index(j, array, where, code);
}

// Sandpaper's extras: every key typed and in range, its unit in its name.
struct Extras {
  const json& j;
  std::string where;
  const json& at(const char* key) const {
    auto it = j.find(key);
    if (it == j.end())
      refuse("E0714", where + " has no \"" + key + "\"", "export the material again with `sandpaper export --format gltf`");
    return *it;
  }
  double number(const char* key, double lo, double hi) const {
    const json& v = at(key);
    if (!v.is_number()) refuse("E0714", where + "." + key + " is " + v.type_name() + ", not a number");
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
      refuse("E0714", where + "." + key + " is " + num(x) + ", outside " + num(lo) + " to " + num(hi));
    return x;
  }
  void pair(const char* key, double lo, double hi, double out[2]) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
      refuse("E0714", where + "." + key + " is not a pair of numbers [x, y]");
    for (int a = 0; a < 2; ++a) {
      out[a] = v[static_cast<std::size_t>(a)].get<double>();
      if (!std::isfinite(out[a]) || out[a] < lo || out[a] > hi)
        refuse("E0714", where + "." + key + "[" + std::to_string(a) + "] is " + num(out[a]) + ", outside " + num(lo) +
                            " to " + num(hi));
    }
  }
  std::string text(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) refuse("E0714", where + "." + key + " is " + v.type_name() + ", not a string");
    return v.get<std::string>();
  }
  bool flag(const char* key) const {
    const json& v = at(key);
    if (!v.is_boolean()) refuse("E0714", where + "." + key + " is " + v.type_name() + ", not true or false");
    return v.get<bool>();
  }
};

constexpr const char* kReencodedFix =
    "export it again from Sandpaper; in glTF-Transform register the MPEG_haptic_material extension "
    "(interop/gltf-transform, docs/GLTF.md), which keeps haptic textures as written";

// What a pipeline made of a haptic texture, from its first bytes: "an 8-bit RGB PNG", "a WebP image";
// nullopt for a 16-bit greyscale PNG and for bytes no pipeline writes (those are E0716's).
std::optional<std::string> reencoded(const std::vector<unsigned char>& b) {
  auto starts = [&](std::size_t at, std::string_view magic) {
    return b.size() >= at + magic.size() && std::equal(magic.begin(), magic.end(), b.begin() + static_cast<std::ptrdiff_t>(at),
                                                        [](char m, unsigned char c) { return static_cast<unsigned char>(m) == c; });
  };
  if (starts(0, "\x89PNG\r\n\x1a\n") && starts(12, "IHDR") && b.size() >= 26) {
    const int depth = b[24], colour = b[25];
    if (depth == 16 && colour == 0) return std::nullopt;
    const char* kind = colour == 0 ? "greyscale" : colour == 2 ? "RGB" : colour == 3 ? "palette" : colour == 4 ? "greyscale-alpha"
                                                 : colour == 6 ? "RGBA" : "unknown-colour";
    return std::string(depth == 8 ? "an " : "a ") + std::to_string(depth) + "-bit " + kind + " PNG";
  }
  if (starts(0, "RIFF") && starts(8, "WEBP")) return "a WebP image";
  if (starts(0, "\xff\xd8\xff")) return "a JPEG image";
  if (starts(4, "ftypavif") || starts(4, "ftypavis")) return "an AVIF image";
  if (starts(0, "\xabKTX 20\xbb")) return "a KTX2 image";
  return std::nullopt;
}

class Reader {
 public:
  Reader(const Compiler& c, const GltfDocument& doc, Diagnostics& diags)
      : c_(c), doc_(doc), root_(doc.root()), shown_(doc.shown()), diags_(diags) {}

  // The program of haptic material `index` (built once, shared by every mesh naming it).
  std::shared_ptr<const schema::PatchProgram> program(std::size_t index) {
    auto it = built_.find(index);
    if (it != built_.end()) return it->second;
    auto p = std::make_shared<const schema::PatchProgram>(build(index));
    built_.emplace(index, p);
    return p;
  }

  const json& haptic_materials() const { return materials_; }
  void set_materials(const json& m) { materials_ = m; }

 private:
  schema::PatchProgram build(std::size_t index) {
    const std::string where = "extensions.MPEG_haptic_material.materials[" + std::to_string(index) + "]";
    const json& m = materials_[index];
    if (!m.is_object()) refuse("E0713", where + " is not a JSON object");
    const json* extras = optional_member(m, "extras");
    const json* ours = extras ? optional_member(*extras, gltf::kExtrasKey) : nullptr;
    if (!ours || !ours->is_object())
      refuse("E0714", where + " has no extras.sandpaper object: the asset was not written by Sandpaper",
             "Sandpaper reads back the assets `sandpaper export --format gltf` writes (docs/GLTF.md)");
    const Extras x{*ours, where + ".extras.sandpaper"};
    const double version = x.number("version", 0, 1e9);
    if (version != gltf::kExtrasVersion && version != gltf::kExtrasVersionOldNames)
      refuse("E0714", x.where + ".version is not " + std::to_string(gltf::kExtrasVersionOldNames) + " or " +
                          std::to_string(gltf::kExtrasVersion),
             "export it again with this Sandpaper");
    const char* force_key = version == gltf::kExtrasVersionOldNames ? "max_lateral_force_N" : "compiled_max_lateral_force_N";
    const auto& device = c_.device();
    schema::PatchProgram p;
    p.name = x.text("name");
    p.describes = x.text("describes");
    p.device = device.name;
    x.pair("patch_size_m", 1e-6, 10, p.size_m);
    const std::string kind = x.text("texture");
    const std::string source = x.text("source");
    p.provenance.push_back({"patch.width", p.size_m[0], "m", num(p.size_m[0] * 1e3) + " mm", "physical", shown_ + " (glTF extras)"});
    p.provenance.push_back({"patch.height", p.size_m[1], "m", num(p.size_m[1] * 1e3) + " mm", "physical", shown_ + " (glTF extras)"});
    if (const json* nc = optional_member(*ours, "not_carried"); nc && nc->is_array() && !nc->empty()) {
      std::string list;
      for (const auto& n : *nc)
        if (n.is_string() && list.size() < 1000) list += (list.empty() ? "" : ", ") + n.get<std::string>();
      diags_.warning("W0703", at(), "'" + p.name + "' had parts glTF does not carry, left out of the asset: " + list,
                     "compile the original material (" + source.substr(0, 200) + ") for the whole of it");
    }
    if (kind == "none") return finish(p, 0);
    if (kind != "grating" && kind != "height_field")
      refuse("E0714", x.where + ".texture is \"" + kind.substr(0, 40) + "\", not \"grating\", \"height_field\" or \"none\"");
    const double force = x.number(force_key, 0, 1e4);
    const double k = x.number("lateral_gain_N", 1e-12, 1e4);
    const double range = x.number("height_range_m", 1e-15, 1);
    const gltf::Png16 png = texture(m, where, kind);
    std::vector<double> h(png.texels.size());
    if (kind == "grating") {
      if (png.ny != 1 || png.nx < 2)
        refuse("E0717", "the grating texture of " + where + " is " + std::to_string(png.nx) + " x " + std::to_string(png.ny) +
                            " px; a grating is one row of at least 2 texels (one period)");
      schema::GratingTerm g;
      g.period_m = x.number("period_m", 1e-6, 1);
      g.orientation_rad = x.number("orientation_rad", -1e3, 1e3);
      for (std::size_t i = 0; i < h.size(); ++i) h[i] = png.texels[i] / gltf::kTexelMax * range;
      g.force_N = gltf::grating_forces(h, g.period_m, k);
      p.terms.emplace_back(std::move(g));
      p.provenance.push_back({"texture.period", std::get<schema::GratingTerm>(p.terms.back()).period_m, "m",
                              "period_m in the glTF extras", "physical", shown_ + " (glTF extras)"});
    } else {
      schema::HeightFieldTerm f;
      f.nx = static_cast<std::uint32_t>(png.nx);
      f.ny = static_cast<std::uint32_t>(png.ny);
      x.pair("grid_spacing_m", 1e-9, 1, f.spacing_m);
      x.pair("grid_origin_m", -10, 10, f.origin_m);
      f.repeat = x.flag("repeat");
      // The patch reader's rule (schema/src/patch_io.cpp): one texel across is a field constant along
      // that axis, which only a repeating field can mean (a 256 x 1 texture that
      // does not repeat made a program the reader refuses).
      if (!f.repeat && (png.nx < 2 || png.ny < 2))
        refuse("E0717", "the height texture of " + where + " is " + std::to_string(png.nx) + " x " + std::to_string(png.ny) +
                            " px and does not repeat; a height field that ends needs at least 2 texels each way",
               "export the material again, or give it `repeat` if it is a tile");
      for (int r = 0; r < png.ny; ++r)  // PNG row 0 is the top (+y) edge; the grid's row 0 the bottom
        for (int c = 0; c < png.nx; ++c)
          h[static_cast<std::size_t>(png.ny - 1 - r) * png.nx + c] = png.texels[static_cast<std::size_t>(r) * png.nx + c] / gltf::kTexelMax * range;
      gltf::height_field_forces(h, png.nx, png.ny, f.spacing_m[0], f.spacing_m[1], f.repeat, k, f.force_x_N, f.force_y_N);
      p.terms.emplace_back(std::move(f));
    }
    // What the heights ask for, against the device: the reader's own check, not the extras' word.
    double peak = 0;
    for (const auto& term : p.terms) {
      if (const auto* g = std::get_if<schema::GratingTerm>(&term))
        for (float f : g->force_N) peak = std::max(peak, static_cast<double>(std::abs(f)));
      if (const auto* f = std::get_if<schema::HeightFieldTerm>(&term))
        for (std::size_t i = 0; i < f->force_x_N.size(); ++i)
          peak = std::max(peak, std::hypot(static_cast<double>(f->force_x_N[i]), static_cast<double>(f->force_y_N[i])));
    }
    if (!std::isfinite(peak) || peak > device.max_force_N || force > device.max_force_N)
      refuse("E0718",
             "the texture of " + where + " asks for " + num(std::max(peak, force)) + " N of lateral force; device '" +
                 device.name + "' reaches " + num(device.max_force_N) + " N at most (" + device.file + ")",
             "compile for a stronger device (--device), or export the material again with less force");
    p.provenance.push_back({"texture.max_lateral_force", force, "N", num(force) + " N (" + force_key + ")", "physical",
                            shown_ + " (glTF extras; " + source.substr(0, 200) + ")"});
    return finish(p, force);
  }

  // The device's command scale and the roughness map's prediction, as codegen records them.
  schema::PatchProgram finish(schema::PatchProgram& p, double force) {
    const auto& device = c_.device();
    const auto& map = c_.calibration().roughness_map();
    p.command.device_file = device.file;
    p.command.command_unit = device.command_unit;
    p.command.command_max = device.command_max;
    p.command.max_force_N = device.max_force_N;
    p.command.calibrated = device.calibrated();
    for (int a = 0; a < 2; ++a) p.command.newtons_per_command_unit[a] = device.axis_scale(a).step_N(force);
    p.max_lateral_force_N = force;
    p.roughness = force > 0 ? map.percept_of(force) : 0;
    p.roughness_map = map.id;
    p.roughness_map_file = map.file;
    if (force > 0)
      p.provenance.push_back({"texture.roughness", p.roughness, "1", "from the maximum lateral force", "derived", map.provenance()});
    return std::move(p);
  }

  // The material's haptic texture, decoded: vibrotactileTexture[0] -> textures -> images -> PNG.
  gltf::Png16 texture(const json& m, const std::string& where, const std::string& kind) {
    const json* list = optional_member(m, "vibrotactileTexture");
    if (!list || !list->is_array() || list->empty())
      refuse("E0715", where + " has no vibrotactileTexture, but its extras say it has a " + kind + " texture");
    const json& info = member((*list)[0], "texture", where + ".vibrotactileTexture[0]", "E0715");
    const json& textures = member(root_, "textures", "the asset", "E0715");
    const std::size_t ti = index_into(member(info, "index", where + ".vibrotactileTexture[0].texture", "E0715"), textures,
                                      where + ".vibrotactileTexture[0].texture.index", "E0715");
    const std::string tw = "textures[" + std::to_string(ti) + "]";
    const json& images = member(root_, "images", "the asset", "E0715");
    if (!optional_member(textures[ti], "source"))
      if (const json* e = optional_member(textures[ti], "extensions"); e && e->is_object())
        for (const auto& [name, format] : std::initializer_list<std::pair<const char*, const char*>>{
                 {"EXT_texture_webp", "WebP"}, {"EXT_texture_avif", "AVIF"}, {"KHR_texture_basisu", "KTX2"}})
          if (e->contains(name))
            refuse("E0720", "the haptic texture of " + where + " (" + tw + ") is a " + format + " image (" + name +
                                "), not the 16-bit greyscale PNG its heights were written as: a pipeline re-encoded it and the heights are lost",
                   kReencodedFix);
    const std::size_t ii = index_into(member(textures[ti], "source", tw, "E0715"), images, tw + ".source", "E0715");
    const std::string iw = "images[" + std::to_string(ii) + "]";
    const json* uri = optional_member(images[ii], "uri");
    std::optional<std::vector<unsigned char>> bytes;
    const std::string prefix = gltf::kPngDataUriPrefix;
    if (optional_member(images[ii], "bufferView") && !uri) {
      bytes = doc_.buffer_view(images[ii]["bufferView"], iw + ".bufferView");
    } else if (!uri || !uri->is_string()) {
      refuse("E0715", iw + " has neither a uri nor a bufferView", "export the material again with `sandpaper export --format gltf`");
    } else if (const std::string& u = uri->get_ref<const std::string&>(); u.compare(0, prefix.size(), prefix) == 0) {
      bytes = gltf::base64_decode(std::string_view(u).substr(prefix.size()));
      if (!bytes) refuse("E0715", iw + ".uri is not valid base64");
    } else {
      bytes = doc_.folder_file(u, iw);
    }
    if (const auto what = reencoded(*bytes))
      refuse("E0720", "the haptic texture of " + where + " (" + iw + ") is " + *what +
                          ", not the 16-bit greyscale PNG its heights were written as: a pipeline re-encoded it and the heights are lost",
             kReencodedFix);
    std::string why;
    const long long budget = kMaxGltfTexels - texels_;
    const long long limit = std::min<long long>(kind == "grating" ? 65536 : kMaxImagePixels, budget);
    auto png = gltf::decode_png16(*bytes, std::max<long long>(limit, 0), why);
    if (!png) refuse(why.find("over the limit") != std::string::npos ? schema::Code("E0717") : schema::Code("E0716"), iw + ": " + why);
    texels_ += static_cast<long long>(png->texels.size());
    return std::move(*png);
  }

  SourceLocation at() const { return SourceLocation{std::make_shared<const SourceFile>(shown_, ""), 0, 0, 1}; }

  const Compiler& c_;
  const GltfDocument& doc_;  // the asset's JSON and buffers
  const json& root_;
  std::string shown_;
  Diagnostics& diags_;
  json materials_;
  std::map<std::size_t, std::shared_ptr<const schema::PatchProgram>> built_;
  long long texels_ = 0;
};

// One patch in the scene: node `node`'s mesh `mesh`, its primitives `prims` (those of one visual
// material that marks a haptic material, or those the mesh's own haptic material covers), and that
// haptic material's index.
struct Piece {
  std::size_t node = 0, mesh = 0;
  std::vector<std::size_t> prims;
  std::size_t haptic = 0;
  std::optional<std::size_t> marked_by;  // the visual material whose extras name the haptic material
};

// A primitive's haptic material: the one its visual material marks (`extras.sandpaper.hapticMaterialIndex`,
// which Sandpaper writes on each patch's own material, so that a mesh merged from several patches
// keeps each), else the one its mesh names (MPEG_haptic_material's `hapticMaterialIndex`), else none.
std::optional<std::size_t> primitive_haptic(const json& root, const json& prim, const json* mesh_index, std::size_t materials,
                                            const std::string& pw, std::optional<std::size_t>* marked_by = nullptr) {
  const json* material = prim.is_object() ? optional_member(prim, "material") : nullptr;
  if (material) {
    const json* visuals = optional_member(root, "materials");
    if (!visuals || !visuals->is_array()) refuse("E0712", pw + ".material names a material, but the asset has no materials");
    const json& visual = (*visuals)[index_into(*material, *visuals, pw + ".material", "E0712")];
    const json* extras = visual.is_object() ? optional_member(visual, "extras") : nullptr;
    const json* ours = extras && extras->is_object() ? optional_member(*extras, gltf::kExtrasKey) : nullptr;
    const json* mark = ours && ours->is_object() ? optional_member(*ours, "hapticMaterialIndex") : nullptr;
    if (mark) {
      if (!mark->is_number_unsigned() || mark->get<std::uint64_t>() >= materials)
        refuse("E0713", "materials[" + std::to_string(material->get<std::uint64_t>()) + "].extras.sandpaper.hapticMaterialIndex (of " + pw +
                            ") is not an index into the " + std::to_string(materials) + " haptic materials");
      if (marked_by) *marked_by = static_cast<std::size_t>(material->get<std::uint64_t>());
      return static_cast<std::size_t>(mark->get<std::uint64_t>());
    }
  }
  if (!mesh_index) return std::nullopt;
  return static_cast<std::size_t>(mesh_index->get<std::uint64_t>());
}

// The scene's patches: each node's mesh's primitives grouped by the visual material that marks their
// haptic material (unmarked ones by the mesh's), in the order first met. A node whose mesh has none
// is scenery.
std::vector<Piece> haptic_pieces(const json& root, std::size_t materials) {
  const json* nodes = optional_member(root, "nodes");
  if (!nodes || !nodes->is_array()) refuse("E0713", "the asset has no nodes, so no mesh carries a haptic material");
  std::vector<std::size_t> order;
  if (const json* scenes = optional_member(root, "scenes")) {
    std::size_t s = 0;
    if (const json* scene = optional_member(root, "scene")) s = index_into(*scene, *scenes, "scene", "E0712");
    if (!scenes->is_array() || scenes->empty()) refuse("E0712", "scenes is not a non-empty array");
    const json* list = optional_member((*scenes)[s], "nodes");
    if (list) {
      if (!list->is_array()) refuse("E0712", "scenes[" + std::to_string(s) + "].nodes is not an array");
      for (std::size_t i = 0; i < list->size(); ++i)
        order.push_back(index_into((*list)[i], *nodes, "scenes[" + std::to_string(s) + "].nodes[" + std::to_string(i) + "]", "E0712"));
    }
  } else {
    for (std::size_t i = 0; i < nodes->size(); ++i) order.push_back(i);
  }
  const json* meshes = optional_member(root, "meshes");
  std::vector<Piece> out;
  for (std::size_t n : order) {
    const std::string nw = "nodes[" + std::to_string(n) + "]";
    const json& node = (*nodes)[n];
    if (!node.is_object()) refuse("E0712", nw + " is not a JSON object");
    const json* mesh = optional_member(node, "mesh");
    if (!mesh) continue;
    if (!meshes) refuse("E0712", nw + ".mesh names a mesh, but the asset has no meshes");
    const std::size_t mi = index_into(*mesh, *meshes, nw + ".mesh", "E0712");
    const std::string mw = "meshes[" + std::to_string(mi) + "]";
    const json* ext = optional_member((*meshes)[mi], "extensions");
    const json* hm = ext ? optional_member(*ext, gltf::kExtension) : nullptr;
    const json* mesh_index = nullptr;
    if (hm) {
      if (materials == 0) refuse("E0713", "the asset has no MPEG_haptic_material materials for " + mw + " to name");
      mesh_index = &member(*hm, "hapticMaterialIndex", mw + ".extensions.MPEG_haptic_material", "E0713");
      if (!mesh_index->is_number_unsigned() || mesh_index->get<std::uint64_t>() >= materials)
        refuse("E0713", mw + ".extensions.MPEG_haptic_material.hapticMaterialIndex is not an index into the " +
                            std::to_string(materials) + " haptic materials");
    }
    const json* prims = optional_member((*meshes)[mi], "primitives");
    std::vector<Piece> found;
    if (prims && prims->is_array())
      for (std::size_t p = 0; p < prims->size(); ++p) {
        std::optional<std::size_t> marked_by;
        const auto h = primitive_haptic(root, (*prims)[p], mesh_index, materials, mw + ".primitives[" + std::to_string(p) + "]", &marked_by);
        if (!h) continue;  // a primitive without haptics is scenery
        // Sandpaper marks each patch's own visual material, so primitives of one marked material are
        // one patch (a mesh merged from several keeps them apart); the unmarked ones are the mesh's.
        auto same = std::find_if(found.begin(), found.end(), [&](const Piece& x) { return x.marked_by == marked_by; });
        if (same == found.end()) found.push_back(Piece{n, mi, {p}, *h, marked_by});
        else same->prims.push_back(p);
      }
    if (found.empty()) continue;  // a mesh without haptics is scenery, not a patch
    for (const char* k : {"matrix", "children"})
      if (optional_member(node, k))
        refuse("E0712", nw + " has a \"" + k + "\": Sandpaper reads patches placed by translation and scale alone, on the ground plane",
               "export the asset again from Sandpaper, or remove the transform");
    out.insert(out.end(), found.begin(), found.end());
    if (out.size() > schema::limits::kMaxWorkspacePatches)
      refuse("E0719", "the asset has more than " + std::to_string(schema::limits::kMaxWorkspacePatches) + " haptic meshes");
  }
  return out;
}

// A node's numbers: `count` finite numbers within `bound`, or `fallback` when absent.
std::array<double, 4> numbers(const json& node, const char* key, std::size_t n, std::size_t count, double bound,
                              std::array<double, 4> fallback) {
  const json* t = optional_member(node, key);
  if (!t) return fallback;
  const std::string w = "nodes[" + std::to_string(n) + "]." + key;
  if (!t->is_array() || t->size() != count) refuse("E0712", w + " is not " + std::to_string(count) + " numbers");
  std::array<double, 4> v{};
  for (std::size_t i = 0; i < count; ++i) {
    if (!(*t)[i].is_number()) refuse("E0712", w + " is not " + std::to_string(count) + " numbers");
    v[i] = (*t)[i].get<double>();
    if (!std::isfinite(v[i]) || std::abs(v[i]) > bound) refuse("E0712", w + "[" + std::to_string(i) + "] is not within " + num(bound));
  }
  return v;
}

// An accessor bound as a number: KHR_mesh_quantization's normalized integers are read as glTF 2.0
// section 3.11 maps them to [-1, 1] or [0, 1]; other values are as written.
double dequantized(double v, const json& accessor) {
  const json* normalized = optional_member(accessor, "normalized");
  if (!normalized || !normalized->is_boolean() || !normalized->get<bool>()) return v;
  const json* type = optional_member(accessor, "componentType");
  const int t = type && type->is_number_integer() ? type->get<int>() : 0;
  switch (t) {
    case 5120: return std::max(v / 127.0, -1.0);    // BYTE
    case 5121: return v / 255.0;                    // UNSIGNED_BYTE
    case 5122: return std::max(v / 32767.0, -1.0);  // SHORT
    case 5123: return v / 65535.0;                  // UNSIGNED_SHORT
    default: refuse("E0712", "a POSITION accessor is normalized but of component type " + std::to_string(t));
  }
}

// The box of the piece's POSITION bounds over its primitives (accessor min and max, which glTF
// requires of POSITION), in the mesh's own frame; nullopt if a primitive has none.
std::optional<std::array<double, 6>> mesh_bounds(const json& root, const Piece& piece) {
  const std::size_t mi = piece.mesh;
  const json& mesh = root["meshes"][mi];
  const json* prims = optional_member(mesh, "primitives");
  const json* accessors = optional_member(root, "accessors");
  if (!prims || !prims->is_array() || prims->empty() || !accessors) return std::nullopt;
  std::array<double, 6> box{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (std::size_t p : piece.prims) {
    const std::string pw = "meshes[" + std::to_string(mi) + "].primitives[" + std::to_string(p) + "]";
    const json* attributes = optional_member((*prims)[p], "attributes");
    const json* position = attributes ? optional_member(*attributes, "POSITION") : nullptr;
    if (!position) return std::nullopt;
    const json& a = (*accessors)[index_into(*position, *accessors, pw + ".attributes.POSITION", "E0712")];
    const json* lo = optional_member(a, "min");
    const json* hi = optional_member(a, "max");
    if (!lo || !hi || !lo->is_array() || !hi->is_array() || lo->size() != 3 || hi->size() != 3) return std::nullopt;
    for (std::size_t i = 0; i < 3; ++i) {
      if (!(*lo)[i].is_number() || !(*hi)[i].is_number()) refuse("E0712", pw + "'s POSITION min or max is not three numbers");
      const double l = dequantized((*lo)[i].get<double>(), a), h = dequantized((*hi)[i].get<double>(), a);
      if (!std::isfinite(l) || !std::isfinite(h) || l > h) refuse("E0712", pw + "'s POSITION min and max are not a box");
      box[i] = std::min(box[i], l);
      box[3 + i] = std::max(box[3 + i], h);
    }
  }
  return box;
}

// The patch's place on the workspace, the centre of its mesh's box in the scene: glTF (x, 0, z) is
// patch (x, -z). A node may scale its mesh (glTF pipelines' quantization does, to undo the integer
// positions' scale) but not rotate it, and the mesh must span the patch's size on the ground plane.
void centre_of(const json& root, const Piece& piece, const double size_m[2], double centre[2]) {
  const std::size_t n = piece.node;
  const json& node = root["nodes"][n];
  const std::string nw = "nodes[" + std::to_string(n) + "]";
  const auto t = numbers(node, "translation", n, 3, 10, {0, 0, 0, 0});
  const auto s = numbers(node, "scale", n, 3, 1e6, {1, 1, 1, 0});
  const auto q = numbers(node, "rotation", n, 4, 1, {0, 0, 0, 1});
  if (std::abs(q[0]) > 1e-6 || std::abs(q[1]) > 1e-6 || std::abs(q[2]) > 1e-6)
    refuse("E0712", nw + " is rotated: Sandpaper reads patches lying on the ground plane as exported",
           "export the asset again from Sandpaper, or remove the rotation");
  for (int i = 0; i < 3; ++i)
    if (!(s[i] > 0)) refuse("E0712", nw + ".scale[" + std::to_string(i) + "] is " + num(s[i]) + ": a patch is scaled by positive numbers only");
  double c[3] = {t[0], t[1], t[2]};
  if (const auto box = mesh_bounds(root, piece)) {
    double span[3];
    for (int i = 0; i < 3; ++i) {
      c[i] = t[i] + s[i] * ((*box)[i] + (*box)[3 + i]) / 2;
      span[i] = s[i] * ((*box)[3 + i] - (*box)[i]);
    }
    // 1e-3 of the size: float positions and 14-bit quantized ones both hold it with room to spare.
    if (std::abs(span[0] - size_m[0]) > 1e-3 * size_m[0] || std::abs(span[2] - size_m[1]) > 1e-3 * size_m[1] || span[1] > 1e-6)
      refuse("E0712", nw + "'s mesh spans " + num(span[0] * 1e3) + " mm x " + num(span[2] * 1e3) + " mm (and " + num(span[1] * 1e3) +
                          " mm up) in the scene, but its patch is " + num(size_m[0] * 1e3) + " mm x " + num(size_m[1] * 1e3) +
                          " mm flat: the node or its mesh was scaled or reshaped",
             "export the asset again from Sandpaper");
  } else if (s[0] != 1 || s[1] != 1 || s[2] != 1) {
    refuse("E0712", nw + " is scaled, and its mesh has no POSITION min and max to say where its patch lies");
  }
  if (std::abs(c[1]) > 1e-6) refuse("E0712", nw + " lifts the patch off the ground plane (y = " + num(c[1]) + " m)");
  if (std::abs(c[0]) > 10 || std::abs(c[2]) > 10) refuse("E0712", nw + " places its patch more than 10 m from the origin");
  // Read to the micrometre: a place carried in float positions (a pipeline that moved the patches
  // into their vertices, a merged mesh) is off by up to 1e-8 m at 10 cm, and no device resolves a
  // micrometre, so the place a translation gives and the one the same vertices give read the same.
  const auto micrometre = [](double v) { return std::round(v * 1e6) / 1e6 + 0.0; };  // + 0.0: no -0
  centre[0] = micrometre(c[0]);
  centre[1] = micrometre(-c[2]);
}

void read(const Compiler& c, const std::string& file_bytes, const std::string& shown,
          const std::optional<std::filesystem::path>& folder, GltfImportResult& r) {
  const GltfDocument doc = GltfDocument::parse(file_bytes, shown, folder);
  const json& root = doc.root();
  const json* ext = optional_member(root, "extensions");
  const json* top = ext ? optional_member(*ext, gltf::kExtension) : nullptr;
  if (!top) refuse("E0713", "the asset has no MPEG_haptic_material extension, so nothing in it has haptics",
                   "export a material with `sandpaper export --format gltf`");
  const json& materials = member(*top, "materials", "extensions.MPEG_haptic_material", "E0713");
  if (!materials.is_array() || materials.empty())
    refuse("E0713", "extensions.MPEG_haptic_material.materials is not a non-empty array");
  const auto placed = haptic_pieces(root, materials.size());
  if (placed.empty()) refuse("E0713", "no mesh in the scene names a haptic material (meshes[].extensions.MPEG_haptic_material)");
  // Sandpaper writes one haptic material per distinct material and a mesh for every patch: a
  // material no mesh names, or fewer meshes than the patches written, is a patch a pipeline lost.
  std::vector<bool> named(materials.size(), false);
  for (const auto& piece : placed) named[piece.haptic] = true;
  if (const json* meshes = optional_member(root, "meshes"); meshes && meshes->is_array())
    for (std::size_t mi = 0; mi < meshes->size(); ++mi) {  // a mesh of another scene still holds its patch
      const json& mesh = (*meshes)[mi];
      if (!mesh.is_object()) continue;
      const json* e = optional_member(mesh, "extensions");
      const json* hm = e ? optional_member(*e, gltf::kExtension) : nullptr;
      const json* index = hm ? optional_member(*hm, "hapticMaterialIndex") : nullptr;
      if (index && !(index->is_number_unsigned() && index->get<std::uint64_t>() < materials.size())) index = nullptr;
      const json* prims = optional_member(mesh, "primitives");
      if (!prims || !prims->is_array()) continue;
      for (std::size_t p = 0; p < prims->size(); ++p)
        if (const auto h = primitive_haptic(root, (*prims)[p], index, materials.size(),
                                            "meshes[" + std::to_string(mi) + "].primitives[" + std::to_string(p) + "]"))
          named[*h] = true;
    }
  if (const auto lost = static_cast<std::size_t>(std::count(named.begin(), named.end(), false)); lost > 0)
    refuse("E0721",
           std::to_string(lost) + " of the " + std::to_string(materials.size()) +
               " haptic materials are named by no mesh (first: extensions.MPEG_haptic_material.materials[" +
               std::to_string(std::find(named.begin(), named.end(), false) - named.begin()) +
               "]): their patches' meshes were merged into others or removed, as glTF-Transform's join (and optimize, which joins) does",
           "export the asset again from Sandpaper (its patches now have visual materials of their own, which join keeps apart), "
             "or join with meshes kept apart (gltf-transform optimize --join false)");
  Reader reader(c, doc, r.diagnostics);
  reader.set_materials(materials);
  const json* extras = optional_member(root, "extras");
  const json* ours = extras ? optional_member(*extras, gltf::kExtrasKey) : nullptr;
  const json* ws = ours ? optional_member(*ours, "workspace") : nullptr;
  if (!ws) {
    if (placed.size() != 1)
      refuse("E0713", std::to_string(placed.size()) + " meshes carry haptic materials, but the asset is not a workspace (no extras.sandpaper.workspace)",
             "export a workspace (.hws) to get an asset of several patches");
    r.program = *reader.program(placed.front().haptic);
    double centre[2];  // a lone patch has no place, but its mesh must still be the patch, on the ground
    centre_of(root, placed.front(), r.program->size_m, centre);
    return;
  }
  if (!ws->is_object()) refuse("E0714", "extras.sandpaper.workspace is not a JSON object");
  const Extras x{*ws, "extras.sandpaper.workspace"};
  schema::WorkspaceProgram w;
  w.name = x.text("name");
  x.pair("size_m", 1e-6, 10, w.size_m);
  if (ws->contains("patches")) {  // an asset that does not say how many it was written with is not checked
    const double written = x.number("patches", 1, static_cast<double>(schema::limits::kMaxWorkspacePatches));
    if (static_cast<double>(placed.size()) != written)
      refuse("E0721",
             "the workspace was written with " + num(written) + " patches, but " + std::to_string(placed.size()) +
                 " meshes in the scene carry haptic materials: a pipeline merged or removed the others (glTF-Transform's join, optimize)",
             "export the asset again from Sandpaper (its patches now have visual materials of their own, which join keeps apart), "
             "or join with meshes kept apart (gltf-transform optimize --join false)");
  }
  for (const auto& piece : placed) {
    auto program = reader.program(piece.haptic);
    double centre[2];
    centre_of(root, piece, program->size_m, centre);
    const json& name = materials[piece.haptic]["extras"][gltf::kExtrasKey]["source"];
    w.patches.push_back(schema::place_shared_patch(program, centre, name.get<std::string>()));
  }
  r.workspace = std::move(w);
}

}  // namespace


GltfImportResult import_gltf_text(const Compiler& compiler, const std::string& bytes, const std::string& shown_name,
                                  const std::optional<std::filesystem::path>& folder) {
  GltfImportResult r;
  const SourceLocation at{std::make_shared<const SourceFile>(shown_name, ""), 0, 0, 1};
  try {
    read(compiler, bytes, shown_name, folder, r);
  } catch (const Refusal& e) {
    r.program.reset();
    r.workspace.reset();
    r.diagnostics.error(schema::Code::of(e.code), at, e.message, e.suggestion);
  } catch (const json::exception& e) {
    // Every access above is checked first; this is a defect's safety net, still the input's error.
    r.program.reset();
    r.workspace.reset();
    r.diagnostics.error("E0712", at, std::string("'") + shown_name + "' is not a glTF asset Sandpaper reads: " + e.what());
  }
  return r;
}

GltfImportResult import_gltf_file(const Compiler& compiler, const std::filesystem::path& path) {
  std::string bytes;
  try {
    bytes = schema::read_input_file(path, kMaxGltfBytes);
  } catch (const schema::InputFileError& e) {
    GltfImportResult r;
    r.diagnostics.error("E0710", SourceLocation{std::make_shared<const SourceFile>(path.string(), ""), 0, 0, 1},
                        "cannot read glTF file '" + path.string() + "': " + e.reason, "check the path");
    return r;
  }
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  return import_gltf_text(compiler, bytes, path.string(), folder);
}

}  // namespace sandpaper::compiler
