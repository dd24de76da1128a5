#include <cmath>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "cli.hpp"
#include "scene_input.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"

namespace sandpaper::cli {

namespace {

// "X,Y,Z" in millimetres -> metres; nullopt when it is not three finite numbers.
std::optional<glm::dvec3> point_mm(const std::string& text) {
  std::istringstream in(text);
  glm::dvec3 p;
  char c1 = 0, c2 = 0;
  if (!(in >> p.x >> c1 >> p.y >> c2 >> p.z) || c1 != ',' || c2 != ',') return std::nullopt;
  in >> std::ws;
  if (!in.eof() || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return std::nullopt;
  return p * 1e-3;
}

// A probe holds the device still at each step: the proxy is updated until it stops moving (one
// update can end before the proxy reaches its place: the renderer bounds its work a tick), at most
// this many times.
constexpr int kSettleUpdates = 64;

}  // namespace

int cmd_probe(const CommonOptions& o, const ProbeOptions& p) {
  const auto from = point_mm(p.from), to = point_mm(p.to);
  if (!from || !to) {
    std::cerr << "sandpaper probe: --from and --to take X,Y,Z in millimetres, e.g. --from 0,120,0\n";
    return kExitUsage;
  }
  if (p.steps < 1 || p.steps > 1000000) {
    std::cerr << "sandpaper probe: --steps takes 1 to 1000000\n";
    return kExitUsage;
  }
  auto c = make_compiler(o);
  auto r = load_scene(o, c);
  if (!r) return kExitBadInput;
  const shapes::SceneProgram& scene = *r->program;
  shapes::SceneRenderer renderer(scene);
  renderer.reset_rt(*from);

  nlohmann::json rows = nlohmann::json::array();
  if (!o.json)
    std::cout << fmt::format("probe \"{}\" from {} to {} mm in {} steps (scene frame: x right, y up, z toward the user)\n",
                             scene.name, p.from, p.to, p.steps)
              << "  step  device mm                    force N (x, y, z)              |F| N    contact\n";
  for (int i = 0; i <= p.steps; ++i) {
    const glm::dvec3 device = *from + (*to - *from) * (static_cast<double>(i) / p.steps);
    glm::dvec3 force{0.0}, last_proxy{std::nan("")};
    for (int k = 0; k < kSettleUpdates; ++k) {
      force = renderer.update_rt(device);
      const glm::dvec3 proxy = renderer.proxy_rt().proxy_rt();
      if (proxy == last_proxy) break;
      last_proxy = proxy;
    }
    const int surface = renderer.surface_rt();
    const auto& contact = renderer.proxy_rt().contact_rt();
    std::string where = "free";
    if (surface >= 0) {
      const auto& s = scene.surfaces[surface];
      where = "\"" + s.object + "\"" + (s.side.empty() ? "" : " " + s.side) + (contact.sliding ? ", sliding" : "");
    }
    if (o.json) {
      const glm::dvec3 proxy = renderer.proxy_rt().proxy_rt();
      nlohmann::json row{{"step", i},
                         {"device_mm", {device.x * 1e3, device.y * 1e3, device.z * 1e3}},
                         {"proxy_mm", {proxy.x * 1e3, proxy.y * 1e3, proxy.z * 1e3}},
                         {"force_N", {force.x, force.y, force.z}},
                         {"force_magnitude_N", glm::length(force)},
                         {"texture_force_N", {renderer.texture_force_rt().x, renderer.texture_force_rt().y, renderer.texture_force_rt().z}},
                         {"in_contact", surface >= 0}};
      if (surface >= 0) {
        const auto& s = scene.surfaces[surface];
        row["object"] = s.object;
        row["side"] = s.side;
        row["material"] = s.material;
        row["normal"] = {contact.normal.x, contact.normal.y, contact.normal.z};
        row["normal_force_N"] = contact.normal_force_N;
        row["sliding"] = contact.sliding;
        if (s.relief_depth_m > 0) {
          // normal_force_N is the mesh surface's press; the relief takes the carve's share back.
          const glm::dvec3 relief = renderer.relief_force_rt();
          row["relief_force_N"] = {relief.x, relief.y, relief.z};
          row["relief_carve_mm"] = renderer.relief_depth_rt() * 1e3;
        }
      }
      rows.push_back(std::move(row));
    } else {
      std::cout << fmt::format("  {:>4}  {:>8.3f} {:>8.3f} {:>8.3f}   {:>9.4f} {:>9.4f} {:>9.4f}   {:>7.4f}  {}\n", i, device.x * 1e3,
                               device.y * 1e3, device.z * 1e3, force.x, force.y, force.z, glm::length(force), where);
    }
  }
  if (o.json)
    std::cout << schema::json_text(nlohmann::json{{"ok", true},
                                                  {"scene", scene.name},
                                                  {"device", scene.device},
                                                  {"from_mm", p.from},
                                                  {"to_mm", p.to},
                                                  {"steps", rows},
                                                  {"diagnostics", diagnostics_json(r->diagnostics)}},
                                   2)
              << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli
