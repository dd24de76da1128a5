// glTF 2.0 scenes -> SceneSource (gltf_scene.hpp; docs/GLTF.md, "Scenes (3-D)"): the node
// hierarchy walked with its transforms composed, each mesh primitive's triangles placed in the
// scene's frame and each glTF material's surface bound (gltf_binding.hpp). Outside input: the first
// problem ends the read with one diagnostic naming the JSON place.
#include "sandpaper/scenes/gltf_scene.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "gltf_accessor.hpp"
#include "gltf_binding.hpp"
#include "sandpaper/compiler/gltf_document.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::scenes {
namespace {

namespace fs = std::filesystem;
using compiler::GltfDocument;
using compiler::gltf_index;
using compiler::gltf_member;
using compiler::gltf_optional_member;
using compiler::refuse_gltf;
using compiler::SourceLocation;
using nlohmann::json;

// Extensions that compress a mesh's geometry: their accessors hold no readable data without a
// decoder, and glTF says a reader that does not know a required extension must not load the asset.
constexpr std::string_view kGeometryCompression[] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};
// Required extensions that change nothing Sandpaper reads (looks, lights, image formats, other MPEG
// media) or that it reads (quantized attributes).
constexpr std::string_view kHarmlessPrefixes[] = {"KHR_materials_", "KHR_texture_", "EXT_texture_", "KHR_lights_", "MPEG_",
                                                  "KHR_mesh_quantization"};

std::string num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// `count` finite numbers at `key` of a node, or nullopt when absent (E0860 otherwise).
std::optional<std::vector<double>> numbers(const json& node, const char* key, std::size_t count, const std::string& nw) {
  const json* t = gltf_optional_member(node, key);
  if (!t) return std::nullopt;
  const std::string w = nw + "." + key;
  if (!t->is_array() || t->size() != count) refuse_gltf("E0860", w + " is not " + std::to_string(count) + " numbers");
  std::vector<double> v(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!(*t)[i].is_number()) refuse_gltf("E0860", w + " is not " + std::to_string(count) + " numbers");
    v[i] = (*t)[i].get<double>();
    if (!std::isfinite(v[i])) refuse_gltf("E0860", w + "[" + std::to_string(i) + "] is not finite");
  }
  return v;
}

// A node's local transform (glTF 2.0 section 3.5.3): its matrix (column-major), or T * R * S.
glm::dmat4 local_transform(const json& node, const std::string& nw) {
  const auto matrix = numbers(node, "matrix", 16, nw);
  const auto t = numbers(node, "translation", 3, nw);
  const auto r = numbers(node, "rotation", 4, nw);
  const auto s = numbers(node, "scale", 3, nw);
  if (matrix) {
    if (t || r || s)
      refuse_gltf("E0860", nw + " has both a matrix and a translation, rotation or scale, which glTF does not allow",
                  "give the node one or the other");
    glm::dmat4 m(1.0);
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row) m[c][row] = (*matrix)[static_cast<std::size_t>(c * 4 + row)];
    // glTF's matrices are affine (decomposable into T * R * S): the bottom row is 0 0 0 1.
    if (std::abs(m[0][3]) > 1e-9 || std::abs(m[1][3]) > 1e-9 || std::abs(m[2][3]) > 1e-9 || std::abs(m[3][3] - 1) > 1e-9)
      refuse_gltf("E0860", nw + ".matrix is not affine (its bottom row is not 0 0 0 1)");
    return m;
  }
  glm::dmat4 out(1.0);
  if (t) out = glm::translate(out, glm::dvec3((*t)[0], (*t)[1], (*t)[2]));
  if (r) {
    glm::dquat q((*r)[3], (*r)[0], (*r)[1], (*r)[2]);  // glTF writes x, y, z, w
    const double norm = glm::length(q);
    if (!(norm > 1e-6)) refuse_gltf("E0860", nw + ".rotation is a zero quaternion, not a rotation");
    out = out * glm::mat4_cast(q / norm);
  }
  if (s) out = glm::scale(out, glm::dvec3((*s)[0], (*s)[1], (*s)[2]));
  return out;
}

