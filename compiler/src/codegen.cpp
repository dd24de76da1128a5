#include "sandpaper/compiler/codegen.hpp"

#include <cmath>
#include <optional>
#include <sstream>

#include "sandpaper/compiler/laws.hpp"
#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/compiler/textures.hpp"

namespace sandpaper::compiler {
namespace {

std::string num(double v, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

void record(schema::PatchProgram& out, const std::string& parameter, const Param& p, const char* si_unit) {
  out.provenance.push_back({parameter, p.si, si_unit, p.stated, layer_name(p.layer), p.source});
}

// The version-2 grating the thesis' way (3.5.2): the 256 px seed, quantized, repeated per period.
bool generate_seed_grating(const ResolvedGrating& g, int bits, const Param& force, schema::PatchProgram& out) {
  Param sigma = g.smoothing ? *g.smoothing
                            : Param{g.period.si * kSeedSigmaPerPeriod,
                                    "6/256 of the period (thesis 3.5.2 seed, Gaussian kernel 24 of 256 px)",
                                    Layer::Default, "default", {}};
  const double sigma_seed_px = sigma.si / g.period.si * kSeedPixels;
  out.terms.emplace_back(make_seed_grating(g.period.si, g.hill.si, g.orientation.si, sigma_seed_px, bits, force.si));
  record(out, "texture.period", g.period, "m");
  record(out, "texture.hill", g.hill, "1");
  record(out, "texture.orientation", g.orientation, "rad");
  record(out, "texture.smoothing", sigma, "m");
  out.provenance.push_back({"texture.seed_grating", kSeedPixels, "px",
                            "256 px per period, hill " + num(std::round(g.hill.si * kSeedPixels)) + " px, sigma " +
                                num(sigma_seed_px) + " px, gradient h(i+1) - h(i-1) of " + std::to_string(bits) +
                                "-bit heights",
                            "derived", "thesis 3.5.2 seed, Appendix B Waves"});
  return true;
}

void record_pattern(schema::PatchProgram& out, const ResolvedPattern& p, const std::string& summary) {
  out.provenance.push_back({"texture.pattern", 0, "", summary, "physical", p.location.str()});
  record(out, "texture.pixel", p.pixel, "m");
  const auto px = [&](const std::optional<Param>& q, const char* name, const char* unit) {
    if (q) record(out, name, *q, unit);
  };
  px(p.valley, "texture.valley", "m");
  px(p.hill, "texture.hill", "m");
  px(p.offset, "texture.offset", "m");
  px(p.feature, "texture.feature", "m");
  px(p.kernel, "texture.kernel", "px");
  px(p.refilter, "texture.refilter", "px");
  px(p.seed, "texture.seed", "1");
  px(p.count, "texture.count", "1");
}

}  // namespace

bool generate(const ResolvedMaterial& m, const calibration::CalibrationSet& cal,
              const calibration::DeviceCalibration& device, schema::PatchProgram& out, Diagnostics& diags) {
  const auto& map = cal.roughness_map();
  out = {};
  out.name = m.name;
  out.describes = m.describes;
  out.device = device.name;
  out.size_m[0] = m.size_width.si;
  out.size_m[1] = m.size_height.si;
  out.roughness_map = map.id;
  record(out, "patch.width", m.size_width, "m");
  record(out, "patch.height", m.size_height, "m");

  bool has_texture = !std::holds_alternative<std::monostate>(m.texture);
  if (has_texture) {
    // A height map read as a stylus relief (depth + press) has no target: its force is computed
    // from the image, so the field is built first and its maximum takes the target's place.
    const auto* hm = std::get_if<ResolvedHeightmap>(&m.texture);
    std::optional<HeightFieldBuild> field;
    std::optional<Param> computed;
    if (hm && hm->stylus() && !m.max_lateral_force) {
      field = make_height_field(*hm, std::nullopt, diags);
      if (!field) return false;
      computed = Param{field->max_lateral_force_N,
                       "press " + hm->press->stated + " x steepest slope " + num(field->steepest_slope) + " (depth " +
                           hm->depth->stated + ")",
                       Layer::Physical, hm->press->source, hm->press->location};
    }
    if (!m.max_lateral_force && !computed) throw InternalError("codegen: texture without a force after resolution");
    const Param& force = computed ? *computed : *m.max_lateral_force;
    if (force.si > device.max_force_N) {
      double best = map.percept_of(device.max_force_N);
      diags.error("E0310", force.location,
                  "this material asks for " + num(force.si) + " N of lateral force (" + force.stated + "); device '" +
                      device.name + "' reaches " + num(device.max_force_N) + " N at most",
                  computed ? "lower press or depth, or add smoothing: the image's steepest slope times press must stay below " +
                                 num(device.max_force_N) + " N"
                           : "this device reaches roughness " + num(best, 3) + " at most; lower the roughness or amplitude");
      return false;
    }
    record(out, "texture.max_lateral_force", force, "N");
    if (m.roughness) record(out, "texture.roughness_target", *m.roughness, "1");

    const int bits = m.quantize_bits ? static_cast<int>(m.quantize_bits->si) : 0;
    if (m.quantize_bits) record(out, "texture.quantization", *m.quantize_bits, "bit");
    if (const auto* seed = std::get_if<ResolvedGrating>(&m.texture); seed && bits > 0) {
      if (!generate_seed_grating(*seed, bits, force, out)) return false;
    } else if (const auto* pt = std::get_if<ResolvedPattern>(&m.texture)) {
      schema::HeightFieldTerm pattern_field;
      std::string summary;
      if (!make_pattern_field(*pt, m.size_width.si, m.size_height.si, bits, force.si, pattern_field, diags, summary))
        return false;
      out.terms.emplace_back(std::move(pattern_field));
      record_pattern(out, *pt, summary);
    } else if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
      Param sigma = g->smoothing ? *g->smoothing
                                 : Param{g->period.si * kSeedSigmaPerPeriod,
                                         "6/256 of the period (thesis 3.5.2 seed, Gaussian kernel 24 of 256 px)",
                                         Layer::Default, "default", {}};
      // Below 1/512 of the period the walls are steeper than the 1024-sample table can hold.
      if (sigma.si < g->period.si / 512) {
        diags.error("E0304", sigma.location.file ? sigma.location : g->location,
                    "grating smoothing " + num(sigma.si * 1e3) + " mm is too sharp to display: the walls would be vertical",
                    "use a smoothing of at least " + num(g->period.si / 512 * 1e3) + " mm (1/512 of the period)");
        return false;
      }
      out.terms.emplace_back(make_grating(g->period.si, g->hill.si, g->orientation.si, sigma.si, force.si));
      record(out, "texture.period", g->period, "m");
      record(out, "texture.hill", g->hill, "1");
      record(out, "texture.orientation", g->orientation, "rad");
      record(out, "texture.smoothing", sigma, "m");
    } else if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture)) {
      if (!field) field = make_height_field(*h, force.si, diags);
      if (!field) return false;
      out.terms.emplace_back(std::move(field->term));
      out.provenance.push_back({"texture.image", 0, "", h->stated_path + " (" + field->summary + ")", "physical", h->source});
      record(out, "texture.image_width", h->width, "m");
      record(out, "texture.image_height", h->height, "m");
      if (h->smoothing) record(out, "texture.smoothing", *h->smoothing, "m");
      if (h->sampling) record(out, "texture.sampling", *h->sampling, "m");
      if (h->depth) record(out, "texture.depth", *h->depth, "m");
      if (h->press) record(out, "texture.press", *h->press, "N");
    }
    out.max_lateral_force_N = force.si;
    out.roughness = map.percept_of(force.si);
    out.provenance.push_back({"texture.roughness", out.roughness, "1",
                              "(F / " + num(map.reference_si) + " N)^" + num(map.slope, 6), "derived",
                              "calibration " + map.id});
  }
  if (m.spring) {
    out.terms.emplace_back(schema::SpringTerm{m.spring->si, {0, 0}});
    record(out, "spring.stiffness", *m.spring, "N/m");
  }
  if (m.damper) {
    out.terms.emplace_back(schema::DamperTerm{m.damper->si});
    record(out, "damper.damping", *m.damper, "N*s/m");
  }
  generate_percepts(m, out, diags);  // slipperiness's anti-viscous term; perceptual targets (compiler/percepts.hpp)
  return generate_laws(m, device, out, diags);
}

}  // namespace sandpaper::compiler
