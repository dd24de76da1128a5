// glTF 2.0 scenes into SceneSource (scenes/gltf_scene.hpp; docs/GLTF.md, "Scenes (3-D)"): small
// assets built here, their buffers as base64 data URIs, read back and checked against positions
// computed by hand, the materials they bind compiled, and each refusal's code.
#include <gtest/gtest.h>

#if SANDPAPER_SCENES_GLTF

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <zlib.h>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/gltf_export.hpp"
#include "sandpaper/scenes/gltf_scene.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"
#include "sandpaper/shapes/mesh.hpp"

namespace {

using namespace sandpaper;
using nlohmann::json;
namespace fs = std::filesystem;

const compiler::Compiler& C() {
  static const compiler::Compiler c([] {
    compiler::CompileOptions o;
    o.library_dir = std::string(SANDPAPER_SOURCE_DIR) + "/library";
    o.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
    return o;
  }());
  return c;
}

std::string base64(const std::string& bytes) {
  static constexpr char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  auto at = [&](std::size_t j) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[j])); };
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (at(i) << 16) | (at(i + 1) << 8) | at(i + 2);
    for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    const std::uint32_t v = (at(i) << 16) | (i + 1 < bytes.size() ? at(i + 1) << 8 : 0);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

template <class T>
std::string bytes_of(const std::vector<T>& v) {
  std::string s(v.size() * sizeof(T), '\0');
  std::memcpy(s.data(), v.data(), s.size());  // little-endian hosts, as glTF stores them
  return s;
}

// An 8-bit greyscale PNG, as any tool writes a texture of values.
std::string png8(int w, int h, const std::vector<unsigned char>& grey) {
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw += '\0';
    raw.append(reinterpret_cast<const char*>(grey.data()) + static_cast<std::ptrdiff_t>(y) * w, static_cast<std::size_t>(w));
  }
  uLongf zlen = compressBound(static_cast<uLong>(raw.size()));
  std::string z(zlen, '\0');
  compress(reinterpret_cast<Bytef*>(z.data()), &zlen, reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()));
  z.resize(zlen);
  auto be32 = [](std::uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
  auto chunk = [&](const std::string& type, const std::string& data) {
    const std::string td = type + data;
    return be32(static_cast<std::uint32_t>(data.size())) + td +
           be32(static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(td.data()), static_cast<uInt>(td.size()))));
  };
  const std::string ihdr = be32(static_cast<std::uint32_t>(w)) + be32(static_cast<std::uint32_t>(h)) + std::string{8, 0, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", z) + chunk("IEND", "");
}

// A glTF asset under construction: one buffer, views and accessors appended to it.
struct Asset {
  json j = {{"asset", {{"version", "2.0"}, {"generator", "sandpaper tests"}}}};
  std::string bin;

