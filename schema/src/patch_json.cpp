#include "sandpaper/schema/patch_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <type_traits>
#include <variant>

#include "sandpaper/schema/no_coverage.hpp"
#include "sandpaper/schema/term_kinds.hpp"

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

std::string roughness_text(double r) {
  std::ostringstream os;
  os.precision(3);
  os << r;
  return os.str();
}

namespace {

// Per-sample loops, uninstrumented in the fuzzing build (no_coverage.hpp).
SANDPAPER_NO_COVERAGE float max_abs(const std::vector<float>& v) {
  float m = 0;
  for (float x : v) m = std::max(m, std::abs(x));
  return m;
}

// The largest |(x, y)| over the first n pairs.
SANDPAPER_NO_COVERAGE float largest_magnitude(const float* x, const float* y, std::size_t n) {
  float m = 0;
  for (std::size_t i = 0; i < n; ++i) m = std::max(m, std::hypot(x[i], y[i]));
  return m;
}

nlohmann::json pair(const double (&v)[2]) { return nlohmann::json::array({v[0], v[1]}); }

// A listed field's JSON value, by its member's type (docs/PATCH_FORMAT.md, "JSON").
template <class M>
nlohmann::json value_json(const M& v) {
  if constexpr (std::is_same_v<M, double[2]>) {
    return pair(v);
  } else if constexpr (std::is_enum_v<M>) {
    const auto& names = terms::EnumNames<M>::names;
    const auto i = static_cast<std::size_t>(v);
    return i < names.size() ? std::string(names[i]) : std::string("unknown");
  } else {
    return v;
  }
}

nlohmann::json body_json(const GratingTerm& g, bool with_tables) {
  nlohmann::json j{{"period_m", g.period_m},
                   {"orientation_rad", g.orientation_rad},
                   {"samples_per_period", g.force_N.size()},
                   {"table_max_force_N", max_abs(g.force_N)}};
  if (with_tables) j["force_N"] = g.force_N;
  return j;
}

nlohmann::json body_json(const HeightFieldTerm& h, bool with_tables) {
  nlohmann::json j{{"samples", {h.nx, h.ny}}, {"origin_m", pair(h.origin_m)}, {"spacing_m", pair(h.spacing_m)}, {"repeat", h.repeat}};
  j["table_max_force_N"] =
      largest_magnitude(h.force_x_N.data(), h.force_y_N.data(), std::min(h.force_x_N.size(), h.force_y_N.size()));
  if (with_tables) {
    j["force_x_N"] = h.force_x_N;
    j["force_y_N"] = h.force_y_N;
  }
  return j;
}

// Only the masses in use: one entry per mass (and per link, link i ending at mass i).
nlohmann::json body_json(const PointMassesTerm& m, bool) {
  using nlohmann::json;
  json masses = json::array(), stiffness = json::array(), damping = json::array();
  for (std::uint32_t i = 0; i < m.count && i < 2; ++i) {
    masses.push_back(m.mass_kg[i]);
    stiffness.push_back(m.stiffness_N_per_m[i]);
    damping.push_back(m.damping_Ns_per_m[i]);
  }
  return json{{"count", m.count}, {"mass_kg", masses}, {"stiffness_N_per_m", stiffness}, {"damping_Ns_per_m", damping},
              {"ground_damping_Ns_per_m", m.ground_damping_Ns_per_m}, {"gravity_m_s2", pair(m.gravity_m_s2)}};
}

template <terms::Listed T>
nlohmann::json body_json(const T& term, bool) {
  nlohmann::json j = nlohmann::json::object();
  terms::for_each_field<T>([&](const auto& f) { j[std::string(f.json)] = value_json(term.*(f.member)); });
  return j;
}

nlohmann::json term_json(const Term& t, bool with_tables) {
  return std::visit(
      [&]<class T>(const T& term) {
        nlohmann::json j = body_json(term, with_tables);
        j["kind"] = std::string(terms::Kind<T>::json);
        return j;
      },
      t);
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
  // Compiled values: what a run feels is reported apart, as felt_... (docs/PATCH_FORMAT.md).
  j["compiled_max_lateral_force_N"] = p.max_lateral_force_N;
  j["compiled_roughness"] = p.roughness;
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
  j["compiled_max_lateral_force_command_units"] = {commands(0), commands(1)};
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
