// Compiled patches -> glTF 2.0 with MPEG_haptic_material (docs/GLTF.md). The heights written are
// chosen so that the reader's force rules (gltf_support.hpp) give the compiled forces back; the
// writer measures that on its own 16-bit output and says how closely it holds.
#include "sandpaper/compiler/gltf_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gltf_support.hpp"
#include "sandpaper/compiler/recovered_height_field.hpp"
#include "sandpaper/schema/term_kinds.hpp"

namespace sandpaper::compiler {
namespace {

// glTF constants (glTF 2.0 specification, 5.x): component types, buffer targets, sampler values.
constexpr int kFloat = 5126, kUnsignedShort = 5123;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kLinear = 9729, kRepeat = 10497, kClampToEdge = 33071;

constexpr const char* kCannotCarry =
    "glTF's MPEG_haptic_material carries a height texture only: force laws with state or of velocity (springs, "
    "dampers, anti-viscous terms, physics models, friction, followers, attractors), constant and periodic force "
    "laws, energy budgets and perceptual targets are not carried; a patch's forces outside its height grid are "
    "zero in Sandpaper but clamped to the edge texels by a glTF sampler";

std::string num(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

// A haptic texture and what it came to, for one distinct program.
struct Texture {
  std::string kind = "none";  // "grating", "height_field", "none"
  int nx = 0, ny = 0;
  std::vector<std::uint16_t> texels;  // PNG order: row 0 the top (+y) row
  double k_N = 0, range_m = 0;
  bool nominal = true;
  double period_m = 0, orientation_rad = 0;                  // grating
  double origin_m[2] = {0, 0}, spacing_m[2] = {0, 0};        // height field
  bool repeat = false;
  double error = 0;  // largest |F' - F| / maximum lateral force
  std::vector<std::string> not_carried;
};

// Heights -> 16-bit texels and the range they span; false for a flat field.
bool quantize(const std::vector<double>& h, std::vector<std::uint16_t>& texels, std::vector<double>& back, double& range) {
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  range = *hi - *lo;
  if (!(range > 0) || !std::isfinite(range)) return false;
  texels.resize(h.size());
  back.resize(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    texels[i] = static_cast<std::uint16_t>(std::lround((h[i] - *lo) / range * gltf::kTexelMax));
    back[i] = texels[i] / gltf::kTexelMax * range;
  }
  return true;
}

double worst(const std::vector<float>& a, const std::vector<float>& b) {
  double w = 0;
  for (std::size_t i = 0; i < a.size(); ++i) w = std::max(w, std::abs(static_cast<double>(a[i]) - b[i]));
  return w;
}

bool grating_texture(const RecoveredHeightField& th, const schema::GratingTerm& g, double max_force_N, Texture& t,
                     std::string& why) {
  std::vector<double> back;
  if (!quantize(th.h_m, t.texels, back, t.range_m)) {
    why = "its grating is flat";
    return false;
  }
  t.kind = "grating";
  t.nx = th.nx;
  t.ny = 1;
  t.k_N = th.k_N;
  t.period_m = th.period_m;
  t.orientation_rad = th.orientation_rad;
  t.error = worst(gltf::grating_forces(back, g.period_m, th.k_N), g.force_N) / (max_force_N > 0 ? max_force_N : th.k_N);
  return true;
}

bool height_field_texture(const RecoveredHeightField& th, const schema::HeightFieldTerm& term,
                          const schema::PatchProgram& program, Texture& t, std::string& why) {
  const int nx = th.nx, ny = th.ny;
  std::vector<std::uint16_t> grid_texels;
  std::vector<double> back;
  if (!quantize(th.h_m, grid_texels, back, t.range_m)) {
    why = "its height map is flat";
    return false;
  }
  t.texels.resize(grid_texels.size());
  for (int r = 0; r < ny; ++r)  // PNG row 0 is the top edge (+y); grid row 0 is the bottom
    std::copy_n(grid_texels.begin() + static_cast<std::ptrdiff_t>(ny - 1 - r) * nx, nx,
                t.texels.begin() + static_cast<std::ptrdiff_t>(r) * nx);
  t.kind = "height_field";
  t.nx = nx;
  t.ny = ny;
  t.nominal = th.nominal;
  t.k_N = th.k_N;
  std::copy_n(th.origin_m, 2, t.origin_m);
  std::copy_n(th.spacing_m, 2, t.spacing_m);
  t.repeat = th.repeat;
  std::vector<float> fx, fy;
  gltf::height_field_forces(back, nx, ny, term.spacing_m[0], term.spacing_m[1], term.repeat, t.k_N, fx, fy);
  t.error = std::max(worst(fx, term.force_x_N), worst(fy, term.force_y_N)) / program.max_lateral_force_N;
  return true;
}

// The program's texture (its first grating or height field) and the rest, listed as not carried.
// False, with `why`, for a texture that cannot be exported.
bool make_texture(const schema::PatchProgram& program, const ResolvedMaterial* material, Texture& t, std::string& why) {
  bool have = false;
  for (const auto& term : program.terms) {
    const auto* grating = std::get_if<schema::GratingTerm>(&term);
    const auto* field = std::get_if<schema::HeightFieldTerm>(&term);
    if (!have && (grating || field)) {
      const auto heights = recover_height_field(program, material, why);  // of this, the first texture term
      if (!heights) return false;
      if (grating ? !grating_texture(*heights, *grating, program.max_lateral_force_N, t, why)
                  : !height_field_texture(*heights, *field, program, t, why))
        return false;
      have = true;
      continue;
    }
    schema::terms::visit_kind(term, [&](auto kind, const auto& each) {
      std::string what(kind.label);
      if (kind.has_state) what += " (keeps state)";
      if (!kind.passive(each)) what += " (not passive)";
      t.not_carried.push_back(what);
    });
  }
  if (program.energy_budget_J > 0)
    t.not_carried.push_back("energy budget " + num(program.energy_budget_J) + " J, refilled at " +
                            num(program.energy_refill_W) + " W");
  return true;
}

// Little-endian bytes of the asset's one buffer.
struct Bytes {
  std::vector<unsigned char> data;
  template <class T>
  void put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    data.insert(data.end(), b, b + sizeof(T));
  }
  void align4() {
    while (data.size() % 4) data.push_back(0);
  }
};

nlohmann::json sandpaper_extras(const schema::PatchProgram& p, const Texture& t, const std::string& source) {
  nlohmann::json provenance = nlohmann::json::array();
  std::string force_source;
  for (const auto& e : p.provenance) {
    provenance.push_back({{"parameter", e.parameter}, {"value_si", e.value_si}, {"si_unit", e.si_unit},
                          {"stated", e.stated}, {"layer", e.layer}, {"source", e.source}});
    if (e.parameter == "texture.max_lateral_force") force_source = e.stated + " (" + e.source + ")";
  }
  nlohmann::json j = {
      {"version", gltf::kExtrasVersion},
      {"name", p.name},
      {"describes", p.describes},
      {"source", source},
      {"device", p.device},
      {"texture", t.kind},
      {"patch_size_m", {p.size_m[0], p.size_m[1]}},
      {"compiled_max_lateral_force_N", p.max_lateral_force_N},
      {"max_lateral_force_source", force_source},
      {"compiled_roughness", p.roughness},
      {"roughness_map", p.roughness_map},
      {"not_carried", t.not_carried},
      {"format_cannot_carry", kCannotCarry},
      {"provenance", provenance},
  };
  if (t.kind == "none") return j;
  j["height_rule"] = "h_m = texel / 65535 * height_range_m; F_N = -lateral_gain_N * grad(h_m) (docs/GLTF.md)";
  j["height_range_m"] = t.range_m;
  j["heights_nominal"] = t.nominal;
  j["lateral_gain_N"] = t.k_N;
  j["round_trip_force_error"] = t.error;
  if (t.kind == "grating") {
    j["period_m"] = t.period_m;
    j["orientation_rad"] = t.orientation_rad;
  } else {
    j["grid_origin_m"] = {t.origin_m[0], t.origin_m[1]};
    j["grid_spacing_m"] = {t.spacing_m[0], t.spacing_m[1]};
    j["repeat"] = t.repeat;
  }
  return j;
}

// Texture coordinates of a patch-plane point (x, y), m: where its texel lies (docs/GLTF.md).
std::pair<float, float> uv_of(const Texture& t, const schema::PatchProgram& p, double x, double y) {
  if (t.kind == "grating") {
    const double c = std::cos(t.orientation_rad), s = std::sin(t.orientation_rad);
    return {static_cast<float>((x * c + y * s) / t.period_m), static_cast<float>((-x * s + y * c) / t.period_m)};
  }
  if (t.kind == "height_field") {
    const double x0 = t.origin_m[0] - 0.5 * t.spacing_m[0], y0 = t.origin_m[1] - 0.5 * t.spacing_m[1];
    return {static_cast<float>((x - x0) / (t.nx * t.spacing_m[0])), static_cast<float>(1 - (y - y0) / (t.ny * t.spacing_m[1]))};
  }
  return {static_cast<float>(x / p.size_m[0] + 0.5), static_cast<float>(0.5 - y / p.size_m[1])};
}

}  // namespace

std::optional<nlohmann::json> export_gltf(const std::vector<GltfPatch>& patches,
                                          const std::optional<GltfWorkspaceInfo>& workspace,
                                          const std::string& shown_name, Diagnostics& diags) {
  const SourceLocation at{std::make_shared<const SourceFile>(shown_name, ""), 0, 0, 1};
  nlohmann::json haptic_materials = nlohmann::json::array(), textures = nlohmann::json::array(),
                 images = nlohmann::json::array(), samplers = nlohmann::json::array(),
                 meshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 accessors = nlohmann::json::array(), views = nlohmann::json::array();
  std::map<const schema::PatchProgram*, std::size_t> material_of;
  std::vector<Texture> made;
  std::vector<std::optional<std::size_t>> texture_of;  // per haptic material, its height texture
  nlohmann::json visual_materials = nlohmann::json::array();
  Bytes buffer;
  bool failed = false;

  for (std::size_t pi = 0; pi < patches.size(); ++pi) {
    const GltfPatch& patch = patches[pi];
    const schema::PatchProgram& p = *patch.program;
    auto [it, fresh] = material_of.emplace(&p, made.size());
    if (fresh) {
      Texture t;
      std::string why;
      const std::string who = workspace ? "patch " + std::to_string(pi + 1) + " (" + patch.source + ")" : "'" + p.name + "'";
      if (!make_texture(p, patch.material, t, why)) {
        diags.error("E0702", at, "cannot export " + who + " to glTF: " + why,
                    "export a material with a grating or a height-map image (docs/GLTF.md, \"What is exported\")");
        failed = true;
        made.push_back(t);
        texture_of.emplace_back();
        continue;
      }
      if (t.kind == "none" && !workspace) {
        diags.error("E0701", at, "'" + p.name + "' has no texture (grating or height map) to export: glTF's haptic textures carry heights only",
                    "export a material with a texture; its force laws are listed in docs/GLTF.md, \"What cannot be carried\"");
        failed = true;
      }
      if (!t.not_carried.empty()) {
        std::string list;
        for (const auto& n : t.not_carried) list += (list.empty() ? "" : ", ") + n;
        diags.warning("W0701", at, "glTF cannot carry part of " + who + ": " + list + "; the asset holds its texture only",
                      "play the .hmat or .patch for the whole material; the asset's extras list what was left out");
      }
      if (t.kind != "none" && t.error > kGltfForceTolerance)
        diags.warning("W0702", at,
                      "the 16-bit heights of " + who + " give its forces back within " + num(t.error * 100) +
                          " % of its maximum lateral force, more than " + num(kGltfForceTolerance * 100) + " %",
                      "the texture's slope is small against its height range; add smoothing or use a smaller image");
      nlohmann::json hm = {{"name", p.name}};
      texture_of.emplace_back();
      if (t.kind != "none") {
        const std::size_t image = images.size();
        images.push_back({{"name", p.name + " heights"}, {"mimeType", "image/png"},
                          {"uri", std::string(gltf::kPngDataUriPrefix) + gltf::base64_encode(gltf::encode_png16(t.nx, t.ny, t.texels))}});
        const int wrap = (t.kind == "grating" || t.repeat) ? kRepeat : kClampToEdge;
        samplers.push_back({{"magFilter", kLinear}, {"minFilter", kLinear}, {"wrapS", wrap}, {"wrapT", wrap}});
        textures.push_back({{"sampler", samplers.size() - 1}, {"source", image}});
        hm["vibrotactileTexture"] = {{{"texture", {{"index", textures.size() - 1}}}, {"type", "High_Resolution"}}};
        texture_of.back() = textures.size() - 1;
      }
      hm["extras"] = {{gltf::kExtrasKey, sandpaper_extras(p, t, patch.source)}};
      haptic_materials.push_back(hm);
      made.push_back(std::move(t));
    }
    if (failed) continue;
    const Texture& t = made[it->second];

    // The plane: patch x -> glTF +X, patch y -> glTF -Z, normal +Y (glTF is y-up, right-handed).
    const double w = p.size_m[0], h = p.size_m[1];
    const double corner[4][2] = {{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}};
    const std::size_t first_view = views.size();
    auto view = [&](std::size_t begin, int target) {
      views.push_back({{"buffer", 0}, {"byteOffset", begin}, {"byteLength", buffer.data.size() - begin}, {"target", target}});
    };
    std::size_t begin = buffer.data.size();
    for (const auto& c : corner) buffer.put(static_cast<float>(c[0])), buffer.put(0.0f), buffer.put(static_cast<float>(-c[1]));
    view(begin, kArrayBuffer);
    begin = buffer.data.size();
    for (int i = 0; i < 4; ++i) buffer.put(0.0f), buffer.put(1.0f), buffer.put(0.0f);
    view(begin, kArrayBuffer);
    begin = buffer.data.size();
    for (const auto& c : corner) {
      const auto [u, v] = uv_of(t, p, c[0], c[1]);
      buffer.put(u), buffer.put(v);
    }
    view(begin, kArrayBuffer);
    begin = buffer.data.size();
    for (int i : {0, 1, 2, 0, 2, 3}) buffer.put(static_cast<std::uint16_t>(i));
    view(begin, kElementArrayBuffer);
    buffer.align4();
    const auto fw = static_cast<float>(w / 2), fh = static_cast<float>(h / 2);
    accessors.push_back({{"bufferView", first_view}, {"componentType", kFloat}, {"count", 4}, {"type", "VEC3"},
                         {"min", {-fw, 0.0f, -fh}}, {"max", {fw, 0.0f, fh}}});
    accessors.push_back({{"bufferView", first_view + 1}, {"componentType", kFloat}, {"count", 4}, {"type", "VEC3"}});
    accessors.push_back({{"bufferView", first_view + 2}, {"componentType", kFloat}, {"count", 4}, {"type", "VEC2"}});
    accessors.push_back({{"bufferView", first_view + 3}, {"componentType", kUnsignedShort}, {"count", 6}, {"type", "SCALAR"}});
    const std::size_t a = accessors.size() - 4;
    const std::string name = workspace ? "patch " + std::to_string(pi + 1) + ": " + patch.source : p.name;
    // Each patch's primitive gets a visual material of its own, its heights as the colour, marked with
    // its haptic material: pipelines merge primitives that share a visual material (glTF-Transform's
    // join) and fold untextured materials together (palette), and a merged mesh's primitives keep
    // their haptic materials only through their own materials (docs/GLTF.md, "What is exported").
    nlohmann::json visual = {{"name", name},
                             {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                             {"extras", {{gltf::kExtrasKey, {{"hapticMaterialIndex", it->second}, {"patch", pi}}}}}};
    if (texture_of[it->second]) visual["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", *texture_of[it->second]}};
    visual_materials.push_back(visual);
    meshes.push_back({{"name", name},
                      {"primitives", {{{"attributes", {{"POSITION", a}, {"NORMAL", a + 1}, {"TEXCOORD_0", a + 2}}},
                                       {"indices", a + 3}, {"material", visual_materials.size() - 1}, {"mode", 4}}}},
                      {"extensions", {{gltf::kExtension, {{"hapticMaterialIndex", it->second}}}}}});
    nlohmann::json node = {{"name", name}, {"mesh", meshes.size() - 1}};
    if (patch.centre_m[0] != 0 || patch.centre_m[1] != 0) node["translation"] = {patch.centre_m[0], 0.0, -patch.centre_m[1]};
    nodes.push_back(node);
  }
  if (failed || diags.has_errors()) return std::nullopt;

  nlohmann::json scene_nodes = nlohmann::json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) scene_nodes.push_back(i);
  const std::string scene_name = workspace ? workspace->name : patches.empty() ? "" : patches.front().program->name;
  nlohmann::json asset = {
      {"asset", {{"version", "2.0"}, {"generator", "Sandpaper (sandpaper export --format gltf)"}}},
      {"extensionsUsed", {gltf::kExtension}},
      {"extensions", {{gltf::kExtension, {{"materials", haptic_materials}}}}},
      {"scene", 0},
      {"scenes", {{{"name", scene_name}, {"nodes", scene_nodes}}}},
      {"nodes", nodes},
      {"meshes", meshes},
      {"materials", visual_materials},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"byteLength", buffer.data.size()},
                    {"uri", "data:application/octet-stream;base64," + gltf::base64_encode(buffer.data)}}}},
  };
  if (!images.empty()) {
    asset["images"] = images;
    asset["samplers"] = samplers;
    asset["textures"] = textures;
  }
  if (workspace)
    asset["extras"] = {{gltf::kExtrasKey,
                        {{"version", gltf::kExtrasVersion},
                         {"workspace", {{"name", workspace->name}, {"size_m", {workspace->size_m[0], workspace->size_m[1]}},
                                        {"patches", patches.size()}}}}}};
  return asset;
}

