#include "sandpaper/schema/patch_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <variant>

namespace sandpaper::schema {

std::string display_value(double v, const std::string& unit) {
  std::ostringstream os;
  os.precision(4);
  if (unit == "m") os << v * 1e3 << " mm";
  else if (unit == "rad") os << v * 180.0 / 3.14159265358979323846 << " deg";
  else if (unit == "m/s") os << v * 1e3 << " mm/s";
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

nlohmann::json pair(const double (&v)[2]) { return nlohmann::json::array({v[0], v[1]}); }

const char* shape_name(PeriodicShape shape) {
  switch (shape) {
    case PeriodicShape::Sine: return "sine";
    case PeriodicShape::Sawtooth: return "sawtooth";
    case PeriodicShape::Triangle: return "triangle";
  }
  return "unknown";
}

nlohmann::json term_json(const Term& t, bool with_tables) {
  using nlohmann::json;
  if (const auto* s = std::get_if<SpringTerm>(&t))
    return json{{"kind", "spring"}, {"stiffness_N_per_m", s->stiffness_N_per_m}, {"centre_m", pair(s->centre_m)}};
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
  if (const auto* h = std::get_if<HeightFieldTerm>(&t)) {
    json j{{"kind", "height_field"},
           {"samples", {h->nx, h->ny}},
           {"origin_m", pair(h->origin_m)},
           {"spacing_m", pair(h->spacing_m)},
           {"repeat", h->repeat}};
    float m = 0;
    for (std::size_t i = 0; i < h->force_x_N.size() && i < h->force_y_N.size(); ++i)
      m = std::max(m, std::hypot(h->force_x_N[i], h->force_y_N[i]));
    j["table_max_force_N"] = m;
    if (with_tables) {
      j["force_x_N"] = h->force_x_N;
      j["force_y_N"] = h->force_y_N;
    }
    return j;
  }
  if (const auto* c = std::get_if<ConstantForceTerm>(&t)) return json{{"kind", "constant_force"}, {"force_N", pair(c->force_N)}};
  if (const auto* n = std::get_if<NapTerm>(&t)) return json{{"kind", "nap"}, {"damping_Ns_per_m", n->damping_Ns_per_m}};
  if (const auto* p = std::get_if<PeriodicTerm>(&t))
    return json{{"kind", "periodic"}, {"shape", shape_name(p->shape)}, {"amplitude_N", p->amplitude_N},
                {"period_m", p->period_m}, {"on_x", p->on_x}, {"on_y", p->on_y}};
  if (const auto* r = std::get_if<RidgeTerm>(&t))
    return json{{"kind", "ridge"}, {"stiffness_N_per_m", r->stiffness_N_per_m}, {"wavelength_m", r->wavelength_m},
                {"ridge_width_m", r->ridge_width_m}};
  if (const auto* b = std::get_if<BowlTerm>(&t))
    return json{{"kind", "bowl"}, {"stiffness_N_per_m", b->stiffness_N_per_m}, {"radius_m", b->radius_m}};
  if (const auto* f = std::get_if<LinearFieldTerm>(&t))
    return json{{"kind", "linear_field"}, {"radial_N_per_m", f->radial_N_per_m}, {"tangential_N_per_m", f->tangential_N_per_m}};
  if (const auto* l = std::get_if<LinearSpringTerm>(&t))
    return json{{"kind", "linear_spring"}, {"stiffness_N_per_m", l->stiffness_N_per_m},
                {"orientation_rad", l->orientation_rad}, {"centre_m", pair(l->centre_m)}};
  if (const auto* m = std::get_if<MinusTerm>(&t))
    return json{{"kind", "minus"}, {"stiffness_N_per_m", m->stiffness_N_per_m}, {"lead_s", m->lead_s}};
  if (const auto* f = std::get_if<FrictionTerm>(&t))
    return json{{"kind", "friction"}, {"static_coefficient", f->static_coefficient}, {"kinetic_coefficient", f->kinetic_coefficient},
                {"press_N", f->press_N}, {"stiffness_N_per_m", f->stiffness_N_per_m}, {"stick_speed_m_s", f->stick_speed_m_s}};
  if (const auto* f = std::get_if<FollowerSpringTerm>(&t))
    return json{{"kind", "follower_spring"}, {"stiffness_N_per_m", f->stiffness_N_per_m}, {"lag_s", f->lag_s}};
  if (const auto* m = std::get_if<PointMassesTerm>(&t)) {
    // Only the masses in use: one entry per mass (and per link, link i ending at mass i).
    json masses = json::array(), stiffness = json::array(), damping = json::array();
    for (std::uint32_t i = 0; i < m->count && i < 2; ++i) {
      masses.push_back(m->mass_kg[i]);
      stiffness.push_back(m->stiffness_N_per_m[i]);
      damping.push_back(m->damping_Ns_per_m[i]);
    }
    return json{{"kind", "point_masses"}, {"count", m->count}, {"mass_kg", masses}, {"stiffness_N_per_m", stiffness},
                {"damping_Ns_per_m", damping}, {"ground_damping_Ns_per_m", m->ground_damping_Ns_per_m},
                {"gravity_m_s2", pair(m->gravity_m_s2)}};
  }
  const auto& a = std::get<AttractorTerm>(t);
  return json{{"kind", "attractor"}, {"stiffness_N_per_m", a.stiffness_N_per_m}, {"radius_m", a.radius_m},
              {"period_s", a.period_s}, {"swirl", a.swirl}, {"centre_m", pair(a.centre_m)}};
}

nlohmann::json term_entry(const Term& t, bool with_tables) {
  nlohmann::json j = term_json(t, with_tables);
  j["passive"] = is_passive(t);
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
  j["roughness_map_file"] = p.roughness_map_file;
  j["device_file"] = p.command.device_file;
  const auto& c = p.command;
  j["command"] = {{"unit", c.command_unit},
                  {"newtons_per_command_unit", {c.newtons_per_command_unit[0], c.newtons_per_command_unit[1]}},
                  {"command_max", c.command_max},
                  {"max_force_N", c.max_force_N},
                  {"calibrated", c.calibrated}};
  // The texture's maximum lateral force as each axis would command it, rounded as a quantized device rounds.
  auto commands = [&](int a) {
    double u = p.max_lateral_force_N / c.newtons_per_command_unit[a];
    return c.command_max > 0 ? std::round(u) : u;
  };
  j["max_lateral_force_command_units"] = {commands(0), commands(1)};
  j["energy_budget_J"] = p.energy_budget_J;
  j["energy_refill_W"] = p.energy_refill_W;
  j["warnings"] = json::array();
  for (const auto& w : p.warnings) j["warnings"].push_back({{"code", w.code}, {"message", w.message}});
  j["provenance"] = json::object();
  for (const auto& pv : p.provenance)
    j["provenance"][pv.parameter] = {{"value", pv.value_si}, {"unit", pv.si_unit}, {"display", pv.si_unit.empty() ? pv.stated : display_value(pv.value_si, pv.si_unit)},
                                     {"stated", pv.stated}, {"layer", pv.layer}, {"source", pv.source}};
  j["terms"] = json::array();
  for (const auto& t : p.terms) j["terms"].push_back(term_entry(t, with_tables));
  return j;
}

}  // namespace sandpaper::schema
