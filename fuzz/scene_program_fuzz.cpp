// Scene programs (.sp3, what the runtime-only player reads; shapes/scene_io.hpp) through
// shapes::deserialize_scene, once as given and once with the header's size and CRC-32 fixed up so
// mutations reach the field parser; the bytes as given also through read_scene_program_file,
// which must agree. An accepted scene must be one the writer writes and whose bytes read back and
// write again unchanged, and one a SceneRenderer is built from (the reader's promise): the
// renderer is then pressed into a few of its triangles, every force finite, every relief's carve
// within its depth. Seeds: the small
// scenes of tests/shapes/scene_io_test.cpp, written by the writer
// (SceneIo.TheFuzzSeedsAreTheWritersBytes).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>

#include "fuzz_support.hpp"
#include "sandpaper/shapes/scene_io.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"

namespace {

using namespace sandpaper;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Presses the device through up to four triangles picked by `variant`: from above each one's
// centroid, along its normal, to as far below, sliding sideways, 8 ticks each.
void press(const shapes::SceneProgram& scene, std::uint32_t variant) {
  shapes::SceneRenderer renderer(scene);
  const std::size_t nt = renderer.mesh().triangle_count();
  if (nt == 0) {
    fuzz::check(renderer.update_rt(glm::dvec3{0.0}) == glm::dvec3{0.0}, "an empty scene pushed");
    return;
  }
  for (std::uint32_t k = 0; k < 4; ++k) {
    const std::size_t t = (variant + k * 7919u) % nt;
    const auto& tri = renderer.mesh().triangles()[t];
    const auto v = renderer.mesh().vertices();
    const glm::dvec3 centre = (v[tri[0]] + v[tri[1]] + v[tri[2]]) / 3.0;
    const shapes::TriangleFrame& f = renderer.mesh().frame(t);
    const double depth = 0.5 * std::max(glm::length(f.e1), glm::length(f.e2)) * ((variant >> k) & 1 ? 0.1 : 1.0);
    const glm::dvec3 from = centre + depth * f.normal, to = centre - depth * f.normal;
    renderer.reset_rt(from);
    for (int i = 0; i <= 8; ++i) {
      const glm::dvec3 p = from + (to - from) * (i / 8.0) + f.tangent * (depth * i / 16.0);
      const glm::dvec3 force = renderer.update_rt(p, (to - from) * 125.0);
      fuzz::check(finite(force), "a scene the reader accepted gave a force that is not finite");
      fuzz::check(finite(renderer.texture_force_rt()), "a scene the reader accepted gave a texture force that is not finite");
      fuzz::check(finite(renderer.relief_force_rt()) && std::isfinite(renderer.relief_depth_rt()),
                  "a scene the reader accepted gave a relief that is not finite");
      const int surface = renderer.surface_rt();
      if (surface >= 0)
        fuzz::check(renderer.relief_depth_rt() >= 0 && renderer.relief_depth_rt() <= scene.surfaces[surface].relief_depth_m * (1 + 1e-9),
                    "a relief carved outside 0 to its depth");
      const int s = renderer.surface_rt();
      fuzz::check(s >= -1 && s < static_cast<int>(scene.surfaces.size()), "the renderer named a surface out of range");
    }
  }
}

void try_bytes(const std::vector<unsigned char>& bytes, std::uint32_t variant, bool through_file) {
  shapes::SceneProgram scene;
  std::string refused;
  try {
    scene = shapes::deserialize_scene(bytes);
  } catch (const schema::PatchFormatError& e) {
    refused = e.what();
  }
  if (through_file) {
    const auto path = fuzz::scratch_dir() / "input.sp3";
    fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    bool file_refused = false;
    try {
      (void)shapes::read_scene_program_file(path);
    } catch (const schema::PatchFormatError&) {
      file_refused = true;
    }
    fuzz::check(file_refused == !refused.empty(), "the file reader and deserialize_scene disagree: " + refused);
  }
  if (!refused.empty()) return;
  std::vector<unsigned char> written;
  try {
    written = shapes::serialize_scene(scene);
  } catch (const std::invalid_argument& e) {
    fuzz::fail(std::string("a scene the reader accepted is not written: ") + e.what());
  }
  shapes::SceneProgram again;
  try {
    again = shapes::deserialize_scene(written);
  } catch (const schema::PatchFormatError& e) {
    fuzz::fail(std::string("a scene the reader accepted, written again, does not read back: ") + e.what());
  }
  fuzz::check(shapes::serialize_scene(again) == written, "read -> write -> read -> write changed the bytes");
  try {
    press(scene, variant);
  } catch (const std::invalid_argument& e) {
    fuzz::fail(std::string("the renderer refused a scene the reader accepted: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto fixed = fuzz::with_valid_header(data, size, "SNDSCENE", shapes::kSceneFormatVersion);
  std::uint32_t variant = 0;
  std::memcpy(&variant, fixed.data() + 24, sizeof variant);
  const std::vector<unsigned char> raw(data, data + size);
  try_bytes(raw, variant, true);
  if (raw != fixed) try_bytes(fixed, variant, false);
  return 0;
}
