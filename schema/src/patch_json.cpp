#include "sandpaper/schema/patch_json.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sandpaper::schema {

std::string display_value(double v, const std::string& unit) {
  std::ostringstream os;
  os.precision(4);
  if (unit == "m") os << v * 1e3 << " mm";
  else if (unit == "rad") os << v * 180.0 / 3.14159265358979323846 << " deg";
  else if (unit == "1") os << v;
  else os << v << " " << unit;
  return os.str();
}

namespace {

float max_abs(const std::vector<float>& v) {
  float m = 0;
  for (float x : v) m = std::max(m, std::abs(x));
  return m;
}

nlohmann::json term_json(const Term& t, bool with_tables) {
  using nlohmann::json;
  if (const auto* s = std::get_if<SpringTerm>(&t))
    return json{{"kind", "spring"}, {"stiffness_N_per_m", s->stiffness_N_per_m}, {"centre_m", {s->centre_m[0], s->centre_m[1]}}};
  if (const auto* d = std::get_if<DamperTerm>(&t)) return json{{"kind", "damper"}, {"damping_Ns_per_m", d->damping_Ns_per_m}};
  if (const auto* g = std::get_if<GratingTerm>(&t)) {
    json j{{"kind", "grating"},
           {"period_m", g->period_m},
           {"orientation_rad", g->orientation_rad},
           {"samples_per_period", g->force_N.size()},
           {"table_max_force_N", max_abs(g->force_N)}};
    if (with_tables) j["force_N"] = g->force_N;
    return j;
  }
  const auto& h = std::get<HeightFieldTerm>(t);
  json j{{"kind", "height_field"},
         {"samples", {h.nx, h.ny}},
         {"origin_m", {h.origin_m[0], h.origin_m[1]}},
         {"spacing_m", {h.spacing_m[0], h.spacing_m[1]}},
         {"repeat", h.repeat}};
  float m = 0;
  for (std::size_t i = 0; i < h.force_x_N.size(); ++i) m = std::max(m, std::hypot(h.force_x_N[i], h.force_y_N[i]));
  j["table_max_force_N"] = m;
  if (with_tables) {
    j["force_x_N"] = h.force_x_N;
    j["force_y_N"] = h.force_y_N;
  }
  return j;
}

}  // namespace

nlohmann::json to_json(const PatchProgram& p, bool with_tables) {
  using nlohmann::json;
  json j;
  j["format_version"] = kPatchFormatVersion;
  j["material"] = p.name;
  j["describes"] = p.describes;
  j["device"] = p.device;
  j["size_m"] = {p.size_m[0], p.size_m[1]};
  j["max_lateral_force_N"] = p.max_lateral_force_N;
  j["roughness"] = p.roughness;
  j["roughness_map"] = p.roughness_map;
  j["warnings"] = json::array();
  for (const auto& w : p.warnings) j["warnings"].push_back({{"code", w.code}, {"message", w.message}});
  j["provenance"] = json::object();
  for (const auto& pv : p.provenance)
    j["provenance"][pv.parameter] = {{"value", pv.value_si}, {"unit", pv.si_unit}, {"display", pv.si_unit.empty() ? pv.stated : display_value(pv.value_si, pv.si_unit)},
                                     {"stated", pv.stated}, {"layer", pv.layer}, {"source", pv.source}};
  j["terms"] = json::array();
  for (const auto& t : p.terms) j["terms"].push_back(term_json(t, with_tables));
  return j;
}

}  // namespace sandpaper::schema
