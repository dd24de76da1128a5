// The perceptual words besides roughness: the word table, and their codegen and explain text.
#include "sandpaper/compiler/percepts.hpp"

#include <cmath>
#include <sstream>

#include "sandpaper/schema/force_laws.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler {

const std::vector<PerceptWord>& percept_words() {
  // Aliases share a percept and so a map: stickiness is viscosity; springiness is softness (the same
  // continuum, not its inverse: docs/CALIBRATION.md, "Provisional maps").
  static const std::vector<PerceptWord> words{
      {"viscosity", "viscosity", "damper.damping", "the damping", "damping b", "N*s/m", "damper 2 N*s/m", nullptr},
      {"stickiness", "viscosity", "damper.damping", "the damping", "damping b", "N*s/m", "damper 2 N*s/m", nullptr},
      {"slipperiness", "slipperiness", "friction.coefficient", "the friction coefficient", "friction coefficient mu", "1",
       "physics Friction static 0.7 kinetic 0.7 press 1 N", "would be infinitely sticky"},
      {"softness", "softness", "spring.stiffness", "the spring stiffness", "spring stiffness k", "N/m", "spring 50 N/m",
       "would be an infinitely stiff spring"},
      {"springiness", "softness", "spring.stiffness", "the spring stiffness", "spring stiffness k", "N/m",
       "spring 50 N/m", "would be an infinitely stiff spring"},
      {"bumpiness", "bumpiness", "texture.period", "the texture", "grating period P", "m", "grating period 3.6 mm",
       "would be a grating of period 0"},
  };
  return words;
}

const PerceptWord* find_percept_word(std::string_view word) {
  for (const auto& w : percept_words())
    if (word == w.word) return &w;
  return nullptr;
}

std::optional<calibration::Range> ratio_domain(const calibration::PsychophysicalMap& map) {
  const std::string& p = map.ratio_predictor;
  if (p == "force") return map.force;
  if (p == "period") return map.period;
  if (p == "feature") return map.feature;
  if (p == "damping") return map.damping;
  if (p == "stiffness") return map.stiffness;
  if (p == "friction") return map.friction;
  return std::nullopt;
}

namespace {

constexpr double kSlipperinessPress_N = 1.0;

// "damper.damping" -> "damper.viscosity_target"
std::string target_parameter(const PerceptTarget& t) {
  return t.parameter.substr(0, t.parameter.find('.')) + "." + t.percept + "_target";
}

}  // namespace

void generate_percepts(const ResolvedMaterial& m, schema::PatchProgram& out, Diagnostics& diags) {
  if (m.friction_coefficient) {
    // Coulomb friction with one coefficient for holding and sliding (no stick-slip jerk: the
    // slipperiness maps were scaled on sliding), the hand taken to press with 1 N as the library's
    // friction materials do, and Friction's own presliding stiffness and stick band.
    const Param& mu = *m.friction_coefficient;
    const auto* law = schema::find_law(schema::LawFamily::Physics, "Friction");
    const auto param = [&](std::string_view name) { return schema::find_param(*law, name)->default_si; };
    out.terms.emplace_back(schema::FrictionTerm{mu.si, mu.si, kSlipperinessPress_N, param("stiffness"), param("stick_speed")});
    out.provenance.push_back({"friction.coefficient", mu.si, "1", mu.stated, layer_name(mu.layer), mu.source});
    out.provenance.push_back({"friction.press", kSlipperinessPress_N, "N", "1 N", "default",
                              "the hand taken to press with 1 N (docs/FORCE_LAWS.md, Friction)"});
  }
  for (const auto& t : m.percepts) {
    const std::string via = t.map_id + " (" + t.map_file + ")";
    out.provenance.push_back({target_parameter(t), t.value.si, "1", t.value.stated, layer_name(t.value.layer),
                              t.value.source + " via " + via});
    if (t.real_material)
      diags.warning("W0321", t.value.location,
                    "`" + t.value.stated + "` compiles through " + via + ", whose source felt real materials, not a "
                        "force-feedback device: on a joystick the " + t.percept + " extrapolates",
                    "treat the " + t.percept + " as approximate until a lab calibrates it on its device "
                    "(docs/EXPERIMENTS.md; `sandpaper experiment analyse --map-out`)");
    if (!t.provisional) continue;
    const std::string inherited = t.value.layer == Layer::Representative ? ", inherited as " + t.value.source + "," : "";
    diags.warning("W0320", t.value.location,
                  "`" + t.value.stated + "`" + inherited + " compiles through the provisional map " + via +
                      ": designed, with no published or measured source",
                  "treat the result as a first guess; the map's [source] says where its numbers come from "
                  "(docs/CALIBRATION.md, \"Maps beyond roughness\")");
  }
}

