// The scene-program file (shapes/scene_io.hpp, docs/PATCH_FORMAT.md "Scene programs"): a scene
// written and read back is the same scene, byte for byte and force for force, and every file the
// reader refuses is refused with PatchFormatError before anything is built from it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <tuple>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <zlib.h>

#include "allocation_counter.hpp"
#include "patch_on_plane.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/scene_io.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"

namespace sandpaper::shapes {
namespace {

using Bytes = std::vector<unsigned char>;
using schema::PatchFormatError;

MeshData data_of(const Mesh& mesh) {
  MeshData d;
  d.vertices.assign(mesh.vertices().begin(), mesh.vertices().end());
  d.triangles.assign(mesh.triangles().begin(), mesh.triangles().end());
  d.uvs.assign(mesh.uvs().begin(), mesh.uvs().end());
  return d;
}

// Appends `part` to the scene's mesh as one object whose triangles are all on `surface`.
void add_object(SceneProgram& scene, const std::string& name, const std::string& shape, const MeshData& part,
                std::uint16_t surface) {
  MeshData& m = scene.mesh;
  const auto base = static_cast<std::uint32_t>(m.vertices.size());
  scene.objects.push_back({name, shape, static_cast<std::uint32_t>(m.triangles.size()),
                           static_cast<std::uint32_t>(part.triangles.size())});
  m.vertices.insert(m.vertices.end(), part.vertices.begin(), part.vertices.end());
  m.uvs.insert(m.uvs.end(), part.uvs.begin(), part.uvs.end());
  for (Triangle t : part.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  m.materials.insert(m.materials.end(), part.triangles.size(), surface);
}

constexpr double kRadius = 0.05, kTableZ = -0.08;

// A corduroy ball of 50 mm above a plain table with friction: two objects, two surfaces, one of
// them with the compiled material's texture laid round the ball at its own scale.
const SceneProgram& ball_on_table() {
  static const SceneProgram scene = [] {
    SceneProgram s;
    s.name = "ball on a table";
    s.device = "sim";
    add_object(s, "ball", "sphere", uv_sphere_data(kRadius, 32, 16), 0);
    add_object(s, "table", "plane", data_of(plane(0.15, 0.15, 4, 4, kTableZ)), 1);
    s.surfaces.push_back({"ball", "", "like corduroy", {600, 0.5, 0, 0}, 0,
                          {2 * std::numbers::pi * kRadius, std::numbers::pi * kRadius}});
    s.surfaces.push_back({"table", "", "wood", {800, 0, 0.6, 0.4}, -1, {0.1, 0.1}});
    s.surfaces[0].relief_depth_m = 0.0004;  // corduroy's ribs carved into the ball as well
    s.programs.push_back(compiled("like corduroy"));
    return s;
  }();
  return scene;
}

// Small programs built by hand (no compiler, no library): a grating and a repeating height field.
schema::PatchProgram grating_program() {
  schema::PatchProgram p;
  p.name = "seed grating";
  p.device = "sim";
  p.size_m[0] = p.size_m[1] = 0.04;
  schema::GratingTerm g;
  g.period_m = 0.004;
  g.orientation_rad = 0.5;
  g.force_N = {0.0f, 0.2f, 0.3f, 0.2f, 0.0f, -0.2f, -0.3f, -0.2f};
  p.terms.push_back(g);
  p.max_lateral_force_N = 0.3;
  return p;
}

schema::PatchProgram bumps_program() {
  schema::PatchProgram p;
  p.name = "seed bumps";
  p.device = "sim";
  p.size_m[0] = p.size_m[1] = 0.02;
  schema::HeightFieldTerm h;
  h.nx = h.ny = 4;
  h.origin_m[0] = h.origin_m[1] = -0.006;
  h.spacing_m[0] = h.spacing_m[1] = 0.004;
  h.repeat = true;
  for (std::uint32_t iy = 0; iy < 4; ++iy)
    for (std::uint32_t ix = 0; ix < 4; ++ix) {
      h.force_x_N.push_back(0.25f * static_cast<float>((ix % 2) * 2) - 0.25f);
      h.force_y_N.push_back(0.25f * static_cast<float>((iy % 2) * 2) - 0.25f);
    }
  p.terms.push_back(h);
  p.max_lateral_force_N = 0.35;
  return p;
}

// A small scene whose bytes do not depend on the library or the calibration: the fuzz seeds, and
// the file that is cut at every length.
SceneProgram small_ball_on_table() {
  SceneProgram s;
  s.name = "small ball";
  s.device = "sim";
  add_object(s, "ball", "sphere", uv_sphere_data(0.03, 6, 4), 0);
  add_object(s, "table", "plane", data_of(plane(0.05, 0.05, 1, 1, -0.04)), 1);
  s.surfaces.push_back({"ball", "", "grating period 4 mm", {500, 0.2, 0, 0}, 0, {0.19, 0.09}});
  s.surfaces.push_back({"table", "", "wood", {800, 0, 0.6, 0.4}, -1, {0.1, 0.1}});
  s.programs.push_back(grating_program());
  return s;
}

// A tetrahedron without UVs or surface indices (every triangle on surface 0), and no texture.
SceneProgram plain_tetrahedron() {
  SceneProgram s;
  s.name = "tetrahedron";
  s.device = "sim";
  s.mesh.vertices = {{0, 0, 0}, {0.02, 0, 0}, {0, 0.02, 0}, {0, 0, 0.02}};
  s.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  s.objects.push_back({"tetrahedron", "mesh", 0, 4});
  s.surfaces.push_back({"tetrahedron", "", "", {300, 0, 0, 0}, -1, {0.1, 0.1}});
  return s;
}

// A 2 x 2 tiled floor whose squares alternate between two textures, and a sphere on it sharing one.
SceneProgram checkered_floor() {
  SceneProgram s;
  s.name = "checkered floor";
  s.device = "sim";
  MeshData floor = data_of(plane(0.04, 0.04, 2, 2, 0.0));
  s.objects.push_back({"floor", "plane", 0, static_cast<std::uint32_t>(floor.triangles.size())});
  s.mesh = floor;
  for (std::size_t t = 0; t < floor.triangles.size(); ++t) s.mesh.materials.push_back(static_cast<std::uint16_t>((t / 2) % 2));
  add_object(s, "pebble", "sphere", uv_sphere_data(0.01, 4, 3, {0, 0, 0.012}), 1);
  s.surfaces.push_back({"floor", "", "grating", {900, 1.0, 0.3, 0.2}, 0, {0.08, 0.08}});
  s.surfaces.push_back({"floor", "", "bumps", {400, 0, 0, 0}, 1, {0.02, 0.03}});
  // The grating carved 0.3 mm deep and felt through that alone; the bumps carved 0.1 mm under their
  // lateral force (format version 2).
  s.surfaces[0].relief_depth_m = 0.0003;
  s.surfaces[0].lateral_texture = false;
  s.surfaces[1].relief_depth_m = 0.0001;
  s.programs.push_back(grating_program());
  s.programs.push_back(bumps_program());
  return s;
}

// The byte offsets of the payload's parts, from the scene written.
struct Layout {
  std::size_t counts, vertices, uvs, triangles, materials, surfaces;
};
Layout layout_of(const SceneProgram& s) {
  Layout l{};
  l.counts = 32 + 4 + s.name.size() + 4 + s.device.size();
  l.vertices = l.counts + 7 * 8;
  l.uvs = l.vertices + 24 * s.mesh.vertices.size();
  l.triangles = l.uvs + 16 * s.mesh.uvs.size();
  l.materials = l.triangles + 12 * s.mesh.triangles.size();
  l.surfaces = l.materials + 2 * s.mesh.materials.size();
  for (const SceneObject& o : s.objects) l.surfaces += 4 + o.name.size() + 4 + o.shape.size() + 8;
  return l;
}

// The header's size and CRC-32 made to match the payload, so a change reaches the parser.
Bytes refixed(Bytes b) {
  const std::uint64_t size = b.size() - 32;
  std::memcpy(b.data() + 16, &size, 8);
  const auto crc = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), b.data() + 32, static_cast<uInt>(size)));
  std::memcpy(b.data() + 24, &crc, 4);
  return b;
}
template <class T>
Bytes with(Bytes b, std::size_t offset, T value) {
  std::memcpy(b.data() + offset, &value, sizeof value);
  return refixed(std::move(b));
}

