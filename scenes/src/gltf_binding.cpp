// A glTF scene surface's material and contact (gltf_binding.hpp).
#include "gltf_binding.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "sandpaper/compiler/gltf_document.hpp"
#include "sandpaper/scenes/gltf_scene.hpp"
#include "sandpaper/schema/confined_path.hpp"

namespace sandpaper::scenes::gltf_read {
namespace {

using compiler::gltf_index;
using compiler::gltf_member;
using compiler::gltf_optional_member;
using compiler::refuse_gltf;
using nlohmann::json;

std::string num(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// `extras.sandpaper` of a JSON object, or null; E0865 when it is there but not an object.
const json* sandpaper_extras(const json& j, const std::string& where) {
  const json* extras = gltf_optional_member(j, "extras");
  const json* ours = extras ? gltf_optional_member(*extras, "sandpaper") : nullptr;
  if (ours && !ours->is_object()) refuse_gltf("E0865", where + ".extras.sandpaper is not a JSON object");
  return ours;
}

// The places a surface's `extras.sandpaper` keys are looked for, first found wins.
struct Place {
  const json* extras;
  std::string where;  // "materials[2].extras.sandpaper"
};

const json* first(const std::vector<Place>& places, const char* key, std::string& where) {
  for (const Place& p : places)
    if (const json* v = gltf_optional_member(*p.extras, key)) {
      where = p.where + "." + key;
      return v;
    }
  return nullptr;
}

std::optional<double> number(const std::vector<Place>& places, const char* key, double lo, double hi, bool lo_open) {
  std::string where;
  const json* v = first(places, key, where);
  if (!v) return std::nullopt;
  if (!v->is_number()) refuse_gltf("E0865", where + " is " + v->type_name() + ", not a number");
  const double x = v->get<double>();
  if (!std::isfinite(x) || (lo_open ? x <= lo : x < lo) || x > hi)
    refuse_gltf("E0865", where + " is " + num(x) + ", outside " + (lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + "]");
  // The compiler's range for a quantity, which a scene program keeps to (shapes/scene_io.hpp).
  if (x != 0 && x < 1e-12) refuse_gltf("E0865", where + " is " + num(x) + ": below 1e-12, no quantity Sandpaper reads");
  return x;
}

}  // namespace

Binder::Binder(const compiler::GltfDocument& doc, compiler::Diagnostics& diags, compiler::SourceLocation at,
               std::optional<std::filesystem::path> folder)
    : doc_(doc), diags_(diags), at_(std::move(at)), folder_(std::move(folder)) {}

std::string Binder::material_text(const std::string& text, const std::string& where) {
  if (text.empty() || text.size() > kMaxGltfMaterialText)
    refuse_gltf("E0865", where + " is " + (text.empty() ? std::string("empty") : "over " + std::to_string(kMaxGltfMaterialText) + " bytes"),
                "name a library entry (\"corduroy\"), write a one-line material, or name a .hmat file beside the asset");
  if (text.find_first_of(std::string("\0\n\r", 3)) != std::string::npos)
    refuse_gltf("E0865", where + " holds a line break or a NUL: a material named in a glTF asset is one line");
  // A file must lie in the asset's own folder, as its buffers and images must (E0715).
  if (ends_with(text, ".hmat")) {
    if (!folder_)
      refuse_gltf("E0865", where + " names the file '" + text.substr(0, 120) + "', but the asset was read without its folder");
    try {
      (void)schema::confined_path(*folder_, text, "the asset's folder", "a glTF scene's .hmat materials lie in its own folder");
    } catch (const schema::OutsideFolder& e) {
      refuse_gltf("E0865", where + ": " + e.what());
    }
  }
  if (materials_.insert(text).second && materials_.size() > kMaxGltfSceneMaterials)
    refuse_gltf("E0864", "the scene binds more than " + std::to_string(kMaxGltfSceneMaterials) + " distinct materials (at " + where + ")",
                "bind fewer materials, or split the scene");
  return text;
}

std::optional<std::size_t> Binder::haptic_index(std::optional<std::size_t> material, std::size_t mesh) {
  const json* ext = gltf_optional_member(doc_.root(), "extensions");
  const json* top = ext ? gltf_optional_member(*ext, "MPEG_haptic_material") : nullptr;
  const json* list = top ? gltf_optional_member(*top, "materials") : nullptr;
  auto checked = [&](const json& index, const std::string& where) {
    if (!list || !list->is_array())
      refuse_gltf("E0865", where + " names a haptic material, but the asset has no extensions.MPEG_haptic_material.materials");
    return gltf_index(index, *list, where, "E0865");
  };
  // Sandpaper marks each patch's own visual material; other tools name one per mesh.
  if (material) {
    const std::string mw = "materials[" + std::to_string(*material) + "]";
    if (const json* ours = sandpaper_extras(doc_.root()["materials"][*material], mw))
      if (const json* mark = gltf_optional_member(*ours, "hapticMaterialIndex"))
        return checked(*mark, mw + ".extras.sandpaper.hapticMaterialIndex");
  }
  const std::string mw = "meshes[" + std::to_string(mesh) + "]";
  const json* mext = gltf_optional_member(doc_.root()["meshes"][mesh], "extensions");
  const json* hm = mext ? gltf_optional_member(*mext, "MPEG_haptic_material") : nullptr;
  if (!hm) return std::nullopt;
  const std::string hw = mw + ".extensions.MPEG_haptic_material";
  return checked(gltf_member(*hm, "hapticMaterialIndex", hw, "E0865"), hw + ".hapticMaterialIndex");
}

// The mean of the first usable texture of a stiffness or friction list (normalized texels, 0..1).
std::optional<double> Binder::value_texture(const json& list, const std::string& where, const char* what,
                                            std::vector<std::string>& unused) {
  if (!list.is_array()) refuse_gltf("E0865", where + " is not an array of haptic textures");
  // The list may hold one property several ways (a texture and a taxel map, two resolutions): the
  // first high-resolution texture, else the first low-resolution one.
  const json* chosen = nullptr;
  std::size_t chosen_at = 0;
  for (const char* wanted : {"High_Resolution", "Low_Resolution"}) {
    for (std::size_t i = 0; i < list.size() && !chosen; ++i) {
      const std::string iw = where + "[" + std::to_string(i) + "]";
      const json& type = gltf_member(list[i], "type", iw, "E0865");
      if (!type.is_string()) refuse_gltf("E0865", iw + ".type is not a string");
      if (type.get<std::string>() == wanted) chosen = &list[i], chosen_at = i;
    }
  }
  if (!chosen) {
    if (!list.empty()) unused.push_back(std::string(what) + " (a Reference or Other texture: an MPEG_haptic media Sandpaper does not read)");
    return std::nullopt;
  }
  const std::string iw = where + "[" + std::to_string(chosen_at) + "]";
  const json& info = gltf_member(*chosen, "texture", iw, "E0865");
  const json& textures = gltf_member(doc_.root(), "textures", "the asset", "E0715");
  const std::size_t ti = gltf_index(gltf_member(info, "index", iw + ".texture", "E0715"), textures, iw + ".texture.index", "E0715");
  const std::string tw = "textures[" + std::to_string(ti) + "]";
  const json* source = gltf_optional_member(textures[ti], "source");
  if (!source)
    refuse_gltf("E0716", "the " + std::string(what) + " texture of " + iw + " (" + tw +
                             ") has no PNG source (its image is in an extension: WebP, AVIF or KTX2)",
                "write the " + std::string(what) + " texture as a PNG");
  const std::vector<unsigned char> bytes = doc_.image_bytes(*source, tw + ".source");
  std::string why;
  const long long limit = std::max<long long>(0, std::min<long long>(4096LL * 4096LL, kMaxGltfSceneValueTexels - texels_));
  const auto image = compiler::decode_gltf_value_png(bytes, limit, why);
  if (!image)
    refuse_gltf(why.find("over the limit") != std::string::npos ? schema::Code("E0717") : schema::Code("E0716"),
                "the " + std::string(what) + " texture of " + iw + " (" + tw + "'s image): " + why);
  texels_ += static_cast<long long>(image->values.size());
  double sum = 0, lo = 1, hi = 0;
  for (float v : image->values) {
    sum += v;
    lo = std::min(lo, static_cast<double>(v));
    hi = std::max(hi, static_cast<double>(v));
  }
  double mean = sum / static_cast<double>(image->values.size());
  if (mean < 1e-12) mean = 0;  // below any quantity Sandpaper reads (a texel in 4096^2 of 1/65535)
  // More than one 8-bit step apart: a texture that varies, where a surface has one value.
  if (hi - lo > 1.5 / 255)
    unused.push_back("the variation of its " + std::string(what) + " (texels " + num(lo) + " to " + num(hi) + "; a surface has one " +
                     what + ", the mean " + num(mean) + " is used)");
  return mean;
}

const Binder::Haptic& Binder::haptic(std::size_t index) {
  if (auto it = haptics_.find(index); it != haptics_.end()) return it->second;
  const json& m = doc_.root()["extensions"]["MPEG_haptic_material"]["materials"][index];
  Haptic h;
  h.where = "extensions.MPEG_haptic_material.materials[" + std::to_string(index) + "]";
  if (!m.is_object()) refuse_gltf("E0865", h.where + " is not a JSON object");
  if (const json* name = gltf_optional_member(m, "name"); name && name->is_string() && !name->get<std::string>().empty())
    h.shown = " (\"" + name->get<std::string>().substr(0, 80) + "\")";
  std::vector<std::string> unused;
  // A haptic material Sandpaper wrote names what it was compiled from: a library entry or a line is
  // compiled again (the whole material, not only the texture the asset carries); a file's path was
  // the writer's, not the asset's.
  bool written_by_sandpaper = false;
  if (const json* ours = sandpaper_extras(m, h.where))
    if (const json* source = gltf_optional_member(*ours, "source"); source && source->is_string()) {
      written_by_sandpaper = true;
      const std::string& s = source->get_ref<const std::string&>();
      if (!s.empty() && s.size() <= kMaxGltfMaterialText && !ends_with(s, ".hmat") && s.find_first_of(std::string("\0\n\r", 3)) == std::string::npos)
        h.source = s;
      else
        unused.push_back("its vibrotactile texture (Sandpaper's, of the file '" + s.substr(0, 120) +
                         "', which is not compiled from the asset: bind the surface by name)");
    }
  if (const json* s = gltf_optional_member(m, "stiffness"))
    if (const auto mean = value_texture(*s, h.where + ".stiffness", "stiffness", unused)) {
      if (*mean > 0) {
        h.stiffness_N_per_m = *mean * kMpegStiffnessFullScale_N_per_m;
        diags_.warning("W0864", at_,
                       h.where + h.shown + ": its stiffness texture reads " + num(*mean) + " of full scale; MPEG_haptic_material gives " +
                           "its texels no unit, so Sandpaper reads them as a fraction of " + num(kMpegStiffnessFullScale_N_per_m) +
                           " N/m: " + num(*h.stiffness_N_per_m) + " N/m",
                       "state the stiffness in SI with extras.sandpaper.stiffness_N_per_m on the glTF material");
      } else {
        diags_.warning("W0864", at_, h.where + h.shown + ": its stiffness texture is zero, which no surface can have: not used",
                       "state the stiffness in SI with extras.sandpaper.stiffness_N_per_m on the glTF material");
      }
    }
  if (const json* f = gltf_optional_member(m, "friction")) h.friction = value_texture(*f, h.where + ".friction", "friction", unused);
  // A vibrotactile texture Sandpaper wrote gives way to the material it came from, compiled again;
  // another tool's has no rule that makes its texels heights or forces.
  if (const json* v = gltf_optional_member(m, "vibrotactileTexture"); v && v->is_array() && !v->empty() && !written_by_sandpaper)
    h.textured = true;
  for (const char* other : {"temperature", "vibration", "custom"})
    if (const json* v = gltf_optional_member(m, other); v && (!v->is_array() || !v->empty())) unused.push_back(std::string("its ") + other);
  if (gltf_optional_member(m, "haptic")) unused.push_back("its haptic (an MPEG_haptic object, which Sandpaper does not read)");
  if (!unused.empty()) {
    std::string list;
    for (const auto& u : unused) list += (list.empty() ? "" : "; ") + u;
    diags_.warning("W0863", at_, h.where + h.shown + ": not used on a 3-D surface: " + list,
                   "a surface takes a material's texture by name (extras.sandpaper.material) and one stiffness and friction");
  }
  return haptics_.emplace(index, std::move(h)).first->second;
}

SurfaceSource Binder::surface(std::optional<std::size_t> material, std::size_t mesh, std::size_t node) {
  const json& root = doc_.root();
  std::vector<Place> places;  // material, node, mesh: the most particular first
  if (material) {
    const std::string w = "materials[" + std::to_string(*material) + "]";
    if (const json* e = sandpaper_extras(root["materials"][*material], w)) places.push_back({e, w + ".extras.sandpaper"});
  }
  {
    const std::string w = "nodes[" + std::to_string(node) + "]";
    if (const json* e = sandpaper_extras(root["nodes"][node], w)) places.push_back({e, w + ".extras.sandpaper"});
    const std::string mw = "meshes[" + std::to_string(mesh) + "]";
    if (const json* e = sandpaper_extras(root["meshes"][mesh], mw)) places.push_back({e, mw + ".extras.sandpaper"});
  }
  SurfaceSource s;
  s.location = at_;
  std::string where;
  if (const json* m = first(places, "material", where)) {
    if (!m->is_string()) refuse_gltf("E0865", where + " is " + m->type_name() + ", not a material's name or text");
    s.material = material_text(m->get<std::string>(), where);
  }
  s.stiffness_N_per_m = number(places, "stiffness_N_per_m", 0, 1e6, true);
  s.damping_Ns_per_m = number(places, "damping_Ns_per_m", 0, 1e4, false);
  s.static_friction = number(places, "static_friction", 0, 10, false);
  s.kinetic_friction = number(places, "kinetic_friction", 0, 10, false);
  if (s.kinetic_friction && !s.static_friction)
    refuse_gltf("E0865", "kinetic_friction is given without static_friction", "give static_friction too (kinetic at most static)");
  if (s.static_friction && !s.kinetic_friction) s.kinetic_friction = s.static_friction;
  if (s.kinetic_friction && *s.kinetic_friction > *s.static_friction)
    refuse_gltf("E0865", "kinetic_friction " + num(*s.kinetic_friction) + " is above static_friction " + num(*s.static_friction),
                "kinetic friction is at most static");
  if (const json* uv = first(places, "uv_size_m", where)) {
    if (!uv->is_array() || uv->size() != 2 || !(*uv)[0].is_number() || !(*uv)[1].is_number())
      refuse_gltf("E0865", where + " is not a pair of numbers [u, v] (metres of surface per unit of u and v)");
    const glm::dvec2 size{(*uv)[0].get<double>(), (*uv)[1].get<double>()};
    if (!(size.x >= 1e-12 && size.x <= 100 && size.y >= 1e-12 && size.y <= 100))
      refuse_gltf("E0865", where + " is not two sizes of 1e-12 to 100 m");
    s.uv_size_m = size;
  }
  // The scene file's `texture relief D [only]`: the carve's depth, at most 10 mm as there (E0814).
  s.relief_depth_m = number(places, "relief_depth_m", 0, 0.01, true);
  if (const json* only = first(places, "relief_only", where)) {
    if (!only->is_boolean()) refuse_gltf("E0865", where + " is " + only->type_name() + ", not true or false");
    if (!s.relief_depth_m)
      refuse_gltf("E0865", where + " is given without relief_depth_m", "give the relief's depth in metres, e.g. \"relief_depth_m\": 0.0005");
    s.lateral_texture = !only->get<bool>();
  }
  // MPEG_haptic_material: its stiffness and friction where extras state none; a Sandpaper-written
  // one's material where no name is bound.
  if (const auto h = haptic_index(material, mesh)) {
    const Haptic& hm = haptic(*h);
    if (!s.stiffness_N_per_m) s.stiffness_N_per_m = hm.stiffness_N_per_m;
    if (!s.static_friction && hm.friction) s.static_friction = s.kinetic_friction = hm.friction;
    if (s.material.empty() && !hm.source.empty()) s.material = material_text(hm.source, hm.where + ".extras.sandpaper.source");
    if (s.material.empty() && hm.textured && untextured_warned_.insert(*h).second)
      diags_.warning("W0863", at_,
                     hm.where + hm.shown + ": not used on a 3-D surface: its vibrotactile texture (not written by Sandpaper: no rule "
                                           "gives its texels as heights or forces); the surface is untextured",
                     "bind the surface to a Sandpaper material by name: extras.sandpaper.material on the glTF material");
  }
  return s;
}

}  // namespace sandpaper::scenes::gltf_read