// shapes::Mesh::build_nonrt's rule (shapes/src/mesh.cpp), computed the same way on the same
// doubles, so that every triangle kept is one the mesh accepts: the sine of the smallest angle,
// twice the area over the product of the two longest edges, must exceed 1e-12.
bool degenerate(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2) {
  const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0, e3 = v2 - v1;
  const double area2 = glm::length(glm::cross(e1, e2));
  const double l1 = glm::length(e1), l2 = glm::length(e2), l3 = glm::length(e3);
  const double longest_pair = std::max({l1 * l2, l2 * l3, l1 * l3});
  return !(area2 > 1e-12 * longest_pair);
}

const char* mode_name(int mode) {
  static constexpr const char* kNames[] = {"points", "lines", "line loops", "line strips"};
  return mode >= 0 && mode < 4 ? kNames[mode] : "?";
}

class Walker {
 public:
  Walker(const GltfDocument& doc, compiler::Diagnostics& diags, SourceLocation at, std::optional<fs::path> folder)
      : doc_(doc), diags_(diags), at_(at), binder_(doc, diags, at, std::move(folder)) {}

  std::vector<ObjectSource> walk() {
    const json& root = doc_.root();
    extensions();
    const json* nodes = gltf_optional_member(root, "nodes");
    if (nodes && !nodes->is_array()) refuse_gltf("E0712", "nodes is not an array");
    const std::size_t n_nodes = nodes ? nodes->size() : 0;
    for (const char* key : {"meshes", "materials"})
      if (const json* a = gltf_optional_member(root, key); a && !a->is_array()) refuse_gltf("E0712", std::string(key) + " is not an array");
    for (const auto& [key, what] : {std::pair{"animations", "animations (the scene is read at rest)"},
                                    std::pair{"skins", "skins (skinned meshes are read in their bind pose, unposed)"}})
      if (const json* a = gltf_optional_member(root, key); a && a->is_array() && !a->empty()) not_read_.insert(what);
    // The default scene's root nodes; without scenes, every node that is no node's child.
    std::vector<std::size_t> roots;
    if (const json* scenes = gltf_optional_member(root, "scenes")) {
      if (!scenes->is_array()) refuse_gltf("E0712", "scenes is not an array");
      std::size_t s = 0;
      if (const json* scene = gltf_optional_member(root, "scene")) s = gltf_index(*scene, *scenes, "scene", "E0712");
      if (!scenes->empty()) {
        const std::string sw = "scenes[" + std::to_string(s) + "]";
        if (const json* name = gltf_optional_member((*scenes)[s], "name"); name && name->is_string()) scene_name_ = name->get<std::string>();
        if (const json* list = gltf_optional_member((*scenes)[s], "nodes")) {
          if (!list->is_array() || !nodes) refuse_gltf("E0712", sw + ".nodes is not an array of node indices");
          for (std::size_t i = 0; i < list->size(); ++i)
            roots.push_back(gltf_index((*list)[i], *nodes, sw + ".nodes[" + std::to_string(i) + "]", "E0712"));
        }
      }
    } else if (gltf_optional_member(root, "scene")) {
      refuse_gltf("E0712", "scene names a scene, but the asset has no scenes");
    } else if (nodes) {
      std::vector<bool> child(n_nodes, false);
      for (std::size_t n = 0; n < n_nodes; ++n)
        if (const json* c = gltf_optional_member((*nodes)[n], "children"); c && c->is_array())
          for (const json& i : *c)
            if (i.is_number_unsigned() && i.get<std::uint64_t>() < n_nodes) child[i.get<std::size_t>()] = true;
      for (std::size_t n = 0; n < n_nodes; ++n)
        if (!child[n]) roots.push_back(n);
    }
    // Depth first, children in order, each node once: glTF's nodes form trees, and a node met twice
    // (under two parents, or its own ancestor) would place its mesh twice or never end.
    std::vector<bool> visited(n_nodes, false);
    for (std::size_t r : roots) {
      std::vector<std::pair<std::size_t, glm::dmat4>> stack{{r, glm::dmat4(1.0)}};
      while (!stack.empty()) {
        auto [n, parent] = stack.back();
        stack.pop_back();
        const std::string nw = "nodes[" + std::to_string(n) + "]";
        if (visited[n])
          refuse_gltf("E0860", nw + " is reached twice (a child of two parents, a root and a child, or its own ancestor): glTF's nodes form trees");
        visited[n] = true;
        const json& node = (*nodes)[n];
        if (!node.is_object()) refuse_gltf("E0712", nw + " is not a JSON object");
        const glm::dmat4 world = parent * local_transform(node, nw);
        if (gltf_optional_member(node, "skin")) not_read_.insert("skins (skinned meshes are read in their bind pose, unposed)");
        if (const json* e = gltf_optional_member(node, "extensions"); e && gltf_optional_member(*e, "EXT_mesh_gpu_instancing"))
          not_read_.insert("GPU instances (EXT_mesh_gpu_instancing: each such mesh is placed once, at its node)");
        if (const json* mesh = gltf_optional_member(node, "mesh")) object(n, nw, *mesh, world);
        if (const json* children = gltf_optional_member(node, "children")) {
          if (!children->is_array()) refuse_gltf("E0712", nw + ".children is not an array of node indices");
          for (std::size_t i = children->size(); i-- > 0;)
            stack.emplace_back(gltf_index((*children)[i], *nodes, nw + ".children[" + std::to_string(i) + "]", "E0712"), world);
        }
      }
    }
    report();
    return std::move(objects_);
  }