// deserialize_scene's refusal of `bytes`, or "" if it took them.
std::string refusal(const Bytes& bytes) {
  try {
    (void)deserialize_scene(bytes);
  } catch (const PatchFormatError& e) {
    return e.what();
  }
  return "";
}

Bytes file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void expect_same_scene(const SceneProgram& a, const SceneProgram& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.device, b.device);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.uvs, b.mesh.uvs);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.materials, b.mesh.materials);
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].name, b.objects[i].name);
    EXPECT_EQ(a.objects[i].shape, b.objects[i].shape);
    EXPECT_EQ(a.objects[i].first_triangle, b.objects[i].first_triangle);
    EXPECT_EQ(a.objects[i].triangle_count, b.objects[i].triangle_count);
  }
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (std::size_t i = 0; i < a.surfaces.size(); ++i) {
    const SceneSurface &x = a.surfaces[i], &y = b.surfaces[i];
    EXPECT_EQ(x.object, y.object);
    EXPECT_EQ(x.side, y.side);
    EXPECT_EQ(x.material, y.material);
    EXPECT_EQ(x.contact.stiffness_N_per_m, y.contact.stiffness_N_per_m);
    EXPECT_EQ(x.contact.damping_Ns_per_m, y.contact.damping_Ns_per_m);
    EXPECT_EQ(x.contact.static_friction, y.contact.static_friction);
    EXPECT_EQ(x.contact.kinetic_friction, y.contact.kinetic_friction);
    EXPECT_EQ(x.program, y.program);
    EXPECT_EQ(x.uv_size_m, y.uv_size_m);
    EXPECT_EQ(x.relief_depth_m, y.relief_depth_m);
    EXPECT_EQ(x.lateral_texture, y.lateral_texture);
  }
  ASSERT_EQ(a.programs.size(), b.programs.size());
  for (std::size_t i = 0; i < a.programs.size(); ++i) EXPECT_EQ(schema::serialize(a.programs[i]), schema::serialize(b.programs[i]));
}