std::string explain_percepts(const ResolvedMaterial& m, const calibration::CalibrationSet& cal, bool inline_first) {
  std::ostringstream os;
  bool first = true;
  for (const auto& t : m.percepts) {
    const PerceptWord* w = find_percept_word(t.word);
    const calibration::PsychophysicalMap* map = cal.find_map(t.map_id);
    if (!(first && inline_first)) os << "                  ";
    first = false;
    os << t.value.stated << " [" << layer_name(t.value.layer) << ", " << t.value.source << "]\n";
    if (!w || !map) continue;
    double value_si = map->value_for(t.value.si);
    os << "                  -> " << w->what << " = " << schema::display_value(map->reference_si, w->si_unit) << " * "
       << t.percept << "^(1/" << schema::display_value(map->slope, "1") << ") = " << schema::display_value(value_si, w->si_unit) << "  ("
       << (t.provisional ? "PROVISIONAL map " : "calibration ") << map->id << ", " << map->file << ")\n";
    os << "                     source: " << map->source() << "\n";
    os << "                     domain: " << domain_text(*map, w->si_unit) << "\n";
    if (map->weber_fraction) {
      // One JND of the physical quantity moves the percept by the factor (1 + w)^|slope|.
      const double step = std::pow(1 + *map->weber_fraction, std::abs(map->slope)) - 1;
      os << "                     JND: " << schema::display_value(*map->weber_fraction * 100, "1") << " % of the "
         << w->what << " = " << schema::display_value(step * 100, "1") << " % of the " << t.percept << " ("
         << map->jnd_source << ")\n";
    }
  }
  return os.str();
}

std::string domain_text(const calibration::PsychophysicalMap& map, const char* si_unit) {
  std::string out;
  if (const auto r = ratio_domain(map))
    out = schema::display_value(r->min, si_unit) + " to " + schema::display_value(r->max, si_unit) + "; ";
  out += map.apparatus.empty() ? std::string("apparatus not stated") : map.apparatus;
  if (!map.effector.empty()) out += ", " + map.effector;
  return out;
}

nlohmann::json percepts_json(const ResolvedMaterial& m, const calibration::CalibrationSet& cal) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& t : m.percepts) {
    const PerceptWord* w = find_percept_word(t.word);
    const calibration::PsychophysicalMap* map = cal.find_map(t.map_id);
    if (!w || !map) continue;
    nlohmann::json domain = nlohmann::json::object();
    if (const auto r = ratio_domain(*map)) domain[map->ratio_predictor] = {r->min, r->max};
    domain["unit"] = w->si_unit;
    domain["apparatus"] = map->apparatus;
    domain["effector"] = map->effector;
    domain["device"] = map->domain_device;
    out.push_back({{"word", t.word},
                   {"percept", t.percept},
                   {"value", t.value.si},
                   {"stated", t.value.stated},
                   {"parameter", t.parameter},
                   {"parameter_value", map->value_for(t.value.si)},
                   {"parameter_unit", w->si_unit},
                   {"map", {{"id", map->id},
                            {"file", map->file},
                            {"status", map->provisional ? "provisional" : "measured"},
                            {"slope", map->slope},
                            {"reference", map->reference_si},
                            {"reference_unit", w->si_unit},
                            {"citation", map->citation},
                            {"where", map->where},
                            {"domain", domain},
                            {"weber_fraction", map->weber_fraction ? nlohmann::json(*map->weber_fraction) : nlohmann::json(nullptr)},
                            {"jnd_source", map->jnd_source}}}});
  }
  return out;
}

}  // namespace sandpaper::compiler
