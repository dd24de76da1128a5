#pragma once
// What `sandpaper run SCENE` and `sandpaper-play SCENE.sp3` print of a scene played on sim3d: one
// report for both programs (docs/SHAPES.md, "Running a scene").
#include <iostream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/shapes/scene_play.hpp"

namespace sandpaper::cli {

// Prints the run (text, or one JSON object with `json`; `extra` is merged into it) and returns
// whether it passed the energy and stability check.
inline bool report_scene_run(const shapes::SceneProgram& scene, const std::string& device, const shapes::ScenePlay& play,
                             double speed_mm_s, bool json, nlohmann::json extra = nlohmann::json::object()) {
  const shapes::SceneServoSummary& s = play.summary;
  const bool passed = s.passed();
  if (json) {
    nlohmann::json strokes = nlohmann::json::array();
    for (const auto& st : play.strokes.strokes)
      strokes.push_back({{"object", st.object}, {"point_mm", {st.point_m.x * 1e3, st.point_m.y * 1e3, st.point_m.z * 1e3}}});
    nlohmann::json j{{"ok", passed},
                     {"scene", scene.name},
                     {"device", device},
                     {"stop", shapes::scene_stop_name(s.stop)},
                     {"ticks", s.ticks},
                     {"rate_hz", s.rate_hz},
                     {"duration_s", s.duration_s},
                     {"speed_mm_s", speed_mm_s},
                     {"ticks_in_contact", s.ticks_in_contact},
                     {"clamped_ticks", s.clamped_ticks},
                     {"peak_force_N", s.peak_force_N},
                     {"max_speed_m_s", s.max_speed_m_s},
                     {"strokes", strokes},
                     {"not_reached", play.strokes.not_reached},
                     {"energy",
                      {{"work_on_handle_J", s.energy.work_on_handle_J},
                       {"hold_work_J", s.energy.hold_work_J},
                       {"environment_work_J", s.energy.environment_work_J},
                       {"energy_gained_J", s.energy.energy_gained_J},
                       {"tolerance_J", s.energy.tolerance_J},
                       {"no_energy_gained", s.energy.no_energy_gained()}}}};
    if (s.hand)
      j["hand"] = {{"active_work_J", s.hand->active_work_J},
                   {"hand_dissipated_in_contact_J", s.hand->hand_dissipated_in_contact_J},
                   {"active_paid", s.hand->active_paid},
                   {"max_excursion_m", s.hand->max_excursion_m},
                   {"excursion_bound_m", s.hand->excursion_bound_m},
                   {"stable", s.hand->stable()}};
    j.update(extra);
    std::cout << schema::json_text(j, 2) << "\n";
    return passed;
  }
  std::cout << fmt::format("scene \"{}\" on {} at {:g} Hz for {:g} s (simulated time): {} ticks, {} in contact, stop {}\n",
                           scene.name, device, s.rate_hz, s.duration_s, s.ticks, s.ticks_in_contact,
                           shapes::scene_stop_name(s.stop));
  std::cout << fmt::format("  the hand presses onto each object from above and strokes 40 mm across it at {:g} mm/s:", speed_mm_s);
  for (const auto& st : play.strokes.strokes)
    std::cout << fmt::format(" \"{}\" at ({:.1f}, {:.1f}, {:.1f}) mm;", st.object, st.point_m.x * 1e3 + 0.0,
                             st.point_m.y * 1e3 + 0.0, st.point_m.z * 1e3 + 0.0);
  std::cout << "\n";
  for (const auto& n : play.strokes.not_reached)
    std::cout << "  not stroked: \"" << n << "\" (no surface of it faces up to a hand from above)\n";
  std::cout << fmt::format("  peak force {:.3f} N, {} ticks clamped at the device's maximum, fastest handle {:.3f} m/s\n",
                           s.peak_force_N, s.clamped_ticks, s.max_speed_m_s);
  std::cout << fmt::format("  energy: the scene's own work on the handle {:.4g} mJ, largest gain at a relaxed tick {:.3g} mJ "
                           "(tolerance {:.3g} mJ): {}\n",
                           s.energy.environment_work_J * 1e3, s.energy.energy_gained_J * 1e3, s.energy.tolerance_J * 1e3,
                           s.energy.no_energy_gained() ? "no energy gained" : "ENERGY GAINED");
  if (s.hand)
    std::cout << fmt::format("  hand: the hold's and texture's active work {:.3g} mJ against {:.3g} mJ its damper took in "
                             "contact ({}); excursion {:.2f} of {:.2f} mm allowed; {}\n",
                             s.hand->active_work_J * 1e3, s.hand->hand_dissipated_in_contact_J * 1e3,
                             s.hand->active_paid ? "paid" : "NOT PAID", s.hand->max_excursion_m * 1e3,
                             s.hand->excursion_bound_m * 1e3, s.hand->stable() ? "stable" : "UNSTABLE");
  std::cout << (passed ? "  passed: no energy gained, stable\n" : "  FAILED the energy and stability check\n");
  return passed;
}

}  // namespace sandpaper::cli