TEST(SceneIo, AWrittenSceneReadsBackWithEveryFieldAndRewritesToTheSameBytes) {
  const SceneProgram& scene = ball_on_table();
  const std::filesystem::path dir = test::temp_dir("scene-io");
  const auto path = dir / "ball.sp3";
  write_scene_program_file(path, scene);
  EXPECT_TRUE(looks_like_scene_program_file(path));
  const Bytes bytes = file_bytes(path);
  EXPECT_EQ(bytes, serialize_scene(scene));
  const SceneProgram back = read_scene_program_file(path);
  expect_same_scene(scene, back);
  EXPECT_EQ(serialize_scene(back), bytes);
  // A patch file is not a scene, nor a folder, nor a missing file.
  schema::write_patch_file(dir / "corduroy.patch", scene.programs[0]);
  EXPECT_FALSE(looks_like_scene_program_file(dir / "corduroy.patch"));
  EXPECT_FALSE(looks_like_scene_program_file(dir));
  EXPECT_FALSE(looks_like_scene_program_file(dir / "none.sp3"));
  EXPECT_THROW(read_scene_program_file(dir / "corduroy.patch"), PatchFormatError);
  EXPECT_THROW(read_scene_program_file(dir), PatchFormatError);
  EXPECT_THROW(read_scene_program_file(dir / "none.sp3"), std::runtime_error);
  std::filesystem::remove_all(dir);
}

