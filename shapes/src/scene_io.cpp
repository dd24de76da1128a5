#include "sandpaper/shapes/scene_io.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include <zlib.h>

#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/shapes/surface_relief.hpp"
#include "sandpaper/shapes/surface_texture.hpp"

namespace sandpaper::shapes {
namespace {

using schema::PatchFormatError;
namespace lim = scene_limits;

constexpr char kMagic[8] = {'S', 'N', 'D', 'S', 'C', 'E', 'N', 'E'};
constexpr std::size_t kHeaderSize = 32;

// The mesh's arrays are written and read as they lie in memory: little-endian IEEE doubles and
// unsigned integers, packed (docs/PATCH_FORMAT.md, "Scene programs").
static_assert(std::endian::native == std::endian::little, "scene I/O assumes a little-endian host");
static_assert(sizeof(glm::dvec3) == 24 && sizeof(glm::dvec2) == 16 && sizeof(Triangle) == 12);
// Bytes of each record with its strings empty: what the counts claim at the least, checked against
// the payload before anything is allocated.
constexpr std::uint64_t kVertexBytes = 24, kUvBytes = 16, kTriangleBytes = 12, kMaterialBytes = 2;
constexpr std::uint64_t kObjectBytes = 4 + 4 + 4 + 4;
constexpr std::uint64_t kSurfaceBytes = 3 * 4 + 4 * 8 + 4 + 2 * 8 + 8 + 1;
constexpr std::uint64_t kProgramBytes = 8;

// ---- writing ----

void put_bytes(std::vector<unsigned char>& out, const void* p, std::size_t n) {
  const auto* b = static_cast<const unsigned char*>(p);
  out.insert(out.end(), b, b + n);
}
template <class T>
void put(std::vector<unsigned char>& out, T v) {
  put_bytes(out, &v, sizeof v);
}
void put_str(std::vector<unsigned char>& out, const std::string& s) {
  put(out, static_cast<std::uint32_t>(s.size()));
  put_bytes(out, s.data(), s.size());
}

std::uint32_t crc_of(const unsigned char* p, std::size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  while (n > 0) {
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

// ---- checking ----

// A name as a message shows it: UTF-8 whatever it held, and at most 80 bytes of it.
std::string shown(const std::string& s) {
  return "\"" + schema::replace_invalid_utf8(std::string_view(s).substr(0, 80)) + (s.size() > 80 ? "...\"" : "\"");
}

std::string surface_name(std::size_t i, const SceneSurface& s) {
  return "surface " + std::to_string(i) + " (" + shown(s.object) + (s.side.empty() ? "" : " " + shown(s.side)) + ")";
}

// A string problem ("" if none): too long, or not UTF-8.
std::string string_problem(const std::string& s, const char* what) {
  if (s.size() > lim::kMaxStringBytes)
    return std::string(what) + " of " + std::to_string(s.size()) + " bytes, more than " +
           std::to_string(lim::kMaxStringBytes);
  if (std::size_t bad = 0; !schema::is_valid_utf8(s, bad))
    return std::string(what) + " that is not UTF-8 (byte " + std::to_string(bad) + " of it)";
  return {};
}

bool within(double x, double bound) { return std::isfinite(x) && std::abs(x) <= bound; }
// 0, or a quantity the compiler could have written.
bool zero_or_quantity(double x) { return x == 0.0 || (std::isfinite(x) && x >= lim::kMinQuantity && x <= lim::kMaxQuantity); }
bool quantity(double x) { return x != 0.0 && zero_or_quantity(x); }

std::string count_problem(std::uint64_t n, std::uint64_t limit, const char* what) {
  if (n <= limit) return {};
  return std::to_string(n) + " " + what + ", more than the limit of " + std::to_string(limit);
}

// The counts alone: what the reader checks before it allocates, and scene_problem first.
std::string counts_problem(std::uint64_t vertices, std::uint64_t uvs, std::uint64_t triangles, std::uint64_t materials,
                           std::uint64_t objects, std::uint64_t surfaces, std::uint64_t programs) {
  for (auto p : {count_problem(vertices, lim::kMaxVertices, "vertices"),
                 count_problem(triangles, lim::kMaxTriangles, "triangles"),
                 count_problem(objects, lim::kMaxObjects, "objects"),
                 count_problem(surfaces, lim::kMaxSurfaces, "surfaces"),
                 count_problem(programs, lim::kMaxPrograms, "material programs")})
    if (!p.empty()) return p;
  if (uvs != 0 && uvs != vertices)
    return std::to_string(uvs) + " UVs for " + std::to_string(vertices) + " vertices (none, or one each)";
  if (materials != 0 && materials != triangles)
    return std::to_string(materials) + " surface indices for " + std::to_string(triangles) +
           " triangles (none, or one each)";
  return {};
}

}  // namespace

std::string scene_problem(const SceneProgram& scene) {
  const MeshData& m = scene.mesh;
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size(), ns = scene.surfaces.size();
  if (auto p = counts_problem(nv, m.uvs.size(), nt, m.materials.size(), scene.objects.size(), ns, scene.programs.size());
      !p.empty())
    return p;
  if (auto p = string_problem(scene.name, "a name"); !p.empty()) return p;
  if (auto p = string_problem(scene.device, "a device name"); !p.empty()) return p;
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::dvec3& v = m.vertices[i];
    if (!within(v.x, lim::kMaxCoordinate) || !within(v.y, lim::kMaxCoordinate) || !within(v.z, lim::kMaxCoordinate))
      return "vertex " + std::to_string(i) + " is not finite or lies beyond 1e12 m";
  }
  for (std::size_t i = 0; i < m.uvs.size(); ++i)
    if (!within(m.uvs[i].x, lim::kMaxCoordinate) || !within(m.uvs[i].y, lim::kMaxCoordinate))
      return "the UVs of vertex " + std::to_string(i) + " are not finite or lie beyond 1e12";
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t index : m.triangles[t])
      if (index >= nv)
        return "triangle " + std::to_string(t) + " names vertex " + std::to_string(index) + " of " + std::to_string(nv);
  // No surface indices: every triangle is on surface 0.
  if (m.materials.empty() && nt > 0 && ns == 0) return "triangle 0 names surface 0 of 0";
  for (std::size_t t = 0; t < m.materials.size(); ++t)
    if (m.materials[t] >= ns)
      return "triangle " + std::to_string(t) + " names surface " + std::to_string(m.materials[t]) + " of " +
             std::to_string(ns);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const std::string which = "object " + std::to_string(i) + " (" + shown(o.name) + ")";
    if (auto p = string_problem(o.name, "a name"); !p.empty()) return which + " has " + p;
    if (auto p = string_problem(o.shape, "a shape"); !p.empty()) return which + " has " + p;
    if (std::uint64_t{o.first_triangle} + o.triangle_count > nt)
      return which + " names triangles " + std::to_string(o.first_triangle) + " to " +
             std::to_string(std::uint64_t{o.first_triangle} + o.triangle_count) + " of " + std::to_string(nt);
  }
  std::vector<SurfaceMaterial> contacts;
  contacts.reserve(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    const SceneSurface& s = scene.surfaces[i];
    const std::string which = "surface " + std::to_string(i);
    if (auto p = string_problem(s.object, "an object name"); !p.empty()) return which + " has " + p;
    if (auto p = string_problem(s.side, "a side"); !p.empty()) return which + " has " + p;
    if (auto p = string_problem(s.material, "a material"); !p.empty()) return which + " has " + p;
    if (s.program < -1 || (s.program >= 0 && static_cast<std::size_t>(s.program) >= scene.programs.size()))
      return surface_name(i, s) + " names material program " + std::to_string(s.program) + " of " +
             std::to_string(scene.programs.size());
    if (!quantity(s.uv_size_m.x) || !quantity(s.uv_size_m.y))
      return surface_name(i, s) + ": its metres per unit of u and v must be between 1e-12 and 1e12 m";
    const SurfaceMaterial& c = s.contact;
    if (!quantity(c.stiffness_N_per_m) || !zero_or_quantity(c.damping_Ns_per_m) || !zero_or_quantity(c.static_friction) ||
        !zero_or_quantity(c.kinetic_friction))
      return surface_name(i, s) +
             ": its stiffness must be 1e-12 to 1e12 N/m, and its damping and friction 0 or 1e-12 to 1e12";
    if (!(s.relief_depth_m == 0.0 || (std::isfinite(s.relief_depth_m) && s.relief_depth_m >= lim::kMinQuantity &&
                                       s.relief_depth_m <= lim::kMaxReliefDepth_m)))
      return surface_name(i, s) + ": its relief depth must be 0 or between 1e-12 m and 10 mm";
    if (s.relief_depth_m != 0.0 && s.program < 0) return surface_name(i, s) + " has a relief but no texture for it to follow";
    contacts.push_back(c);
  }
  if (std::string p = material_problem(contacts); !p.empty()) return "surfaces: " + p;
  // What SceneRenderer builds from each program (a texture the runtime's evaluator accepts).
  for (std::size_t i = 0; i < scene.programs.size(); ++i) {
    try {
      (void)SurfaceTexture::for_program_nonrt(scene.programs[i]);
      if (std::any_of(scene.surfaces.begin(), scene.surfaces.end(),
                      [&](const SceneSurface& s) { return s.program == static_cast<int>(i) && s.relief_depth_m != 0.0; }))
        (void)SurfaceRelief::for_program_nonrt(scene.programs[i], lim::kMaxReliefDepth_m);
    } catch (const std::invalid_argument& e) {
      return "material program " + std::to_string(i) + " (" + shown(scene.programs[i].name) + "): " + e.what();
    }
  }
  // The last check and the only costly one: degenerate triangles, as the renderer will find them.
  try {
    (void)Mesh::build_nonrt(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

namespace {

// ---- reading ----

class Cursor {
 public:
  Cursor(const unsigned char* p, std::size_t n) : p_(p), end_(p + n) {}
  template <class T>
  T pod() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  std::string str(const char* what) {
    const auto n = pod<std::uint32_t>();
    if (n > lim::kMaxStringBytes)
      throw PatchFormatError("scene program holds " + std::string(what) + " of " + std::to_string(n) + " bytes, more than " +
                             std::to_string(lim::kMaxStringBytes));
    need(n);
    std::string s(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    // Names go on to JSON and terminals; the compiler writes only UTF-8.
    if (std::size_t bad = 0; !schema::is_valid_utf8(s, bad))
      throw PatchFormatError("scene program holds " + std::string(what) + " that is not UTF-8 (byte " +
                             std::to_string(bad) + " of it)");
    return s;
  }
  // n records of T, copied as they lie (the counts were checked against the payload already).
  template <class T>
  void array(std::vector<T>& into, std::uint64_t n) {
    need(n * sizeof(T));
    into.resize(n);
    take(into.data(), n * sizeof(T));
  }
  std::vector<unsigned char> bytes(std::uint64_t n) {
    need(n);
    std::vector<unsigned char> v(p_, p_ + n);
    p_ += n;
    return v;
  }
  std::uint64_t remaining() const { return static_cast<std::uint64_t>(end_ - p_); }
  bool done() const { return p_ == end_; }

 private:
  void need(std::uint64_t n) const {
    if (remaining() < n) throw PatchFormatError("scene program truncated");
  }
  void take(void* into, std::size_t n) {
    need(n);
    if (n > 0) std::memcpy(into, p_, n);
    p_ += n;
  }
  const unsigned char* p_;
  const unsigned char* end_;
};

// The payload size a header states, checked against what follows it (`present` bytes): the same
// checks for bytes in memory and for a file before its payload is read.
std::uint64_t checked_header(const unsigned char* head, std::size_t have, std::uint64_t present) {
  if (have < sizeof kMagic || std::memcmp(head, kMagic, sizeof kMagic) != 0)
    throw PatchFormatError("not a Sandpaper scene program (no SNDSCENE header)");
  if (have < kHeaderSize) throw PatchFormatError("scene program truncated in its header");
  std::uint32_t version = 0, flags = 0, crc = 0, padding = 0;
  std::uint64_t size = 0;
  std::memcpy(&version, head + 8, sizeof version);
  std::memcpy(&flags, head + 12, sizeof flags);
  std::memcpy(&size, head + 16, sizeof size);
  std::memcpy(&crc, head + 24, sizeof crc);
  std::memcpy(&padding, head + 28, sizeof padding);
  if (version != kSceneFormatVersion)
    throw PatchFormatError("scene format version " + std::to_string(version) + ", this build reads version " +
                           std::to_string(kSceneFormatVersion) + ": recompile the scene");
  if (flags != 0 || padding != 0) throw PatchFormatError("scene program with reserved header fields that are not 0");
  if (size > lim::kMaxPayloadBytes)
    throw PatchFormatError("scene program of " + std::to_string(size) + " bytes, more than the limit of " +
                           std::to_string(lim::kMaxPayloadBytes));
  if (size != present) throw PatchFormatError("scene program size does not match its header (truncated or padded file)");
  return size;
}

}  // namespace

std::vector<unsigned char> serialize_scene(const SceneProgram& scene, const schema::PatchWriteOptions& options) {
  if (std::string problem = scene_problem(scene); !problem.empty())
    throw std::invalid_argument("scene program not written: " + problem);
  const MeshData& m = scene.mesh;
  std::vector<unsigned char> out(kHeaderSize, 0);
  put_str(out, scene.name);
  put_str(out, scene.device);
  for (std::size_t n : {m.vertices.size(), m.uvs.size(), m.triangles.size(), m.materials.size(), scene.objects.size(),
                        scene.surfaces.size(), scene.programs.size()})
    put(out, static_cast<std::uint64_t>(n));
  put_bytes(out, m.vertices.data(), m.vertices.size() * sizeof(glm::dvec3));
  put_bytes(out, m.uvs.data(), m.uvs.size() * sizeof(glm::dvec2));
  put_bytes(out, m.triangles.data(), m.triangles.size() * sizeof(Triangle));
  put_bytes(out, m.materials.data(), m.materials.size() * sizeof(std::uint16_t));
  for (const SceneObject& o : scene.objects) {
    put_str(out, o.name);
    put_str(out, o.shape);
    put(out, o.first_triangle);
    put(out, o.triangle_count);
  }
  for (const SceneSurface& s : scene.surfaces) {
    put_str(out, s.object);
    put_str(out, s.side);
    put_str(out, s.material);
    put(out, s.contact.stiffness_N_per_m);
    put(out, s.contact.damping_Ns_per_m);
    put(out, s.contact.static_friction);
    put(out, s.contact.kinetic_friction);
    put(out, static_cast<std::int32_t>(s.program));
    put(out, s.uv_size_m.x);
    put(out, s.uv_size_m.y);
    put(out, s.relief_depth_m);
    put(out, static_cast<std::uint8_t>(s.lateral_texture ? 1 : 0));
  }
  for (const schema::PatchProgram& p : scene.programs) {
    const std::vector<unsigned char> program = schema::serialize(p, options);
    put(out, static_cast<std::uint64_t>(program.size()));
    put_bytes(out, program.data(), program.size());
  }
  const std::uint32_t version = kSceneFormatVersion;
  const std::uint64_t size = out.size() - kHeaderSize;
  const std::uint32_t crc = crc_of(out.data() + kHeaderSize, size);
  std::memcpy(out.data(), kMagic, sizeof kMagic);
  std::memcpy(out.data() + 8, &version, sizeof version);
  std::memcpy(out.data() + 16, &size, sizeof size);
  std::memcpy(out.data() + 24, &crc, sizeof crc);
  return out;
}

SceneProgram deserialize_scene(const std::vector<unsigned char>& bytes) {
  const std::uint64_t size =
      checked_header(bytes.data(), bytes.size(), bytes.size() < kHeaderSize ? 0 : bytes.size() - kHeaderSize);
  const unsigned char* payload = bytes.data() + kHeaderSize;
  std::uint32_t crc = 0;
  std::memcpy(&crc, bytes.data() + 24, sizeof crc);
  if (crc_of(payload, size) != crc) throw PatchFormatError("scene program checksum mismatch (corrupted file)");

  Cursor c(payload, size);
  SceneProgram scene;
  scene.name = c.str("a name");
  scene.device = c.str("a device name");
  std::uint64_t n[7];
  for (auto& count : n) count = c.pod<std::uint64_t>();
  const auto [nv, nuv, nt, nm, no, ns, np] = n;
  if (std::string p = counts_problem(nv, nuv, nt, nm, no, ns, np); !p.empty())
    throw PatchFormatError("scene program with " + p);
  // Within the limits these products cannot overflow; a count the payload cannot hold is refused
  // here, before its array is allocated.
  const std::uint64_t least = nv * kVertexBytes + nuv * kUvBytes + nt * kTriangleBytes + nm * kMaterialBytes +
                              no * kObjectBytes + ns * kSurfaceBytes + np * kProgramBytes;
  if (least > c.remaining())
    throw PatchFormatError("scene program truncated: its counts need at least " + std::to_string(least) +
                           " more bytes, it has " + std::to_string(c.remaining()));
  MeshData& m = scene.mesh;
  c.array(m.vertices, nv);
  c.array(m.uvs, nuv);
  c.array(m.triangles, nt);
  c.array(m.materials, nm);
  scene.objects.resize(no);
  for (SceneObject& o : scene.objects) {
    o.name = c.str("an object name");
    o.shape = c.str("a shape");
    o.first_triangle = c.pod<std::uint32_t>();
    o.triangle_count = c.pod<std::uint32_t>();
  }
  scene.surfaces.resize(ns);
  for (SceneSurface& s : scene.surfaces) {
    s.object = c.str("an object name");
    s.side = c.str("a side");
    s.material = c.str("a material");
    s.contact.stiffness_N_per_m = c.pod<double>();
    s.contact.damping_Ns_per_m = c.pod<double>();
    s.contact.static_friction = c.pod<double>();
    s.contact.kinetic_friction = c.pod<double>();
    s.program = c.pod<std::int32_t>();
    s.uv_size_m.x = c.pod<double>();
    s.uv_size_m.y = c.pod<double>();
    s.relief_depth_m = c.pod<double>();
    const auto lateral = c.pod<std::uint8_t>();
    if (lateral > 1)
      throw PatchFormatError("scene program has a surface whose lateral-texture flag is " + std::to_string(lateral) +
                             ", not 0 or 1");
    s.lateral_texture = lateral == 1;
  }
  scene.programs.reserve(np);
  for (std::uint64_t i = 0; i < np; ++i) {
    const auto length = c.pod<std::uint64_t>();
    const std::vector<unsigned char> program = c.bytes(length);
    try {
      scene.programs.push_back(schema::deserialize(program));
    } catch (const PatchFormatError& e) {
      throw PatchFormatError("scene program's material program " + std::to_string(i) + ": " + e.what());
    }
  }
  if (!c.done()) throw PatchFormatError("scene program has trailing bytes");
  if (std::string p = scene_problem(scene); !p.empty()) throw PatchFormatError("scene program: " + p);
  return scene;
}

void write_scene_program_file(const std::filesystem::path& path, const SceneProgram& scene,
                              const schema::PatchWriteOptions& options) {
  const std::vector<unsigned char> bytes = serialize_scene(scene, options);
  schema::write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

SceneProgram read_scene_program_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (const auto status = std::filesystem::status(path, ec);
      !ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw PatchFormatError(path.string() + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open scene program '" + path.string() + "'");
  try {
    std::vector<unsigned char> bytes(kHeaderSize);
    in.read(reinterpret_cast<char*>(bytes.data()), kHeaderSize);
    const auto have = static_cast<std::size_t>(in.gcount());
    const auto file_size = std::filesystem::file_size(path, ec);
    if (ec) throw std::runtime_error("cannot read scene program '" + path.string() + "': " + ec.message());
    // The header's claim against the file and the limit, before the payload is allocated.
    const std::uint64_t size = checked_header(bytes.data(), have, file_size < kHeaderSize ? 0 : file_size - kHeaderSize);
    bytes.resize(kHeaderSize + size);
    in.read(reinterpret_cast<char*>(bytes.data() + kHeaderSize), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size) throw PatchFormatError("scene program truncated");
    return deserialize_scene(bytes);
  } catch (const PatchFormatError& e) {
    throw PatchFormatError(path.string() + ": " + e.what());
  }
}

bool looks_like_scene_program_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  char m[sizeof kMagic] = {};
  in.read(m, sizeof m);
  return in.gcount() == static_cast<std::streamsize>(sizeof m) && std::memcmp(m, kMagic, sizeof m) == 0;
}

}  // namespace sandpaper::shapes