  int view(const std::string& bytes) {
    while (bin.size() % 4) bin += '\0';
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
    bin += bytes;
    return static_cast<int>(j["bufferViews"].size() - 1);
  }
  int accessor(int view_index, int component_type, std::size_t count, const char* type) {
    j["accessors"].push_back({{"bufferView", view_index}, {"componentType", component_type}, {"count", count}, {"type", type}});
    return static_cast<int>(j["accessors"].size() - 1);
  }
  int positions(const std::vector<glm::dvec3>& p) {
    std::vector<float> f;
    for (const auto& v : p) f.insert(f.end(), {float(v.x), float(v.y), float(v.z)});
    return accessor(view(bytes_of(f)), 5126, p.size(), "VEC3");
  }
  int uvs(const std::vector<glm::dvec2>& t) {
    std::vector<float> f;
    for (const auto& v : t) f.insert(f.end(), {float(v.x), float(v.y)});
    return accessor(view(bytes_of(f)), 5126, t.size(), "VEC2");
  }
  int indices(const std::vector<std::uint32_t>& i, int component_type = 5125) {
    std::string b;
    if (component_type == 5121) b = bytes_of(std::vector<std::uint8_t>(i.begin(), i.end()));
    if (component_type == 5123) b = bytes_of(std::vector<std::uint16_t>(i.begin(), i.end()));
    if (component_type == 5125) b = bytes_of(i);
    return accessor(view(b), component_type, i.size(), "SCALAR");
  }
  int mesh(json primitives, const std::string& name = "") {
    json m = {{"primitives", std::move(primitives)}};
    if (!name.empty()) m["name"] = name;
    j["meshes"].push_back(m);
    return static_cast<int>(j["meshes"].size() - 1);
  }
  int node(json n) {
    j["nodes"].push_back(std::move(n));
    return static_cast<int>(j["nodes"].size() - 1);
  }
  int material(json m) {
    j["materials"].push_back(std::move(m));
    return static_cast<int>(j["materials"].size() - 1);
  }
  // A texture of one grey value per texel, as an 8-bit PNG in a buffer view.
  int value_texture(int w, int h, const std::vector<unsigned char>& grey) {
    j["images"].push_back({{"bufferView", view(png8(w, h, grey))}, {"mimeType", "image/png"}});
    j["textures"].push_back({{"source", j["images"].size() - 1}});
    return static_cast<int>(j["textures"].size() - 1);
  }
  json done(std::vector<int> roots) {
    json out = j;
    out["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    out["scene"] = 0;
    out["scenes"] = json::array({{{"name", "test scene"}, {"nodes", roots}}});
    return out;
  }
};

// One triangle in the xy plane, counter-clockwise seen from +z: (0,0,0), (1,0,0), (0,1,0).
json triangle_primitive(Asset& a) {
  const int p = a.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  return json::array({{{"attributes", {{"POSITION", p}}}}});
}

struct Read {
  std::optional<scenes::SceneSource> scene;
  compiler::Diagnostics diags;
};

Read read(const json& asset, const std::optional<fs::path>& folder = std::nullopt) {
  Read r;
  r.scene = scenes::read_gltf_scene_bytes(asset.dump(), "t.gltf", folder, r.diags);
  return r;
}

std::vector<std::string> codes(const compiler::Diagnostics& d, compiler::Severity s) {
  std::vector<std::string> out;
  for (const auto& x : d.all())
    if (x.severity == s) out.push_back(x.code);
  return out;
}

std::string only_error(const Read& r) {
  EXPECT_FALSE(r.scene.has_value());
  const auto e = codes(r.diags, compiler::Severity::Error);
  EXPECT_EQ(e.size(), 1u) << compiler::format_diagnostics(r.diags);
  return e.empty() ? "" : e.front();
}

bool has_warning(const compiler::Diagnostics& d, const std::string& code) {
  const auto w = codes(d, compiler::Severity::Warning);
  return std::find(w.begin(), w.end(), code) != w.end();
}

void expect_near(const glm::dvec3& got, const glm::dvec3& want, double tol = 1e-6) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

glm::dvec3 normal(const shapes::MeshData& m, std::size_t t) {
  const auto& tri = m.triangles[t];
  return glm::normalize(glm::cross(m.vertices[tri[1]] - m.vertices[tri[0]], m.vertices[tri[2]] - m.vertices[tri[0]]));
}

TEST(GltfScene, ANodesTranslationRotationAndScalePlaceTheTriangleWhereComputedByHand) {
  Asset a;
  const int m = a.mesh(triangle_primitive(a), "tri");
  // Scale 2, then 90 degrees about +y (x -> -z, z -> x), then move by (1, 2, 3).
  const double h = std::sqrt(0.5);
  const int n = a.node({{"name", "placed"}, {"mesh", m}, {"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}});
  const auto r = read(a.done({n}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  EXPECT_EQ(r.scene->name, "test scene");
  ASSERT_EQ(r.scene->objects.size(), 1u);
  const auto& o = r.scene->objects[0];
  EXPECT_EQ(o.name, "placed");
  EXPECT_EQ(o.shape, "mesh");
  EXPECT_FALSE(o.natural_uv_size_m.has_value());
  ASSERT_EQ(o.mesh.triangles.size(), 1u);
  const auto& v = o.mesh.vertices;
  expect_near(v[o.mesh.triangles[0][0]], {1, 2, 3});   // the origin only moves
  expect_near(v[o.mesh.triangles[0][1]], {1, 2, 1});   // (1,0,0) -> (2,0,0) -> (0,0,-2) -> (1,2,1)
  expect_near(v[o.mesh.triangles[0][2]], {1, 4, 3});   // (0,1,0) -> (0,2,0) -> (0,2,0) -> (1,4,3)
  expect_near(normal(o.mesh, 0), {1, 0, 0});           // +z turned to +x
  EXPECT_TRUE(o.mesh.uvs.empty());
}

TEST(GltfScene, AChildsTransformComposesWithItsParentsAndAMatrixIsReadColumnMajor) {
  Asset a;
  const int m = a.mesh(triangle_primitive(a));
  const int child = a.node({{"mesh", m}, {"translation", {1, 0, 0}}});
  const int parent = a.node({{"name", "parent"}, {"children", {child}}, {"translation", {0, 1, 0}}, {"scale", {2, 2, 2}}});
  // A matrix moving by (0, 0, -5) and scaling x by 3, column-major as glTF writes it.
  const int matrix = a.node({{"name", "by matrix"}, {"mesh", m}, {"matrix", {3, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1}}});
  const auto r = read(a.done({parent, matrix}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  ASSERT_EQ(r.scene->objects.size(), 2u);
  const auto& c = r.scene->objects[0];
  EXPECT_EQ(c.name, "node 0");  // neither the node nor its mesh has a name
  // (1,0,0) -> child (2,0,0) -> parent scale (4,0,0) -> parent move (4,1,0).
  expect_near(c.mesh.vertices[1], {4, 1, 0});
  expect_near(c.mesh.vertices[2], {2, 3, 0});
  const auto& mm = r.scene->objects[1];
  EXPECT_EQ(mm.name, "by matrix");
  expect_near(mm.mesh.vertices[1], {3, 0, -5});
  expect_near(mm.mesh.vertices[2], {0, 1, -5});
}

TEST(GltfScene, AMirroredNodeKeepsItsFacesWoundOutward) {
  // A tetrahedron wound counter-clockwise from outside, then mirrored in x (and, a second instance,
  // in all three axes, which mirrors too): every face's normal still points away from its centre.
  Asset a;
  const std::vector<glm::dvec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int pos = a.positions(p);
  const int idx = a.indices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, 5123);
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}));
  const int plain = a.node({{"mesh", m}});
  const int mirrored = a.node({{"mesh", m}, {"scale", {-1, 1, 1}}, {"translation", {5, 0, 0}}});
  const int inverted = a.node({{"mesh", m}, {"scale", {-2, -2, -2}}});
  const auto r = read(a.done({plain, mirrored, inverted}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  ASSERT_EQ(r.scene->objects.size(), 3u);
  for (const auto& o : r.scene->objects) {
    glm::dvec3 centre(0.0);
    for (const auto& v : o.mesh.vertices) centre += v / 4.0;
    ASSERT_EQ(o.mesh.triangles.size(), 4u);
    for (std::size_t t = 0; t < 4; ++t) {
      const glm::dvec3 face = (o.mesh.vertices[o.mesh.triangles[t][0]] + o.mesh.vertices[o.mesh.triangles[t][1]] +
                               o.mesh.vertices[o.mesh.triangles[t][2]]) / 3.0;
      EXPECT_GT(glm::dot(normal(o.mesh, t), face - centre), 0) << o.name << " face " << t;
    }
  }
  EXPECT_NEAR(r.scene->objects[1].mesh.vertices[1].x, 4, 1e-12);  // (1,0,0) mirrored, then moved by 5
}

TEST(GltfScene, IndicesOfEveryTypeAndNoneGiveTheSameTriangles) {
  // A quad of two triangles with UVs, indexed by u8, u16, u32, and unindexed (six vertices).
  Asset a;
  const std::vector<glm::dvec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<glm::dvec2> uv{{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  const int pos = a.positions(quad), tex = a.uvs(uv);
  const std::vector<std::uint32_t> corners{0, 1, 2, 0, 2, 3};
  std::vector<int> roots;
  for (int type : {5121, 5123, 5125}) {
    const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", a.indices(corners, type)}}}));
    roots.push_back(a.node({{"mesh", m}}));
  }
  std::vector<glm::dvec3> flat;
  std::vector<glm::dvec2> flat_uv;
  for (auto c : corners) flat.push_back(quad[c]), flat_uv.push_back(uv[c]);
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", a.positions(flat)}, {"TEXCOORD_0", a.uvs(flat_uv)}}}}}));
  roots.push_back(a.node({{"mesh", m}}));
  // A strip and a fan of the same quad (modes 5 and 6).
  const int strip = a.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", a.indices({1, 2, 0, 3}, 5123)}, {"mode", 5}}}));
  roots.push_back(a.node({{"mesh", strip}}));
  const int fan = a.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"mode", 6}}}));
  roots.push_back(a.node({{"mesh", fan}}));
  const auto r = read(a.done(roots));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  ASSERT_EQ(r.scene->objects.size(), 6u);
  for (const auto& o : r.scene->objects) {
    ASSERT_EQ(o.mesh.triangles.size(), 2u) << o.name;
    ASSERT_EQ(o.mesh.uvs.size(), o.mesh.vertices.size());
    double area = 0;
    for (std::size_t t = 0; t < 2; ++t) {
      EXPECT_NEAR(normal(o.mesh, t).z, 1, 1e-12) << o.name;  // both face +z
      const auto& tri = o.mesh.triangles[t];
      area += glm::length(glm::cross(o.mesh.vertices[tri[1]] - o.mesh.vertices[tri[0]], o.mesh.vertices[tri[2]] - o.mesh.vertices[tri[0]])) / 2;
      for (auto v : tri) {  // each corner keeps its own UV: u = x, v = 1 - y
        EXPECT_NEAR(o.mesh.uvs[v].x, o.mesh.vertices[v].x, 1e-7);
        EXPECT_NEAR(o.mesh.uvs[v].y, 1 - o.mesh.vertices[v].y, 1e-7);
      }
    }
    EXPECT_NEAR(area, 1, 1e-12) << o.name;
    EXPECT_NO_THROW(shapes::Mesh::build_nonrt(o.mesh));
  }
}

TEST(GltfScene, ASparseAccessorReplacesTheElementsItNames) {
  // Positions of zeros (no buffer view) with three replaced by a sparse substitution.
  Asset a;
  const int idx = a.view(bytes_of(std::vector<std::uint16_t>{1, 2, 4}));
  const int val = a.view(bytes_of(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
  a.j["accessors"].push_back({{"componentType", 5126}, {"count", 5}, {"type", "VEC3"},
                              {"sparse", {{"count", 3}, {"indices", {{"bufferView", idx}, {"componentType", 5123}}}, {"values", {{"bufferView", val}}}}}});
  const int pos = static_cast<int>(a.j["accessors"].size() - 1);
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", a.indices({0, 1, 2, 3, 2, 4}, 5121)}}}));
  const auto r = read(a.done({a.node({{"mesh", m}})}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  const auto& v = r.scene->objects[0].mesh.vertices;
  expect_near(v[1], {1, 0, 0});
  expect_near(v[2], {0, 1, 0});
  expect_near(v[3], {0, 0, 0});
  expect_near(v[4], {0, 0, 1});
}

TEST(GltfScene, DegenerateTrianglesAreDroppedWithACountAndPointsAreSkipped) {
  Asset a;
  // A good triangle, one with two equal corners, one whose corners lie on a line, one of a sliver
  // whose smallest angle's sine is 1e-13 (below the mesh's 1e-12).
  const int pos = a.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 5}, {1000, 0, 5}, {0, 1e-10, 5}});
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", a.indices({0, 1, 2, 0, 1, 1, 0, 1, 3, 4, 5, 6}, 5121)}},
                                    {{"attributes", {{"POSITION", pos}}}, {"mode", 0}}}));
  const auto r = read(a.done({a.node({{"name", "slivers"}, {"mesh", m}})}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  ASSERT_EQ(r.scene->objects[0].mesh.triangles.size(), 1u);
  EXPECT_TRUE(has_warning(r.diags, "W0861"));
  EXPECT_TRUE(has_warning(r.diags, "W0860"));
  EXPECT_NE(compiler::format_diagnostics(r.diags).find("3 of its 4 triangles"), std::string::npos) << compiler::format_diagnostics(r.diags);
  EXPECT_NO_THROW(shapes::Mesh::build_nonrt(r.scene->objects[0].mesh));
}

TEST(GltfScene, ExtrasSandpaperMaterialBindsTheLibraryEntry) {
  Asset a;
  const int pos = a.positions({{-0.05, 0, 0.05}, {0.05, 0, 0.05}, {0.05, 0, -0.05}, {-0.05, 0, -0.05}});
  const int tex = a.uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  const int fabric = a.material({{"name", "fabric"}, {"extras", {{"sandpaper", {{"material", "corduroy"}}}}}});
  const int plain = a.material({{"name", "plain"}});
  const int idx = a.indices({0, 1, 2, 0, 2, 3}, 5123);
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", idx}, {"material", fabric}},
                                    {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", idx}, {"material", plain}},
                                    {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", idx}, {"material", fabric}}}));
  const auto r = read(a.done({a.node({{"name", "cushion"}, {"mesh", m}})}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  // Primitives of one glTF material share a surface, named by the material.
  const auto& o = r.scene->objects[0];
  ASSERT_EQ(o.surfaces.size(), 2u);
  EXPECT_EQ(o.surfaces[0].material, "corduroy");
  EXPECT_EQ(o.surfaces[0].side, "fabric");
  EXPECT_EQ(o.surfaces[1].material, "");
  EXPECT_EQ(o.surfaces[1].side, "plain");
  ASSERT_EQ(o.mesh.materials.size(), 6u);
  EXPECT_EQ(o.mesh.materials, (std::vector<std::uint16_t>{0, 0, 1, 1, 0, 0}));

  const auto result = scenes::compile_scene_source(C(), *r.scene);
  ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
  const auto& program = *result.program;
  const auto corduroy = C().compile_text("corduroy");
  ASSERT_TRUE(corduroy.ok());
  ASSERT_EQ(program.surfaces.size(), 2u);
  ASSERT_GE(program.surfaces[0].program, 0);
  EXPECT_EQ(program.programs[static_cast<std::size_t>(program.surfaces[0].program)].max_lateral_force_N,
            corduroy.program->max_lateral_force_N);
  // The texture keeps its own scale: metres per UV unit are the patch's size, as the 2-D export lays it.
  EXPECT_EQ(program.surfaces[0].uv_size_m, glm::dvec2(corduroy.program->size_m[0], corduroy.program->size_m[1]));
  EXPECT_EQ(program.surfaces[1].program, -1);  // contact only
  EXPECT_EQ(program.surfaces[1].contact.stiffness_N_per_m, scenes::kDefaultStiffness_N_per_m);
  EXPECT_NO_THROW(shapes::Mesh::build_nonrt(program.mesh));
}

// A scene file's `texture relief 0.5 mm only`, in a glTF asset's extras: the compiled surface
// carries the carve and drops the lateral texture, and bad values are refused.
TEST(GltfScene, ExtrasSandpaperReliefCarvesTheTexture) {
  auto asset = [](const json& extras) {
    Asset a;
    const int pos = a.positions({{-0.05, 0, 0.05}, {0.05, 0, 0.05}, {0.05, 0, -0.05}, {-0.05, 0, -0.05}});
    const int tex = a.uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    const int fabric = a.material({{"name", "fabric"}, {"extras", {{"sandpaper", extras}}}});
    const int idx = a.indices({0, 1, 2, 0, 2, 3}, 5123);
    const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", idx}, {"material", fabric}}}));
    return a.done({a.node({{"mesh", m}})});
  };
  {
    const auto r = read(asset({{"material", "corduroy"}, {"relief_depth_m", 0.0005}, {"relief_only", true}}));
    ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
    const auto result = scenes::compile_scene_source(C(), *r.scene);
    ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
    ASSERT_EQ(result.program->surfaces.size(), 1u);
    EXPECT_EQ(result.program->surfaces[0].relief_depth_m, 0.0005);
    EXPECT_FALSE(result.program->surfaces[0].lateral_texture);
  }
  {
    const auto r = read(asset({{"material", "corduroy"}, {"relief_depth_m", 0.001}}));
    ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
    const auto result = scenes::compile_scene_source(C(), *r.scene);
    ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
    EXPECT_EQ(result.program->surfaces[0].relief_depth_m, 0.001);
    EXPECT_TRUE(result.program->surfaces[0].lateral_texture);
  }
  // Deeper than 10 mm, not a number, `only` not a boolean, `only` without a depth.
  EXPECT_EQ(only_error(read(asset({{"material", "corduroy"}, {"relief_depth_m", 0.02}}))), "E0865");
  EXPECT_EQ(only_error(read(asset({{"material", "corduroy"}, {"relief_depth_m", "0.5 mm"}}))), "E0865");
  EXPECT_EQ(only_error(read(asset({{"material", "corduroy"}, {"relief_depth_m", 0.0005}, {"relief_only", "yes"}}))), "E0865");
  EXPECT_EQ(only_error(read(asset({{"material", "corduroy"}, {"relief_only", true}}))), "E0865");
}

TEST(GltfScene, TheMaterialsExtrasWinOverTheNodesAndTheNodesOverTheMeshs) {
  Asset a;
  const int pos = a.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int bare = a.material({{"name", "bare"}});
  const int named = a.material({{"extras", {{"sandpaper", {{"material", "velvet"}, {"static_friction", 0.4}}}}}});
  json mesh_extras = {{"sandpaper", {{"material", "gravel"}, {"stiffness_N_per_m", 900}, {"static_friction", 0.9}}}};
  const int m1 = a.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"material", bare}}}));
  a.j["meshes"][m1]["extras"] = mesh_extras;
  const int m2 = a.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"material", named}}}));
  a.j["meshes"][m2]["extras"] = mesh_extras;
  const int n1 = a.node({{"mesh", m1}});
  const int n2 = a.node({{"mesh", m1}, {"extras", {{"sandpaper", {{"material", "corduroy"}, {"damping_Ns_per_m", 2}}}}}});
  const int n3 = a.node({{"mesh", m2}, {"extras", {{"sandpaper", {{"material", "corduroy"}}}}}});
  const auto r = read(a.done({n1, n2, n3}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  const auto& s1 = r.scene->objects[0].surfaces.at(0);
  EXPECT_EQ(s1.material, "gravel");
  EXPECT_EQ(s1.stiffness_N_per_m, 900);
  EXPECT_EQ(s1.static_friction, 0.9);
  EXPECT_EQ(s1.kinetic_friction, 0.9);  // kinetic absent: the static coefficient, as a scene file's `friction S`
  const auto& s2 = r.scene->objects[1].surfaces.at(0);
  EXPECT_EQ(s2.material, "corduroy");
  EXPECT_EQ(s2.damping_Ns_per_m, 2);
  EXPECT_EQ(s2.stiffness_N_per_m, 900);  // each key found where it is most particular
  const auto& s3 = r.scene->objects[2].surfaces.at(0);
  EXPECT_EQ(s3.material, "velvet");
  EXPECT_EQ(s3.static_friction, 0.4);
}

// The issue's check: "A glTF scene written by another tool with MPEG_haptic_material (stiffness and
// friction textures) plays with those values."
TEST(GltfScene, AnotherToolsMpegHapticMaterialGivesItsStiffnessAndFriction) {
  Asset a;
  const int pos = a.positions({{-0.1, 0, 0.1}, {0.1, 0, 0.1}, {0.1, 0, -0.1}, {-0.1, 0, -0.1}});
  const int tex = a.uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  const int stiff = a.value_texture(4, 4, std::vector<unsigned char>(16, 102));  // 0.4 of full scale
  const int slip = a.value_texture(2, 2, std::vector<unsigned char>(4, 128));    // mu = 128 / 255
  const int vib = a.value_texture(2, 1, {0, 255});
  a.j["extensionsUsed"] = {"MPEG_haptic_material"};
  a.j["extensions"]["MPEG_haptic_material"]["materials"] = json::array({{
      {"name", "rubber"},
      {"stiffness", {{{"texture", {{"index", stiff}}}, {"type", "High_Resolution"}}}},
      {"friction", {{{"texture", {{"index", slip}}}, {"type", "Low_Resolution"}}}},
      {"vibrotactileTexture", {{{"texture", {{"index", vib}}}, {"type", "High_Resolution"}}}},
  }});
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", a.indices({0, 1, 2, 0, 2, 3}, 5123)}}}),
                       "pad");
  a.j["meshes"][m]["extensions"] = {{"MPEG_haptic_material", {{"hapticMaterialIndex", 0}}}};
  const auto r = read(a.done({a.node({{"mesh", m}})}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  EXPECT_EQ(r.scene->objects[0].name, "pad");  // the node has no name: its mesh's
  const auto& s = r.scene->objects[0].surfaces.at(0);
  EXPECT_NEAR(*s.stiffness_N_per_m, 102.0 / 255 * scenes::kMpegStiffnessFullScale_N_per_m, 1e-3);
  EXPECT_NEAR(*s.static_friction, 128.0 / 255, 1e-6);
  EXPECT_NEAR(*s.kinetic_friction, 128.0 / 255, 1e-6);
  EXPECT_TRUE(has_warning(r.diags, "W0864"));  // the stiffness's unit is Sandpaper's reading
  EXPECT_TRUE(has_warning(r.diags, "W0863"));  // its vibrotactile texture is not used

  const auto result = scenes::compile_scene_source(C(), *r.scene, r.diags);
  ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
  const auto& contact = result.program->surfaces.at(0).contact;
  EXPECT_NEAR(contact.stiffness_N_per_m, 800, 1e-3);
  EXPECT_NEAR(contact.static_friction, 128.0 / 255, 1e-6);
  EXPECT_NEAR(contact.kinetic_friction, 128.0 / 255, 1e-6);
  EXPECT_EQ(result.origins.at(0).stiffness, "scene");
  EXPECT_EQ(result.origins.at(0).friction, "scene");
  EXPECT_EQ(result.program->surfaces.at(0).program, -1);  // untextured
}

TEST(GltfScene, AStiffnessThatVariesOverItsTextureIsItsMeanWithAWarning) {
  Asset a;
  const int stiff = a.value_texture(2, 1, {51, 153});  // 0.2 and 0.6: the mean 0.4
  a.j["extensions"]["MPEG_haptic_material"]["materials"] =
      json::array({{{"stiffness", {{{"texture", {{"index", stiff}}}, {"type", "High_Resolution"}}}}}});
  const int mat = a.material({{"name", "marked"}, {"extras", {{"sandpaper", {{"hapticMaterialIndex", 0}}}}}});
  const int m = a.mesh(json::array({{{"attributes", {{"POSITION", a.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}}}, {"material", mat}}}));
  const auto r = read(a.done({a.node({{"mesh", m}})}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  EXPECT_NEAR(*r.scene->objects[0].surfaces.at(0).stiffness_N_per_m, 0.4 * scenes::kMpegStiffnessFullScale_N_per_m, 1e-3);
  EXPECT_TRUE(has_warning(r.diags, "W0863"));
}

TEST(GltfScene, SandpapersOwnExportReadAsASceneCompilesItsMaterialAgain) {
  const auto corduroy = C().compile_text("corduroy");
  ASSERT_TRUE(corduroy.ok());
  compiler::Diagnostics d;
  compiler::GltfPatch patch{&*corduroy.program, &*corduroy.material, {0, 0}, "corduroy"};
  const auto asset = compiler::export_gltf({patch}, std::nullopt, "corduroy", d);
  ASSERT_TRUE(asset) << compiler::format_diagnostics(d);
  const auto r = read(*asset);
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  ASSERT_EQ(r.scene->objects.size(), 1u);
  EXPECT_EQ(r.scene->objects[0].surfaces.at(0).material, "corduroy");
  const auto result = scenes::compile_scene_source(C(), *r.scene, r.diags);
  ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
  ASSERT_GE(result.program->surfaces.at(0).program, 0);
  EXPECT_EQ(result.program->programs.at(0).max_lateral_force_N, corduroy.program->max_lateral_force_N);
  // The exported plane spans the patch with UVs 0..1: one UV unit is the patch's size.
  EXPECT_EQ(result.program->surfaces.at(0).uv_size_m, glm::dvec2(corduroy.program->size_m[0], corduroy.program->size_m[1]));
}

TEST(GltfScene, FilesBesideTheAssetAreReadAndAGlbToo) {
  const fs::path dir = fs::temp_directory_path() / ("sandpaper-gltf-scene-" + std::to_string(std::random_device{}()));
  fs::create_directories(dir);
  Asset a;
  const int m = a.mesh(triangle_primitive(a), "tri");
  json asset = a.done({a.node({{"mesh", m}, {"extras", {{"sandpaper", {{"material", "mine.hmat"}}}}}})});
  asset["buffers"][0]["uri"] = "geometry%20data.bin";  // percent-encoded, as glTF writes URIs
  std::ofstream(dir / "geometry data.bin", std::ios::binary) << a.bin;
  std::ofstream(dir / "mine.hmat", std::ios::binary) << "like corduroy\n";
  std::ofstream(dir / "scene.gltf", std::ios::binary) << asset.dump();
  const auto result = scenes::compile_gltf_scene(C(), dir / "scene.gltf");
  ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
  EXPECT_EQ(result.program->name, "test scene");
  EXPECT_GE(result.program->surfaces.at(0).program, 0);

  // The same as a .glb: the JSON chunk, then the BIN chunk holding the buffer.
  json glb_json = asset;
  glb_json["buffers"][0].erase("uri");
  std::string js = glb_json.dump();
  while (js.size() % 4) js += ' ';
  std::string bin = a.bin;
  while (bin.size() % 4) bin += '\0';
  auto le32 = [](std::size_t v) { return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; };
  const std::string glb = "glTF" + le32(2) + le32(12 + 8 + js.size() + 8 + bin.size()) + le32(js.size()) + "JSON" + js +
                          le32(bin.size()) + std::string("BIN\0", 4) + bin;
  std::ofstream(dir / "scene.glb", std::ios::binary) << glb;
  compiler::Diagnostics d;
  const auto s = scenes::read_gltf_scene(dir / "scene.glb", d);
  ASSERT_TRUE(s) << compiler::format_diagnostics(d);
  expect_near(s->objects.at(0).mesh.vertices.at(1), {1, 0, 0});

  // A material file outside the asset's folder is refused, as an image there would be.
  asset["nodes"][0]["extras"]["sandpaper"]["material"] = "../elsewhere.hmat";
  std::ofstream(dir / "outside.gltf", std::ios::binary) << asset.dump();
  compiler::Diagnostics d2;
  EXPECT_FALSE(scenes::read_gltf_scene(dir / "outside.gltf", d2));
  EXPECT_EQ(codes(d2, compiler::Severity::Error), std::vector<std::string>{"E0865"});
  fs::remove_all(dir);
}

TEST(GltfScene, EachProblemHasItsCode) {
  auto base = [] {
    Asset a;
    const int m = a.mesh(triangle_primitive(a));
    a.node({{"mesh", m}});
    return a;
  };
  {  // no POSITION
    Asset a = base();
    a.j["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0861");
  }
  {  // an index past the vertices
    Asset a = base();
    a.j["meshes"][0]["primitives"][0]["indices"] = a.indices({0, 1, 3}, 5121);
    const auto r = read(a.done({0}));
    EXPECT_EQ(only_error(r), "E0863");
    EXPECT_NE(compiler::format_diagnostics(r.diags).find("indices[2] is 3"), std::string::npos) << compiler::format_diagnostics(r.diags);
  }
  {  // indices of floats
    Asset a = base();
    a.j["meshes"][0]["primitives"][0]["indices"] = a.accessor(a.view(bytes_of(std::vector<float>{0, 1, 2})), 5126, 3, "SCALAR");
    EXPECT_EQ(only_error(read(a.done({0}))), "E0863");
  }
  {  // too many triangles: refused from the count, before anything is read or allocated
    Asset a = base();
    a.j["accessors"].push_back({{"componentType", 5125}, {"count", 3 * scenes::kMaxGltfSceneTriangles + 3}, {"type", "SCALAR"}});
    a.j["meshes"][0]["primitives"][0]["indices"] = a.j["accessors"].size() - 1;
    EXPECT_EQ(only_error(read(a.done({0}))), "E0864");
  }
  {  // too many vertices
    Asset a = base();
    a.j["accessors"][0]["count"] = scenes::kMaxGltfSceneVertices + 1;
    a.j["accessors"][0].erase("bufferView");
    EXPECT_EQ(only_error(read(a.done({0}))), "E0864");
  }
  {  // POSITION of the wrong type, and past its buffer view
    Asset a = base();
    a.j["accessors"][0]["type"] = "VEC2";
    EXPECT_EQ(only_error(read(a.done({0}))), "E0862");
    Asset b = base();
    b.j["accessors"][0]["count"] = 4;
    EXPECT_EQ(only_error(read(b.done({0}))), "E0862");
  }
  {  // a node its own descendant
    Asset a = base();
    a.j["nodes"][0]["children"] = {0};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0860");
  }
  {  // a zero rotation
    Asset a = base();
    a.j["nodes"][0]["rotation"] = {0, 0, 0, 0};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0860");
  }
  {  // a bound material that is not text, a kinetic friction above static
    Asset a = base();
    a.j["nodes"][0]["extras"] = {{"sandpaper", {{"material", 7}}}};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0865");
    Asset b = base();
    b.j["nodes"][0]["extras"] = {{"sandpaper", {{"static_friction", 0.2}, {"kinetic_friction", 0.5}}}};
    EXPECT_EQ(only_error(read(b.done({0}))), "E0865");
  }
  {  // a haptic material index past the extension's materials
    Asset a = base();
    a.j["extensions"]["MPEG_haptic_material"]["materials"] = json::array({json::object()});
    a.j["meshes"][0]["extensions"] = {{"MPEG_haptic_material", {{"hapticMaterialIndex", 3}}}};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0865");
  }
  {  // a stiffness texture that is not a PNG
    Asset a = base();
    a.j["images"] = json::array({{{"bufferView", a.view("GIF89a not a png")}}});
    a.j["textures"] = json::array({{{"source", 0}}});
    a.j["extensions"]["MPEG_haptic_material"]["materials"] =
        json::array({{{"stiffness", {{{"texture", {{"index", 0}}}, {"type", "High_Resolution"}}}}}});
    a.j["meshes"][0]["extensions"] = {{"MPEG_haptic_material", {{"hapticMaterialIndex", 0}}}};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0716");
  }
  {  // Draco-compressed geometry
    Asset a = base();
    a.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    EXPECT_EQ(only_error(read(a.done({0}))), "E0866");
  }
  {  // the file's own problems: the patch importer's codes
    compiler::Diagnostics d;
    EXPECT_FALSE(scenes::read_gltf_scene_bytes("{\"asset\": ", "t.gltf", std::nullopt, d));
    EXPECT_EQ(codes(d, compiler::Severity::Error), std::vector<std::string>{"E0711"});
    Asset a = base();
    json j = a.done({0});
    j["asset"]["version"] = "1.0";
    EXPECT_EQ(only_error(read(j)), "E0712");
    Asset b = base();
    b.j["bufferViews"][0]["byteLength"] = 4096;
    EXPECT_EQ(only_error(read(b.done({0}))), "E0715");
    compiler::Diagnostics missing;
    EXPECT_FALSE(scenes::read_gltf_scene("/nonexistent/scene.gltf", missing));
    EXPECT_EQ(codes(missing, compiler::Severity::Error), std::vector<std::string>{"E0710"});
  }
}

TEST(GltfScene, TheShippedExampleCompiles) {
  const auto result = scenes::compile_gltf_scene(C(), fs::path(SANDPAPER_SOURCE_DIR) / "examples/3d/gltf-scene/scene.gltf");
  ASSERT_TRUE(result.ok()) << compiler::format_diagnostics(result.diagnostics);
  const auto& p = *result.program;
  EXPECT_EQ(p.name, "cushion on a floor");
  ASSERT_EQ(p.objects.size(), 2u);
  EXPECT_EQ(p.objects[0].name, "cushion");
  EXPECT_EQ(p.objects[0].triangle_count, 12u);
  ASSERT_EQ(p.surfaces.size(), 2u);
  EXPECT_EQ(p.surfaces[0].material, "corduroy");
  EXPECT_GE(p.surfaces[0].program, 0);
  EXPECT_EQ(p.surfaces[0].uv_size_m, glm::dvec2(0.1, 0.1));
  EXPECT_NEAR(p.surfaces[1].contact.stiffness_N_per_m, 153.0 / 255 * 2000, 1e-3);
  EXPECT_NEAR(p.surfaces[1].contact.static_friction, 89.0 / 255, 1e-6);
  EXPECT_NO_THROW(shapes::Mesh::build_nonrt(p.mesh));
  // The cushion sits on the floor, moved 20 mm toward the user.
  double lowest = 1, front = -1;
  for (std::uint32_t t = 0; t < p.objects[0].triangle_count; ++t)
    for (auto v : p.mesh.triangles[t]) lowest = std::min(lowest, p.mesh.vertices[v].y), front = std::max(front, p.mesh.vertices[v].z);
  EXPECT_NEAR(lowest, 0, 1e-7);
  EXPECT_NEAR(front, 0.06, 1e-7);
}

TEST(GltfScene, WhatIsNotReadIsSaid) {
  Asset a;
  const int m = a.mesh(triangle_primitive(a));
  a.j["meshes"][m]["primitives"][0]["targets"] = json::array({{{"POSITION", 0}}});
  a.j["animations"] = json::array({{{"channels", json::array()}, {"samplers", json::array()}}});
  a.j["extensionsRequired"] = {"KHR_materials_unlit", "EXT_unknown_thing"};
  const auto r = read(a.done({a.node({{"mesh", m}})}));
  ASSERT_TRUE(r.scene) << compiler::format_diagnostics(r.diags);
  EXPECT_TRUE(has_warning(r.diags, "W0862"));
  const std::string text = compiler::format_diagnostics(r.diags);
  for (const char* what : {"morph targets", "animations", "EXT_unknown_thing"}) EXPECT_NE(text.find(what), std::string::npos) << what;
  EXPECT_EQ(text.find("KHR_materials_unlit"), std::string::npos);
}

// A glTF asset whose scene holds no mesh compiles to an empty scene, and W0852 speaks of the asset,
// not of scene-file lines.
TEST(GltfScene, AnAssetWithNoMeshWarnsInGltfsWords) {
  json scene = json::object(), asset = json::object();
  scene["nodes"] = json::array({0});
  asset["asset"]["version"] = "2.0";
  asset["scene"] = 0;
  asset["scenes"] = json::array({scene});
  asset["nodes"] = json::array({json::object({{"name", "an empty node"}})});
  Read r = read(asset);
  ASSERT_TRUE(r.scene.has_value()) << compiler::format_diagnostics(r.diags);
  const auto result = scenes::compile_scene_source(C(), *r.scene, r.diags);
  const compiler::Diagnostic* w = nullptr;
  for (const auto& d : result.diagnostics.all())
    if (d.code == "W0852") w = &d;
  ASSERT_NE(w, nullptr) << compiler::format_diagnostics(result.diagnostics);
  EXPECT_NE(w->suggestion.find("meshes of triangles"), std::string::npos) << w->suggestion;
  EXPECT_EQ(w->suggestion.find("sphere radius"), std::string::npos) << w->suggestion;
}

}  // namespace

#endif  // SANDPAPER_SCENES_GLTF