namespace {

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

// The bytes of a data URI export_gltf wrote (base64 after the comma).
std::vector<unsigned char> data_uri_bytes(const std::string& uri) {
  const auto comma = uri.find(',');
  auto bytes = comma == std::string::npos ? std::nullopt : gltf::base64_decode(std::string_view(uri).substr(comma + 1));
  if (!bytes) throw std::logic_error("gltf_to_glb: the asset holds a data URI it did not write");
  return *bytes;
}

}  // namespace

std::string gltf_to_glb(const nlohmann::json& asset) {
  nlohmann::json j = asset;
  std::vector<unsigned char> bin;
  auto pad = [&] { while (bin.size() % 4) bin.push_back(0); };
  // The geometry buffer's bytes first, its views unchanged; then each image as a view of its own.
  if (j.contains("buffers") && !j["buffers"].empty()) {
    bin = data_uri_bytes(j["buffers"][0]["uri"].get<std::string>());
    j["buffers"][0].erase("uri");
  } else {
    j["buffers"] = nlohmann::json::array({nlohmann::json::object()});
  }
  if (j.contains("images"))
    for (auto& image : j["images"]) {
      pad();
      const auto png = data_uri_bytes(image["uri"].get<std::string>());
      if (!j.contains("bufferViews")) j["bufferViews"] = nlohmann::json::array();
      j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", png.size()}});
      image.erase("uri");
      image["bufferView"] = j["bufferViews"].size() - 1;
      bin.insert(bin.end(), png.begin(), png.end());
    }
  pad();
  j["buffers"][0]["byteLength"] = bin.size();
  std::string text = j.dump();
  while (text.size() % 4) text += ' ';  // the JSON chunk is padded with spaces
  std::string out;
  put_u32(out, 0x46546C67);             // "glTF"
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  put_u32(out, static_cast<std::uint32_t>(text.size()));
  put_u32(out, 0x4E4F534A);             // "JSON"
  out += text;
  put_u32(out, static_cast<std::uint32_t>(bin.size()));
  put_u32(out, 0x004E4942);             // "BIN\0"
  out.append(bin.begin(), bin.end());
  return out;
}

}  // namespace sandpaper::compiler
