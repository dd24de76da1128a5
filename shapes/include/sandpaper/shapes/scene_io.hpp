#pragma once
// Binary scene-program files (`.sp3`, docs/PATCH_FORMAT.md, "Scene programs"): what `sandpaper
// compile SCENE -o scene.sp3` writes and the runtime-only player reads without the compiler. A
// 32-byte header like a patch file's (magic "SNDSCENE", format version, payload size, CRC-32 of the
// payload), then the scene's name and device, every count up front, the mesh, the objects, the
// surfaces and each compiled material as a whole patch file (as schema::serialize writes it).
// Little-endian, deterministic: the same SceneProgram always gives the same bytes.
//
// A file that reads is one a SceneRenderer (scene_renderer.hpp) can be built from: the reader
// refuses, with PatchFormatError naming what is wrong, anything the renderer's constructor would
// throw on, and the writer refuses to write what the reader would refuse.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/shapes/scene_program.hpp"

namespace sandpaper::shapes {

// 2: each surface carries its relief depth and whether its lateral texture is kept.
inline constexpr std::uint32_t kSceneFormatVersion = 2;

// What a scene program may hold; each is checked from the counts, before anything is allocated
// for them (docs/RELIABILITY.md, "Limits").
namespace scene_limits {
// 2^20 triangles: a scanned statue of a million faces fits. Reading a sphere of 2^20 triangles and
// building its renderer (frames, edge map, BVH) took 4 s and peaked at 560 MB (release build, this
// machine), so four times it would pass 2 GB. The proxy's cost target is 100k (docs/SHAPES.md).
inline constexpr std::uint64_t kMaxTriangles = std::uint64_t{1} << 20;
// Every triangle with corners of its own.
inline constexpr std::uint64_t kMaxVertices = 3 * kMaxTriangles;
// A triangle names its surface in 16 bits (MeshData::materials): surfaces 0 to 65,535.
inline constexpr std::uint64_t kMaxSurfaces = std::uint64_t{1} << 16;
// Objects, and distinct compiled materials (at most one per surface).
inline constexpr std::uint64_t kMaxObjects = std::uint64_t{1} << 16;
inline constexpr std::uint64_t kMaxPrograms = kMaxSurfaces;
// Each name, shape, side and material text: 64 KiB (a material is named, or a one-line expression).
inline constexpr std::uint64_t kMaxStringBytes = std::uint64_t{1} << 16;
// The payload: 1 GiB. The mesh at its limits is 140 MB; the rest is the materials' force tables,
// which a workspace may hold 512 MiB of (schema::limits::kMaxWorkspaceGridBytes).
inline constexpr std::uint64_t kMaxPayloadBytes = std::uint64_t{1} << 30;
// Vertex coordinates (m) and texture coordinates lie within +-1e12, surface sizes per unit of UV
// within 1e-12 to 1e12 m, and contact values are 0 or within 1e-12 to 1e12 (the compiler's range
// for any quantity, schema::limits::kMaxPlausibleLength_m): every force the renderer then
// computes is finite.
inline constexpr double kMaxCoordinate = 1e12;
inline constexpr double kMinQuantity = 1e-12;
inline constexpr double kMaxQuantity = 1e12;
// A relief (SceneSurface::relief_depth_m) of at most 10 mm: a deeper carve is a shape, not a
// texture, and the proxy's spring would have to press that far to feel its valleys' floors.
inline constexpr double kMaxReliefDepth_m = 0.01;
}  // namespace scene_limits

// Empty when `scene` is one the reader accepts and SceneRenderer builds, else the first thing wrong
// with it ("triangle 7 names vertex 12 of 9", "mesh: triangle 3 is degenerate", ...). Checks the
// counts and string lengths against scene_limits, every string is UTF-8, vertices and UVs finite
// and within range, uvs empty or one per vertex, materials empty or one per triangle, every index
// in range (a triangle's vertices and surface, an object's triangles, a surface's program, or -1),
// each surface's contact (material_problem, and its range), uv size and relief (0, or within
// 1e-12 m to kMaxReliefDepth_m on a surface with a program), each program's texture
// (SurfaceTexture::for_program_nonrt, and SurfaceRelief's for those a relief follows), and builds
// the Mesh (a degenerate triangle). O(n log n) in the triangles, off the servo thread.
std::string scene_problem(const SceneProgram& scene);

// The whole file, header included. `options` applies to the programs' height fields (--compact).
// Throws std::invalid_argument when scene_problem finds something (a file that could not be read).
std::vector<unsigned char> serialize_scene(const SceneProgram& scene, const schema::PatchWriteOptions& options = {});
// From the whole file's bytes. Throws schema::PatchFormatError: a wrong magic, another version,
// nonzero reserved fields, a size that does not match, a checksum mismatch, truncated or trailing
// bytes, a count past scene_limits (before allocating for it), an embedded patch program its
// reader refuses, or anything scene_problem finds.
SceneProgram deserialize_scene(const std::vector<unsigned char>& bytes);

// Written to a temporary file and renamed (schema::write_file_atomically). Throws
// std::invalid_argument as serialize_scene, std::runtime_error on I/O failure.
void write_scene_program_file(const std::filesystem::path& path, const SceneProgram& scene,
                              const schema::PatchWriteOptions& options = {});
// Throws std::runtime_error (cannot read) or schema::PatchFormatError (not a regular file, or not
// a valid scene program: as deserialize_scene, the path in front of the reason). The size in the
// header is checked against the file and kMaxPayloadBytes before the payload is read.
SceneProgram read_scene_program_file(const std::filesystem::path& path);
// True if the file is a regular file starting with the scene-program magic.
bool looks_like_scene_program_file(const std::filesystem::path& path);

}  // namespace sandpaper::shapes
