// The perceptual words besides roughness: the word table, and their codegen and explain text.
#include "sandpaper/compiler/percepts.hpp"

#include <sstream>

#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler {

const std::vector<PerceptWord>& percept_words() {
  // Aliases share a percept and so a map: stickiness is viscosity; springiness is softness (the same
  // continuum, not its inverse: docs/CALIBRATION.md, "Provisional maps").
  static const std::vector<PerceptWord> words{
      {"viscosity", "viscosity", "damper.damping", "the damping", "damping b", "N*s/m", "damper 2 N*s/m", nullptr},
      {"stickiness", "viscosity", "damper.damping", "the damping", "damping b", "N*s/m", "damper 2 N*s/m", nullptr},
      {"slipperiness", "slipperiness", "antiviscous.damping", "the anti-viscous damping", "anti-viscous gain b",
       "N*s/m", "force AntiViscous damping 1 N*s/m", nullptr},
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
  return std::nullopt;
}

namespace {

// "damper.damping" -> "damper.viscosity_target"
std::string target_parameter(const PerceptTarget& t) {
  return t.parameter.substr(0, t.parameter.find('.')) + "." + t.percept + "_target";
}

}  // namespace

void generate_percepts(const ResolvedMaterial& m, schema::PatchProgram& out, Diagnostics& diags) {
  if (m.antiviscous) {
    const Param& b = *m.antiviscous;
    out.terms.emplace_back(schema::DamperTerm{-b.si});
    out.provenance.push_back({"antiviscous.damping", b.si, "N*s/m", b.stated, layer_name(b.layer), b.source});
    if (b.si > 0)
      diags.warning("W0306", b.location,
                    "`" + b.stated + "` compiles to anti-viscous damping F = +b v (Appendix B AntiViscous, the thesis' "
                    "Slick), which is not passive: it can put energy into the hand",
                    "the runtime bounds the energy it injects: `energy budget <J> refill <W>` sets the bound "
                    "(default 50 mJ, refill 10 mW)");
  }
  for (const auto& t : m.percepts) {
    const std::string via = t.map_id + " (" + t.map_file + ")";
    out.provenance.push_back({target_parameter(t), t.value.si, "1", t.value.stated, layer_name(t.value.layer),
                              t.value.source + " via " + via});
    if (!t.provisional) continue;
    const std::string inherited = t.value.layer == Layer::Representative ? ", inherited as " + t.value.source + "," : "";
    diags.warning("W0320", t.value.location,
                  "`" + t.value.stated + "`" + inherited + " compiles through the provisional map " + via +
                      ": not yet measured on a force-feedback joystick",
                  "treat the result as a first guess; the map's [source] says where its numbers come from "
                  "(docs/CALIBRATION.md, \"Provisional maps\")");
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
  }
  return os.str();
}

}  // namespace sandpaper::compiler