  const std::string& scene_name() const { return scene_name_; }

 private:
  void extensions() {
    const json* required = gltf_optional_member(doc_.root(), "extensionsRequired");
    if (!required || !required->is_array()) return;
    for (const json& e : *required) {
      if (!e.is_string()) continue;
      const std::string& name = e.get_ref<const std::string&>();
      for (std::string_view c : kGeometryCompression)
        if (name == c)
          refuse_gltf("E0866", "the asset requires " + name + ", which compresses its meshes; Sandpaper does not decode it",
                      "write the asset without geometry compression (gltf-transform copy, or export without Draco or meshopt)");
      if (std::none_of(std::begin(kHarmlessPrefixes), std::end(kHarmlessPrefixes),
                       [&](std::string_view p) { return name.compare(0, p.size(), p) == 0; }))
        not_read_.insert("the required extension " + name.substr(0, 80));
    }
  }

  // Node `n`'s mesh as an object: every triangle primitive placed by `world`, one surface per glTF
  // material, degenerate triangles dropped.
  void object(std::size_t n, const std::string& nw, const json& mesh_index, const glm::dmat4& world) {
    const json& root = doc_.root();
    const json* meshes = gltf_optional_member(root, "meshes");
    if (!meshes) refuse_gltf("E0712", nw + ".mesh names a mesh, but the asset has no meshes");
    const std::size_t mi = gltf_index(mesh_index, *meshes, nw + ".mesh", "E0712");
    const std::string mw = "meshes[" + std::to_string(mi) + "]";
    const json& mesh = (*meshes)[mi];
    if (!mesh.is_object()) refuse_gltf("E0712", mw + " is not a JSON object");
    const json& prims = gltf_member(mesh, "primitives", mw, "E0861");
    if (!prims.is_array()) refuse_gltf("E0861", mw + ".primitives is not an array");
    // A mirroring transform turns outward faces inward: their winding is turned back.
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0;

    ObjectSource o;
    o.name = name_of(root["nodes"][n], mesh, n);
    o.shape = "mesh";
    o.location = at_;
    std::map<long long, std::uint16_t> surface_of;  // glTF material (-1: none) -> the object's surface
    std::vector<std::optional<std::size_t>> surface_material;
    bool any_uvs = false;
    std::size_t dropped = 0, read = 0;
    for (std::size_t p = 0; p < prims.size(); ++p) {
      const std::string pw = mw + ".primitives[" + std::to_string(p) + "]";
      const json& prim = prims[p];
      if (!prim.is_object()) refuse_gltf("E0861", pw + " is not a JSON object");
      int mode = 4;
      if (const json* m = gltf_optional_member(prim, "mode")) {
        if (!m->is_number_unsigned() || m->get<std::uint64_t>() > 6) refuse_gltf("E0861", pw + ".mode is not a glTF primitive mode (0-6)");
        mode = m->get<int>();
      }
      if (mode < 4) {
        ++skipped_[mode];
        continue;
      }
      if (const json* t = gltf_optional_member(prim, "targets"); t && t->is_array() && !t->empty())
        not_read_.insert("morph targets (their meshes are read with no target weighted)");
      std::optional<std::size_t> material;
      if (const json* m = gltf_optional_member(prim, "material")) {
        const json* materials = gltf_optional_member(root, "materials");
        if (!materials) refuse_gltf("E0712", pw + ".material names a material, but the asset has no materials");
        material = gltf_index(*m, *materials, pw + ".material", "E0712");
      }
      const json& attributes = gltf_member(prim, "attributes", pw, "E0861");
      const json* position = gltf_optional_member(attributes, "POSITION");
      if (!position)
        refuse_gltf("E0861", pw + " has no POSITION: a primitive without vertices has no surface to touch");
      using namespace gltf_read;
      const std::string aw = pw + ".attributes.POSITION";
      const std::vector<double> pos = read_attribute(doc_, *position, aw, "VEC3", {kFloat, kByte, kUnsignedByte, kShort, kUnsignedShort},
                                                     kMaxGltfSceneVertices - vertices_);
      const std::size_t count = pos.size() / 3;
      vertices_ += count;
      std::vector<double> uv;
      if (const json* t = gltf_optional_member(attributes, "TEXCOORD_0")) {
        const std::string tw = pw + ".attributes.TEXCOORD_0";
        if (accessor_count(doc_, *t, tw, "VEC2") != count)
          refuse_gltf("E0862", tw + " has " + std::to_string(accessor_count(doc_, *t, tw, "VEC2")) + " elements for " +
                                   std::to_string(count) + " vertices");
        uv = read_attribute(doc_, *t, tw, "VEC2", {kFloat, kUnsignedByte, kUnsignedShort, kByte, kShort}, count);
      }
      // The corners, in glTF's order for each mode (section 3.7.2.1).
      std::vector<std::uint32_t> idx;
      if (const json* i = gltf_optional_member(prim, "indices")) {
        idx = read_indices(doc_, *i, pw + ".indices", 3 * (kMaxGltfSceneTriangles - triangles_) + 2);
        for (std::size_t k = 0; k < idx.size(); ++k)
          if (idx[k] >= count)
            refuse_gltf("E0863", pw + ".indices[" + std::to_string(k) + "] is " + std::to_string(idx[k]) + ", past its " +
                                     std::to_string(count) + " vertices");
      } else {
        idx.resize(count);
        for (std::size_t k = 0; k < count; ++k) idx[k] = static_cast<std::uint32_t>(k);
      }
      const std::size_t corners = idx.size();
      const std::size_t n_tri = mode == 4 ? corners / 3 : corners >= 3 ? corners - 2 : 0;
      if (n_tri > kMaxGltfSceneTriangles - triangles_)
        refuse_gltf("E0864", "the scene has more than " + std::to_string(kMaxGltfSceneTriangles) + " triangles (at " + pw + ")",
                    "simplify its meshes (gltf-transform simplify), or split the scene");
      triangles_ += n_tri;
      // The vertices in the scene's frame, then the triangles that are not degenerate there.
      const auto base = static_cast<std::uint32_t>(o.mesh.vertices.size());
      for (std::size_t v = 0; v < count; ++v) {
        const glm::dvec4 w = world * glm::dvec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0);
        for (int a = 0; a < 3; ++a)
          if (!std::isfinite(w[a]) || std::abs(w[a]) > kMaxGltfSceneCoordinate_m)
            refuse_gltf("E0862", aw + "[" + std::to_string(v) + "] lies at " + num(w[a]) + " m on axis " + "xyz"[a] +
                                     " in the scene, not within " + num(kMaxGltfSceneCoordinate_m) + " m of its origin");
        o.mesh.vertices.emplace_back(w);
        if (uv.empty()) {
          o.mesh.uvs.emplace_back(0.0);
          continue;
        }
        const glm::dvec2 t(uv[2 * v], uv[2 * v + 1]);
        // The bound a scene program keeps its UVs within (shapes/scene_io.hpp).
        if (!(std::abs(t.x) <= 1e12 && std::abs(t.y) <= 1e12))
          refuse_gltf("E0862", pw + ".attributes.TEXCOORD_0[" + std::to_string(v) + "] is not finite or beyond 1e12");
        o.mesh.uvs.push_back(t);
      }
      any_uvs = any_uvs || !uv.empty();
      read += n_tri;
      for (std::size_t k = 0; k < n_tri; ++k) {
        std::uint32_t a, b, c;
        if (mode == 4) {
          a = idx[3 * k], b = idx[3 * k + 1], c = idx[3 * k + 2];
        } else if (mode == 5) {  // strip: every other triangle reversed, so all face one way
          a = idx[k], b = idx[k + 1 + k % 2], c = idx[k + 2 - k % 2];
        } else {  // fan
          a = idx[k + 1], b = idx[k + 2], c = idx[0];
        }
        if (mirrored) std::swap(b, c);
        shapes::Triangle tri{base + a, base + b, base + c};
        if (degenerate(o.mesh.vertices[tri[0]], o.mesh.vertices[tri[1]], o.mesh.vertices[tri[2]])) {
          ++dropped;
          continue;
        }
        o.mesh.triangles.push_back(tri);
        o.mesh.materials.push_back(surface(o, surface_of, surface_material, material, mi, n));
      }
    }
    if (dropped > 0)
      diags_.warning("W0861", at_,
                     "object \"" + o.name + "\" (" + nw + "): " + std::to_string(dropped) + " of its " + std::to_string(read) +
                         " triangles are degenerate (no area, or an angle too thin to give a normal), dropped" +
                         (o.mesh.triangles.empty() ? "; the object is left out" : ""),
                     "remove degenerate triangles (gltf-transform weld, or the modeller's merge by distance)");
    if (o.mesh.triangles.empty()) return;
    if (!any_uvs) o.mesh.uvs.clear();
    // An object of several surfaces names each by its glTF material, as the asset's tools show it.
    if (o.surfaces.size() > 1)
      for (std::size_t s = 0; s < o.surfaces.size(); ++s) o.surfaces[s].side = material_name(surface_material[s]);
    if (objects_.size() >= kMaxGltfSceneObjects)
      refuse_gltf("E0864", "the scene places more than " + std::to_string(kMaxGltfSceneObjects) + " objects (meshes at nodes)",
                  "join meshes that share materials (gltf-transform join), or split the scene");
    objects_.push_back(std::move(o));
  }

  // The object's surface for glTF material `material`, bound when its first triangle is kept.
  std::uint16_t surface(ObjectSource& o, std::map<long long, std::uint16_t>& surface_of,
                        std::vector<std::optional<std::size_t>>& surface_material, std::optional<std::size_t> material,
                        std::size_t mesh, std::size_t node) {
    const long long key = material ? static_cast<long long>(*material) : -1;
    if (auto it = surface_of.find(key); it != surface_of.end()) return it->second;
    if (surfaces_ >= kMaxGltfSceneSurfaces)
      refuse_gltf("E0864", "the scene has more than " + std::to_string(kMaxGltfSceneSurfaces) + " surfaces (glTF materials on objects)",
                  "use fewer materials, or split the scene");
    ++surfaces_;
    o.surfaces.push_back(binder_.surface(material, mesh, node));
    surface_material.push_back(material);
    const auto s = static_cast<std::uint16_t>(o.surfaces.size() - 1);
    surface_of.emplace(key, s);
    return s;
  }

  std::string material_name(std::optional<std::size_t> material) const {
    if (!material) return "no material";
    const json& m = doc_.root()["materials"][*material];
    if (const json* name = gltf_optional_member(m, "name"); name && name->is_string() && !name->get<std::string>().empty())
      return name->get<std::string>().substr(0, 200);
    return "material " + std::to_string(*material);
  }

  static std::string name_of(const json& node, const json& mesh, std::size_t n) {
    for (const json* j : {&node, &mesh})
      if (const json* name = gltf_optional_member(*j, "name"); name && name->is_string() && !name->get<std::string>().empty())
        return name->get<std::string>().substr(0, 200);
    return "node " + std::to_string(n);
  }

  void report() {
    std::string skipped;
    for (const auto& [mode, count] : skipped_)
      skipped += (skipped.empty() ? "" : ", ") + std::to_string(count) + " of " + mode_name(mode);
    if (!skipped.empty())
      diags_.warning("W0860", at_, "primitives that are not triangles were skipped: " + skipped + " (no surface to touch)",
                     "points and lines have no area; give the objects to be felt triangle meshes");
    if (!not_read_.empty()) {
      std::string list;
      for (const auto& n : not_read_) list += (list.empty() ? "" : "; ") + n;
      diags_.warning("W0862", at_, "parts of the asset are not read: " + list,
                     "apply the pose, morphs or instances in the modeller before exporting, if the scene is to be felt with them");
    }
  }

  const GltfDocument& doc_;
  compiler::Diagnostics& diags_;
  SourceLocation at_;
  gltf_read::Binder binder_;
  std::vector<ObjectSource> objects_;
  std::string scene_name_;
  std::size_t triangles_ = 0, vertices_ = 0, surfaces_ = 0;
  std::map<int, std::size_t> skipped_;  // primitives of points and lines, by mode
  std::set<std::string> not_read_;
};

}  // namespace

