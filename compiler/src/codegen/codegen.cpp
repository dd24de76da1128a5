#include "sandpaper/compiler/codegen.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "sandpaper/compiler/laws.hpp"
#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/compiler/textures.hpp"

namespace sandpaper::compiler {
namespace {

// The finest grating period any joystick can render (see generate()).
constexpr double kLeastPeriod_m = 1e-6;

std::string num(double v, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

// `v` (> 0) rounded DOWN to three significant digits: a reachable limit must stay reachable as shown.
std::string num_up(double v) {
  if (!(v > 0)) return num(v);
  const double scale = std::pow(10.0, 2 - std::floor(std::log10(v)));
  return num(std::ceil(v * scale) / scale, 6);
}

std::string num_down(double v) {
  if (!(v > 0)) return num(v);
  const double scale = std::pow(10.0, 2 - std::floor(std::log10(v)));
  return num(std::floor(v * scale) / scale, 6);
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

// The device the program is compiled for: its command scale travels with the program, and the
// provenance names the device file every device-dependent number comes from.
void record_device(schema::PatchProgram& out, const calibration::DeviceCalibration& device) {
  out.command.device_file = device.file;
  out.command.command_unit = device.command_unit;
  out.command.command_max = device.command_max;
  out.command.max_force_N = device.max_force_N;
  out.command.calibrated = device.calibrated();
  for (int a = 0; a < 2; ++a) out.command.newtons_per_command_unit[a] = device.axis_scale(a).step_N(0);
  out.provenance.push_back({"device.max_force", device.max_force_N, "N", device.name + " maximum continuous force",
                            "device", device.file});
  const bool in_newtons = device.command_unit == "N";
  out.provenance.push_back({"device.command_scale", out.command.newtons_per_command_unit[0], "N",
                            in_newtons ? "commanded in newtons"
                                       : num(out.command.newtons_per_command_unit[0], 6) + " N per " + device.command_unit +
                                             " on x, " + num(out.command.newtons_per_command_unit[1], 6) + " N on y" +
                                             (device.calibrated() ? "" : " (UNCALIBRATED: assumed)"),
                            "device", device.file});
}

// The texture's maximum lateral force in the device's command units, rounded as the device rounds.
void record_command(schema::PatchProgram& out, const calibration::DeviceCalibration& device, double force_N) {
  for (int a = 0; a < 2; ++a) out.command.newtons_per_command_unit[a] = device.axis_scale(a).step_N(force_N);
  const double units = device.command_units(0, force_N);
  const double commanded = device.quantize_N(0, force_N);
  std::string stated = device.command_unit == "N"
                           ? "commanded as " + num(commanded, 6) + " N"
                           : num(device.quantized() ? std::round(units) : units, 6) + " " + device.command_unit + " = " +
                                 num(commanded, 6) + " N";
  out.provenance.push_back({"texture.max_force_command", device.quantized() ? std::round(units) : units, "",
                            stated, "device", device.file});
}

// A device too coarse to resolve this force to one JND (thesis 5.4.2) cannot show the roughness
// differences the map promises around it: warn, and say the least force it resolves to a JND.
void check_resolution(const Param& force, const calibration::PsychophysicalMap& map,
                      const calibration::ForceJndData& jnd, const calibration::DeviceCalibration& device, Diagnostics& diags) {
  if (!device.quantized() || !(force.si > 0)) return;
  const double step = std::max(device.force_step_N(0, force.si), device.force_step_N(1, force.si));
  if (step <= jnd.jnd_at(force.si)) return;
  // Least force whose JND is at least one command step: F_min = step / weber.
  const double f_min = step / jnd.weber_fraction;
  diags.warning("W0311", force.location,
                "device '" + device.name + "' commands force in steps of " + num(step * 1e3) + " mN, coarser than one JND (" +
                    num(jnd.weber_fraction * 100, 3) + " %, " + jnd.file + ") of this material's " + num(force.si * 1e3) +
                    " mN: neighbouring roughness values blur together here",
                "this device resolves roughness to one JND from roughness " + num_up(map.percept_of(f_min)) + " (" +
                    num(f_min * 1e3) + " mN) up; ask for that or more");
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
  out.roughness_map_file = map.file;
  record_device(out, device);
  if (!device.calibrated()) {
    // Anchor the warning where the material asks for force: its texture, spring, damper or first law.
    SourceLocation at = m.max_lateral_force ? m.max_lateral_force->location
                        : m.spring          ? m.spring->location
                        : m.damper          ? m.damper->location
                        : !m.laws.empty()   ? m.laws.front().location
                                            : SourceLocation{};
    diags.warning("W0331", at,
                  "device '" + device.name + "' is uncalibrated: its scale of " + num(device.axis_scale(0).step_N(0), 6) +
                      " N per command unit is assumed (" + device.file + "), so the newtons at the hand are not known",
                  "measure it with a force gauge and `sandpaper calibrate device readings.csv --base " + device.file + "`");
  }
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
      const std::string best = num_down(map.percept_of(device.max_force_N));
      diags.error("E0310", force.location,
                  "this material asks for " + num(force.si) + " N of lateral force (" + force.stated + "); device '" +
                      device.name + "' reaches " + num(device.max_force_N) + " N at most, i.e. roughness " + best +
                      " (" + map.id + "; " + device.file + ")",
                  computed ? "lower press or depth, or add smoothing: the image's steepest slope times press must stay below " +
                                 num(device.max_force_N) + " N"
                           : "this device reaches roughness " + best + " at most; ask for that or less, or compile for a stronger device");
      return false;
    }
    check_resolution(force, map, cal.knowledge().force_jnd, device, diags);
    record(out, "texture.max_lateral_force", force, "N");
    if (m.roughness) record(out, "texture.roughness_target", *m.roughness, "1");

    const int bits = m.quantize_bits ? static_cast<int>(m.quantize_bits->si) : 0;
    if (m.quantize_bits) record(out, "texture.quantization", *m.quantize_bits, "bit");
    // A period the device cannot resolve plays as aliased noise, or (a denormal) as a non-finite force
    // that stops the servo at its first tick: two position counts per period at the least, and never
    // under a micrometre, the finest any joystick senses.
    if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
      const double least_m = std::max(kLeastPeriod_m, 2 * device.position_resolution_m);
      if (!(g->period.si >= least_m)) {
        diags.error("E0304", g->period.location.file ? g->period.location : g->location,
                    "grating period " + num(g->period.si * 1e3) + " mm is finer than " + device.name + " can play (" +
                        num(least_m * 1e3) + " mm: two position steps, and at least 1 um)",
                    "give a period of at least " + num(least_m * 1e3) + " mm; the thesis' gratings are 0.7-10 mm (5.4)");
        return false;
      }
    }
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
                              map.provenance()});
    record_command(out, device, force.si);
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
