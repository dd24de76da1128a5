// The open scene in a studio built with the shapes room (SANDPAPER_SHAPES): compiled by the scenes
// room, drawn by the page, felt through shapes::SceneRenderer on the request's thread (scene_view.hpp).
#include "sandpaper/studio/scene_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include <glm/geometric.hpp>

#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/http/local_server.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"

namespace sandpaper::studio {
namespace {

// The surfaces' colours: the eight hues of `sandpaper preview SCENE` (scenes/src/scene_preview.cpp,
// Okabe & Ito's colour-blind-safe set) in the same order, so the page and the preview picture agree.
constexpr unsigned char kPalette[8][3] = {{230, 159, 0}, {86, 180, 233}, {0, 158, 115},  {240, 228, 66},
                                          {0, 114, 178}, {213, 94, 0},   {204, 121, 167}, {170, 170, 170}};

std::string colour_of(std::size_t surface) {
  const auto* c = kPalette[surface % 8];
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}

nlohmann::json vec_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// A vertex for drawing, to 0.1 um: the page's picture and its ray casts need no more, and the scene's
// 65,000-triangle sphere then travels as about 1 MB of positions rather than 2.
double drawn_m(double v) { return std::round(v * 1e7) * 1e-7; }

}  // namespace

struct SceneView::Impl {
  shapes::SceneProgram scene;
  std::vector<std::string> material_names;  // per surface: the compiled material's name, or ""
  glm::dvec3 min_m{0.0}, max_m{0.0};
  mutable std::mutex mutex;  // the renderer and the last touch: one request at a time
  std::unique_ptr<shapes::SceneRenderer> renderer;
  nlohmann::json last;
  std::uint64_t moves = 0;

  // Where the device waits before the first touch: above the scene's middle, clear of its top by a
  // quarter of its size, so that nothing is felt until the page presses on a surface.
  glm::dvec3 rest_point() const {
    const glm::dvec3 centre = 0.5 * (min_m + max_m);
    return {centre.x, max_m.y + 0.25 * glm::length(max_m - min_m) + 0.01, centre.z};
  }