std::optional<SceneSource> read_gltf_scene_bytes(const std::string& bytes, const std::string& shown_name,
                                                 const std::optional<fs::path>& folder, compiler::Diagnostics& diags) {
  auto file = std::make_shared<const compiler::SourceFile>(shown_name, "");
  const SourceLocation at{file, 0, 0, 1};
  try {
    const GltfDocument doc = GltfDocument::parse(bytes, shown_name, folder);
    Walker walker(doc, diags, at, folder);
    SceneSource s;
    s.objects = walker.walk();
    s.file = file;
    s.name = walker.scene_name().empty() ? fs::path(shown_name).stem().string() : walker.scene_name().substr(0, 200);
    s.name_location = at;
    s.base_dir = folder.value_or(fs::path());
    s.from_gltf = true;
    return s;
  } catch (const compiler::GltfRefusal& e) {
    diags.error(schema::Code::of(e.code), at, e.message, e.suggestion);
  } catch (const json::exception& e) {
    // Every access above is checked first; this is a defect's safety net, still the input's error.
    diags.error("E0712", at, "'" + shown_name + "' is not a glTF asset Sandpaper reads: " + e.what());
  }
  return std::nullopt;
}

std::optional<SceneSource> read_gltf_scene(const fs::path& path, compiler::Diagnostics& diags) {
  std::string bytes;
  try {
    bytes = schema::read_input_file(path, compiler::kMaxGltfBytes);
  } catch (const schema::InputFileError& e) {
    diags.error("E0710", SourceLocation{std::make_shared<const compiler::SourceFile>(path.string(), ""), 0, 0, 1},
                "cannot read glTF file '" + path.string() + "': " + e.reason, "check the path");
    return std::nullopt;
  }
  return read_gltf_scene_bytes(bytes, path.string(), path.has_parent_path() ? path.parent_path() : fs::path("."), diags);
}

SceneResult compile_gltf_scene(const compiler::Compiler& compiler, const fs::path& path) {
  compiler::Diagnostics diags;
  auto source = read_gltf_scene(path, diags);
  if (!source) {
    SceneResult r;
    r.diagnostics = std::move(diags);
    return r;
  }
  return compile_scene_source(compiler, *source, std::move(diags));
}

}  // namespace sandpaper::scenes