// Each scene the small-scene writer makes, and its tetrahedron without UVs or surface indices,
// comes back the same (an empty uvs or materials stays empty).
TEST(SceneIo, ScenesWithoutUvsOrSurfaceIndicesComeBackAsTheyWere) {
  for (const SceneProgram& scene : {small_ball_on_table(), plain_tetrahedron(), checkered_floor()}) {
    const Bytes bytes = serialize_scene(scene);
    const SceneProgram back = deserialize_scene(bytes);
    expect_same_scene(scene, back);
    EXPECT_EQ(serialize_scene(back), bytes) << scene.name;
    SceneRenderer renderer(back);
  }
}

// The renderer built from the read-back scene gives the same force, bit for bit, as the one built
// from the scene in memory: along 16 lines pressed 3 mm into the ball (the texture, the damper)
// and 6 into the table (friction), 20 ticks each, moving sideways as they go in.
TEST(SceneIo, TheReadBackSceneFeelsTheSameAtEveryPoint) {
  const SceneProgram& scene = ball_on_table();
  const SceneProgram back = deserialize_scene(serialize_scene(scene));
  SceneRenderer original(scene), read(back);
  const double dt = 0.001;
  int points = 0, textured = 0, on_table = 0;
  auto probe = [&](glm::dvec3 from, glm::dvec3 to, glm::dvec3 drift) {
    original.reset_rt(from);
    read.reset_rt(from);
    glm::dvec3 last = from;
    for (int i = 0; i <= 20; ++i) {
      const glm::dvec3 p = from + (to - from) * (i / 20.0) + drift * (i / 20.0);
      const glm::dvec3 v = (p - last) / dt;
      last = p;
      const glm::dvec3 f0 = original.update_rt(p, v), f1 = read.update_rt(p, v);
      ++points;
      EXPECT_EQ(f0, f1) << "at " << p.x << ", " << p.y << ", " << p.z;
      EXPECT_EQ(original.surface_rt(), read.surface_rt());
      if (glm::length(read.texture_force_rt()) > 0) ++textured;
      if (read.surface_rt() == 1) ++on_table;
    }
  };
  for (int i = 0; i < 16; ++i) {
    const double phi = 2 * std::numbers::pi * i / 16, theta = 0.3 + 2.4 * i / 15;
    const glm::dvec3 d{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    const glm::dvec3 side = glm::normalize(glm::cross(d, glm::dvec3{0, 0, 1}));
    probe((kRadius + 0.003) * d, (kRadius - 0.003) * d, 0.004 * side);
  }
  for (int i = 0; i < 6; ++i) {
    const glm::dvec3 at{-0.12 + 0.045 * i, 0.09, kTableZ};
    probe(at + glm::dvec3{0, 0, 0.003}, at - glm::dvec3{0, 0, 0.003}, {0.005, 0.002, 0});
  }
  EXPECT_EQ(points, 22 * 21);
  EXPECT_GT(textured, 100);  // the corduroy is felt on the ball, not only the spring
  EXPECT_GT(on_table, 40);
}

TEST(SceneIo, ABadMagicAnotherVersionReservedBitsOrACorruptPayloadAreRefused) {
  const Bytes good = serialize_scene(small_ball_on_table());
  ASSERT_EQ(refusal(good), "");
  Bytes b = good;
  b[0] = 'X';
  EXPECT_NE(refusal(b).find("no SNDSCENE header"), std::string::npos);
  // A file of version 1 (before the relief) is refused with what to do; so is a later one.
  EXPECT_NE(refusal(with<std::uint32_t>(good, 8, 1)).find("format version 1, this build reads version 2: recompile the scene"),
            std::string::npos);
  EXPECT_NE(refusal(with<std::uint32_t>(good, 8, 3)).find("format version 3, this build reads version 2"), std::string::npos);
  EXPECT_NE(refusal(with<std::uint32_t>(good, 12, 1)).find("reserved"), std::string::npos);
  EXPECT_NE(refusal(with<std::uint32_t>(good, 28, 1)).find("reserved"), std::string::npos);
  b = good;
  b[good.size() / 2] ^= 0x10;  // the header's CRC no longer matches
  EXPECT_NE(refusal(b).find("checksum mismatch"), std::string::npos);
  b = good;
  const std::uint64_t huge = std::uint64_t{1} << 40;
  std::memcpy(b.data() + 16, &huge, 8);
  EXPECT_NE(refusal(b).find("more than the limit"), std::string::npos);
  b = good;
  b.push_back(0);
  EXPECT_NE(refusal(b).find("does not match its header"), std::string::npos);
  EXPECT_NE(refusal(refixed(b)).find("trailing bytes"), std::string::npos);
  // The file reader checks the header against the file before it reads the payload.
  const std::filesystem::path dir = test::temp_dir("scene-io-header");
  std::memcpy(b.data() + 16, &huge, 8);
  std::ofstream(dir / "huge.sp3", std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  std::string why;
  std::size_t allocated = 0;
  {
    test::CountedAllocations counted;
    try {
      (void)read_scene_program_file(dir / "huge.sp3");
    } catch (const PatchFormatError& e) {
      why = e.what();
    }
    allocated = counted.bytes();
    counted.stop();
  }
  EXPECT_NE(why.find("huge.sp3: scene program of 1099511627776 bytes, more than the limit"), std::string::npos) << why;
  EXPECT_LT(allocated, std::size_t{1} << 16);
  std::filesystem::remove_all(dir);
}

// Cut at every length, as given (the header's size no longer matches) and with the header made to
// match the cut payload (so the parser meets the end): refused every time, never a crash or an
// exception of another kind.
TEST(SceneIo, AFileCutAtEveryLengthIsRefused) {
  const Bytes good = serialize_scene(small_ball_on_table());
  ASSERT_LT(good.size(), 4096u);
  for (std::size_t n = 0; n < good.size(); ++n) {
    const Bytes cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_THROW((void)deserialize_scene(cut), PatchFormatError) << n;
    if (n >= 32) {
      EXPECT_THROW((void)deserialize_scene(refixed(cut)), PatchFormatError) << n;
    }
  }
  const std::filesystem::path dir = test::temp_dir("scene-io-cut");
  for (std::size_t n : {std::size_t{0}, std::size_t{7}, std::size_t{31}, std::size_t{32}, good.size() / 2, good.size() - 1}) {
    std::ofstream(dir / "cut.sp3", std::ios::binary).write(reinterpret_cast<const char*>(good.data()), static_cast<std::streamsize>(n));
    EXPECT_THROW((void)read_scene_program_file(dir / "cut.sp3"), PatchFormatError) << n;
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneIo, AnIndexOutOfRangeIsRefusedNamingTheTriangle) {
  const SceneProgram scene = small_ball_on_table();
  const Bytes good = serialize_scene(scene);
  const Layout l = layout_of(scene);
  const auto nv = static_cast<std::uint32_t>(scene.mesh.vertices.size());
  // Triangle 5's second corner.
  EXPECT_NE(refusal(with<std::uint32_t>(good, l.triangles + 5 * 12 + 4, nv)).find("triangle 5 names vertex " + std::to_string(nv) + " of " + std::to_string(nv)),
            std::string::npos);
  // Triangle 7's surface: 2 of 2.
  EXPECT_NE(refusal(with<std::uint16_t>(good, l.materials + 7 * 2, 2)).find("triangle 7 names surface 2 of 2"), std::string::npos);
  // A scene in memory with the same faults is not written.
  SceneProgram bad = scene;
  bad.mesh.triangles[5][1] = nv;
  EXPECT_THROW((void)serialize_scene(bad), std::invalid_argument);
  bad = scene;
  bad.mesh.materials[7] = 2;
  EXPECT_THROW((void)serialize_scene(bad), std::invalid_argument);
}

TEST(SceneIo, ANonFiniteVertexOrUvAndADegenerateTriangleAreRefused) {
  const SceneProgram scene = small_ball_on_table();
  const Bytes good = serialize_scene(scene);
  const Layout l = layout_of(scene);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(refusal(with(good, l.vertices + 3 * 24 + 8, nan)).find("vertex 3 is not finite"), std::string::npos);
  EXPECT_NE(refusal(with(good, l.vertices + 4 * 24, 2e12)).find("vertex 4 is not finite or lies beyond 1e12 m"), std::string::npos);
  EXPECT_NE(refusal(with(good, l.uvs + 2 * 16, std::numeric_limits<double>::infinity())).find("the UVs of vertex 2"), std::string::npos);
  // Triangle 9's third corner on its first: the mesh's own check, as a format error.
  Triangle t = scene.mesh.triangles[9];
  t[2] = t[0];
  EXPECT_NE(refusal(with(good, l.triangles + 9 * 12, t)).find("triangle 9 is degenerate"), std::string::npos);
}

// A counts field claiming 2^40 triangles is refused from the counts alone: nothing near their
// 12 TB is asked for. So is a count within the limits that the payload cannot hold.
TEST(SceneIo, ACountPastItsLimitIsRefusedBeforeAllocating) {
  const SceneProgram scene = small_ball_on_table();
  const Bytes good = serialize_scene(scene);
  const Layout l = layout_of(scene);
  for (const auto& [field, count, says] : {std::tuple{2, std::uint64_t{1} << 40, "1099511627776 triangles, more than the limit of 1048576"},
                                          std::tuple{0, std::uint64_t{1} << 40, "vertices, more than the limit"},
                                          std::tuple{5, std::uint64_t{70000}, "70000 surfaces, more than the limit of 65536"},
                                          std::tuple{4, scene_limits::kMaxObjects, "truncated: its counts need at least"},
                                          std::tuple{1, std::uint64_t{3}, "3 UVs for"}}) {
    const Bytes b = with(good, l.counts + 8 * static_cast<std::size_t>(field), count);
    std::string why;
    test::CountedAllocations counted;
    try {
      (void)deserialize_scene(b);
    } catch (const PatchFormatError& e) {
      why = e.what();
    }
    const std::size_t bytes = counted.bytes();
    counted.stop();
    EXPECT_NE(why.find(says), std::string::npos) << why;
    EXPECT_LT(bytes, std::size_t{1} << 16) << says;
  }
}

TEST(SceneIo, SurfacesTheRendererCouldNotUseAreRefused) {
  const SceneProgram scene = small_ball_on_table();
  auto refused = [](const SceneProgram& s) {
    const std::string problem = scene_problem(s);
    EXPECT_THROW((void)serialize_scene(s), std::invalid_argument) << problem;
    return problem;
  };
  SceneProgram bad = scene;
  bad.surfaces[0].program = 1;
  EXPECT_NE(refused(bad).find("names material program 1 of 1"), std::string::npos);
  bad = scene;
  bad.surfaces[1].program = -2;
  EXPECT_NE(refused(bad).find("material program -2"), std::string::npos);
  bad = scene;
  bad.surfaces[0].uv_size_m.y = 0;
  EXPECT_NE(refused(bad).find("metres per unit of u and v"), std::string::npos);
  bad = scene;
  bad.surfaces[1].contact.kinetic_friction = 0.7;  // above the static 0.6
  EXPECT_NE(refused(bad).find("kinetic friction"), std::string::npos);
  bad = scene;
  bad.surfaces[1].contact.stiffness_N_per_m = 1e13;
  EXPECT_NE(refused(bad).find("stiffness must be 1e-12 to 1e12 N/m"), std::string::npos);
  bad = scene;
  bad.programs[0].terms.clear();
  EXPECT_NE(refused(bad).find("no texture"), std::string::npos);
  bad = scene;
  bad.objects[1].triangle_count += 1;
  EXPECT_NE(refused(bad).find("object 1 (\"table\") names triangles"), std::string::npos);
  bad = scene;
  bad.surfaces[0].object = "\xff";
  EXPECT_NE(refused(bad).find("not UTF-8"), std::string::npos);
  bad = scene;
  bad.surfaces[0].relief_depth_m = 0.0101;
  EXPECT_NE(refused(bad).find("relief depth must be 0 or between 1e-12 m and 10 mm"), std::string::npos);
  bad.surfaces[0].relief_depth_m = -1e-4;
  EXPECT_NE(refused(bad).find("relief depth"), std::string::npos);
  bad.surfaces[0].relief_depth_m = NAN;
  EXPECT_NE(refused(bad).find("relief depth"), std::string::npos);
  bad = scene;
  bad.surfaces[1].relief_depth_m = 0.0005;  // the table has no texture
  EXPECT_NE(refused(bad).find("surface 1 (\"table\") has a relief but no texture"), std::string::npos);
  bad = plain_tetrahedron();
  bad.surfaces.clear();
  EXPECT_NE(refused(bad).find("names surface 0 of 0"), std::string::npos);
  // The same fault in a file: surface 0's program index, as the reader sees it.
  const Layout l = layout_of(scene);
  const SceneSurface& s0 = scene.surfaces[0];
  const std::size_t program0 = l.surfaces + 4 + s0.object.size() + 4 + s0.side.size() + 4 + s0.material.size() + 4 * 8;
  const Bytes good = serialize_scene(scene);
  EXPECT_NE(refusal(with<std::int32_t>(good, program0, 1)).find("surface 0 (\"ball\") names material program 1 of 1"),
            std::string::npos);
  // After the program index and the UV size: the relief depth (8 bytes) and the lateral flag (1).
  const std::size_t relief0 = program0 + 4 + 2 * 8, lateral0 = relief0 + 8;
  EXPECT_EQ(refusal(with<double>(good, relief0, 0.005)), "");
  EXPECT_NE(refusal(with<double>(good, relief0, 0.02)).find("relief depth"), std::string::npos);
  EXPECT_EQ(refusal(with<std::uint8_t>(good, lateral0, 0)), "");
  EXPECT_NE(refusal(with<std::uint8_t>(good, lateral0, 2)).find("lateral-texture flag is 2"), std::string::npos);
}

// The seeds of the scene_program fuzz target are what the writer writes for the small scenes
// here (which depend on no library entry). After a change to the format, or to the patch format
// the programs are embedded in, rewrite them with
//   SANDPAPER_WRITE_SCENE_SEEDS=1 build/bin/shapes_tests --gtest_filter=SceneIo.TheFuzzSeedsAreTheWritersBytes
TEST(SceneIo, TheFuzzSeedsAreTheWritersBytes) {
  const std::filesystem::path dir = "fuzz/corpus/scene_program";
  const bool write = std::getenv("SANDPAPER_WRITE_SCENE_SEEDS") != nullptr;
  for (const auto& [name, scene] : {std::pair{"small-ball-on-table.sp3", small_ball_on_table()},
                                    std::pair{"plain-tetrahedron.sp3", plain_tetrahedron()},
                                    std::pair{"checkered-floor.sp3", checkered_floor()}}) {
    const Bytes bytes = serialize_scene(scene);
    EXPECT_LE(bytes.size(), 4096u) << name;  // tools/fuzz.sh's smallest input limit
    if (write) write_scene_program_file(dir / name, scene);
    EXPECT_EQ(file_bytes(dir / name), bytes) << dir / name << " is not what the writer writes; see this test's comment";
  }
}

}  // namespace
}  // namespace sandpaper::shapes