  nlohmann::json read(const glm::dvec3& device, const glm::dvec3& force, int updates) const {
    const auto& contact = renderer->proxy_rt().contact_rt();
    const int surface = renderer->surface_rt();
    nlohmann::json j{{"device_m", vec_json(device)},
                     {"proxy_m", vec_json(renderer->proxy_rt().proxy_rt())},
                     {"force_N", vec_json(force)},
                     {"force_magnitude_N", glm::length(force)},
                     {"texture_force_N", vec_json(renderer->texture_force_rt())},
                     {"relief_force_N", vec_json(renderer->relief_force_rt())},
                     {"relief_carve_m", nullptr},
                     {"in_contact", surface >= 0},
                     {"surface", nullptr},
                     {"object", nullptr},
                     {"side", nullptr},
                     {"material", nullptr},
                     {"material_name", nullptr},
                     {"normal", nullptr},
                     {"normal_force_N", 0.0},
                     {"sliding", false},
                     {"constraints", 0},
                     {"settle_updates", updates},
                     {"moves", moves}};
    if (surface >= 0) {
      const auto& s = scene.surfaces[static_cast<std::size_t>(surface)];
      j["surface"] = surface;
      j["object"] = s.object;
      j["side"] = s.side;
      j["material"] = s.material;
      j["material_name"] = material_names[static_cast<std::size_t>(surface)];
      j["normal"] = vec_json(contact.normal);
      j["normal_force_N"] = contact.normal_force_N;
      j["sliding"] = contact.sliding;
      j["constraints"] = contact.constraints;
      // normal_force_N is the mesh surface's press, as `probe` gives it; a relief takes the carve's
      // share of it back, in relief_force_N.
      if (s.relief_depth_m > 0) j["relief_carve_m"] = renderer->relief_depth_rt();
    }
    return j;
  }
};

bool SceneView::built() noexcept { return true; }

std::string SceneView::unbuilt_message() { return {}; }

SceneView::SceneView(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SceneView::~SceneView() = default;

SceneView::Compiled SceneView::compile(const compiler::Compiler& compiler, const std::string& text, const std::string& name,
                                       const std::filesystem::path& base_dir) {
  scenes::SceneResult r = scenes::compile_scene_text(compiler, text, name, base_dir);
  Compiled out;
  out.answer = {{"ok", false}, {"diagnostics", compiler::diagnostics_json(r.diagnostics)}};
  out.diagnostics = r.diagnostics;
  if (!r.ok()) return out;
  auto impl = std::make_unique<Impl>();
  impl->scene = std::move(*r.program);
  const auto& scene = impl->scene;
  try {
    impl->renderer = std::make_unique<shapes::SceneRenderer>(scene);
  } catch (const std::invalid_argument& e) {
    // The scenes room refuses what the renderer would (shapes::scene_problem): this is a bug.
    throw http::RequestError(500, std::string("internal error (a bug in Sandpaper, please report it): the scene "
                                              "compiled but its renderer refused it: ") + e.what());
  }
  impl->material_names.assign(scene.surfaces.size(), "");
  for (std::size_t i = 0; i < scene.surfaces.size(); ++i)
    if (const int p = scene.surfaces[i].program; p >= 0) impl->material_names[i] = scene.programs[static_cast<std::size_t>(p)].name;
  for (const auto& m : r.materials)  // untextured materials (a spring alone) are named too
    for (const auto s : m.surfaces)
      if (s < impl->material_names.size() && impl->material_names[s].empty() && m.result && m.result->program)
        impl->material_names[s] = m.result->program->name;
  if (!scene.mesh.vertices.empty()) {
    impl->min_m = impl->max_m = scene.mesh.vertices.front();
    for (const auto& v : scene.mesh.vertices) {
      impl->min_m = glm::min(impl->min_m, v);
      impl->max_m = glm::max(impl->max_m, v);
    }
  }
  const glm::dvec3 rest = impl->rest_point();
  impl->renderer->reset_rt(rest);
  impl->last = impl->read(rest, impl->renderer->update_rt(rest), 1);
  out.answer["ok"] = true;
  out.answer["scene"] = {{"scene", scene.name},
                         {"device", scene.device},
                         {"objects", scene.objects.size()},
                         {"triangles", scene.mesh.triangles.size()},
                         {"surfaces", scene.surfaces.size()}};
  out.view = std::shared_ptr<SceneView>(new SceneView(std::move(impl)));
  return out;
}

nlohmann::json SceneView::geometry() const {
  const auto& scene = impl_->scene;
  const auto& mesh = scene.mesh;
  nlohmann::json positions = nlohmann::json::array(), triangles = nlohmann::json::array(),
                 triangle_surfaces = nlohmann::json::array(), surfaces = nlohmann::json::array(),
                 objects = nlohmann::json::array();
  positions.get_ref<nlohmann::json::array_t&>().reserve(mesh.vertices.size() * 3);
  for (const auto& v : mesh.vertices) {
    positions.push_back(drawn_m(v.x));
    positions.push_back(drawn_m(v.y));
    positions.push_back(drawn_m(v.z));
  }
  triangles.get_ref<nlohmann::json::array_t&>().reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles)
    for (const auto i : t) triangles.push_back(i);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) triangle_surfaces.push_back(mesh.materials.empty() ? 0 : mesh.materials[t]);
  for (std::size_t i = 0; i < scene.surfaces.size(); ++i) {
    const auto& s = scene.surfaces[i];
    nlohmann::json j{{"index", i},
                     {"object", s.object},
                     {"side", s.side},
                     {"material", s.material},
                     {"material_name", impl_->material_names[i]},
                     {"colour", colour_of(i)},
                     {"stiffness_N_per_m", s.contact.stiffness_N_per_m},
                     {"damping_Ns_per_m", s.contact.damping_Ns_per_m},
                     {"static_friction", s.contact.static_friction},
                     {"kinetic_friction", s.contact.kinetic_friction},
                     {"textured", s.program >= 0},
                     {"compiled_max_lateral_force_N", nullptr}};
    if (s.program >= 0) j["compiled_max_lateral_force_N"] = scene.programs[static_cast<std::size_t>(s.program)].max_lateral_force_N;
    surfaces.push_back(std::move(j));
  }
  for (const auto& o : scene.objects)
    objects.push_back({{"name", o.name}, {"shape", o.shape}, {"first_triangle", o.first_triangle}, {"triangle_count", o.triangle_count}});
  return {{"scene", scene.name},
          {"device", scene.device},
          {"frame", "x right, y up, z toward the user (glTF); metres"},
          {"positions_m", std::move(positions)},
          {"triangles", std::move(triangles)},
          {"triangle_surfaces", std::move(triangle_surfaces)},
          {"surfaces", std::move(surfaces)},
          {"objects", std::move(objects)},
          {"bounds_m", {{"min", vec_json(impl_->min_m)}, {"max", vec_json(impl_->max_m)}}},
          {"touch", last_touch()}};
}

nlohmann::json SceneView::touch(const Point_m& device_in, const std::optional<Point_m>& from_in) {
  const glm::dvec3 device{device_in[0], device_in[1], device_in[2]};
  const auto reachable = [&](const glm::dvec3& p) {
    return glm::all(glm::greaterThanEqual(p, impl_->min_m - kReach_m)) && glm::all(glm::lessThanEqual(p, impl_->max_m + kReach_m));
  };
  const auto refuse = [](const char* key) {
    throw http::RequestError(400, std::string("\"") + key + "\" must lie within " + std::to_string(static_cast<int>(kReach_m)) +
                                      " m of the scene's bounding box (three numbers, metres, the scene's frame)");
  };
  if (!reachable(device)) refuse("device_m");
  std::optional<glm::dvec3> from;
  if (from_in) {
    from = glm::dvec3{(*from_in)[0], (*from_in)[1], (*from_in)[2]};
    if (!reachable(*from)) refuse("from_m");
  }
  std::lock_guard lock(impl_->mutex);
  auto& renderer = *impl_->renderer;
  if (from) renderer.reset_rt(*from);
  // Held still at the point: a still hand, so no velocity (no damping, and friction by positions).
  glm::dvec3 force{0.0}, last_proxy{std::nan("")};
  int updates = 0;
  while (updates < kSettleUpdates) {
    force = renderer.update_rt(device);
    ++updates;
    const glm::dvec3 proxy = renderer.proxy_rt().proxy_rt();
    if (proxy == last_proxy) break;
    last_proxy = proxy;
  }
  ++impl_->moves;
  impl_->last = impl_->read(device, force, updates);
  return impl_->last;
}

nlohmann::json SceneView::last_touch() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->last;
}

}  // namespace sandpaper::studio
