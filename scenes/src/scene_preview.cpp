#include "sandpaper/scenes/scene_preview.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/mesh.hpp"
#include "sandpaper/shapes/surface_texture.hpp"

namespace sandpaper::scenes {

namespace {

// Eight hues a reader can tell apart (Okabe & Ito 2008, the colour-blind-safe set).
constexpr std::array<std::array<std::uint8_t, 3>, 8> kPalette = {{{230, 159, 0},
                                                                  {86, 180, 233},
                                                                  {0, 158, 115},
                                                                  {240, 228, 66},
                                                                  {0, 114, 178},
                                                                  {213, 94, 0},
                                                                  {204, 121, 167},
                                                                  {170, 170, 170}}};

}  // namespace

ScenePicture render_scene_picture(const shapes::SceneProgram& scene, int max_side) {
  if (max_side < 16 || max_side > 4096) throw std::invalid_argument("scene picture: the side must be 16 to 4096 pixels");
  if (scene.mesh.triangles.empty()) throw std::invalid_argument("scene picture: the scene has no triangles");
  const shapes::Mesh mesh = shapes::Mesh::build_nonrt(scene.mesh);
  const shapes::Bvh bvh = shapes::Bvh::build_nonrt(mesh);
  std::vector<std::optional<shapes::SurfaceTexture>> textures;
  std::vector<double> max_force;
  for (const auto& s : scene.surfaces) {
    if (s.program >= 0 && static_cast<std::size_t>(s.program) < scene.programs.size()) {
      textures.emplace_back(shapes::SurfaceTexture::for_program_nonrt(scene.programs[s.program], s.uv_size_m));
      max_force.push_back(scene.programs[s.program].max_lateral_force_N);
    } else {
      textures.emplace_back();
      max_force.push_back(0);
    }
  }

  ScenePicture pic;
  // From the front, right and above, as one looks down at a table.
  pic.view_from = glm::normalize(glm::dvec3{0.55, 0.75, 1.0});
  const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3{0, 1, 0}, pic.view_from));
  const glm::dvec3 up = glm::cross(pic.view_from, right);
  glm::dvec3 lo{INFINITY}, hi{-INFINITY};
  for (const auto& v : scene.mesh.vertices) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double reach = glm::length(hi - lo) + 1e-3;
  // The box's corners on the picture plane give its extent.
  double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
    const double u = glm::dot(c - centre, right), v = glm::dot(c - centre, up);
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
  }
  const double margin = 0.04 * std::max(u1 - u0, v1 - v0);
  u0 -= margin, u1 += margin, v0 -= margin, v1 += margin;
  pic.pixel_m = std::max(u1 - u0, v1 - v0) / max_side;
  pic.width = std::max(1, static_cast<int>(std::ceil((u1 - u0) / pic.pixel_m)));
  pic.height = std::max(1, static_cast<int>(std::ceil((v1 - v0) / pic.pixel_m)));
  pic.rgb.assign(static_cast<std::size_t>(pic.width) * pic.height * 3, 255);
  for (std::size_t i = 0; i < scene.surfaces.size(); ++i) pic.surface_colours.push_back(kPalette[i % kPalette.size()]);

  const glm::dvec3 light = glm::normalize(pic.view_from + glm::dvec3{-0.4, 0.8, 0.1});
  for (int y = 0; y < pic.height; ++y)
    for (int x = 0; x < pic.width; ++x) {
      const double u = u0 + (x + 0.5) * pic.pixel_m, v = v1 - (y + 0.5) * pic.pixel_m;
      const glm::dvec3 a = centre + u * right + v * up + reach * pic.view_from;
      const auto hit = bvh.first_hit_rt(a, a - 2 * reach * pic.view_from);
      if (!hit) continue;
      ++pic.pixels_on_surfaces;
      const auto surface = mesh.material(hit->triangle);
      const glm::dvec3 n = mesh.frame(hit->triangle).normal;
      // A face seen from behind (inside a room box) is lit as if turned to the viewer, but dimmer.
      const bool front = glm::dot(n, pic.view_from) > 0;
      double shade = 0.35 + 0.65 * std::max(0.0, glm::dot(front ? n : -n, light));
      if (!front) shade *= 0.7;
      if (textures[surface] && max_force[surface] > 0) {
        const double f = glm::length(textures[surface]->force_rt(mesh, hit->triangle, hit->point_m));
        shade *= 0.55 + 0.45 * std::min(1.0, f / max_force[surface]);
      }
      const auto& c = pic.surface_colours[surface];
      auto* px = &pic.rgb[(static_cast<std::size_t>(y) * pic.width + x) * 3];
      for (int k = 0; k < 3; ++k) px[k] = static_cast<std::uint8_t>(std::clamp(c[k] * shade, 0.0, 255.0));
    }
  return pic;
}

}  // namespace sandpaper::scenes
