#include "sandpaper/curation/percepts.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/compiler/recovered_height_field.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::curation {

namespace {

std::string num(double v, int digits = 3) {
  std::ostringstream os;
  os << std::setprecision(digits) << v;
  return os.str();
}

std::string mm(double m) { return num(m * 1000) + " mm"; }

std::string texture_text(const compiler::ResolvedMaterial& m) {
  using namespace compiler;
  if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
    std::string s = "grating period " + mm(g->period.si) + ", hill " + num(g->hill.si * 100) + " %";
    if (g->orientation.si != 0) s += ", orientation " + num(g->orientation.si * 180 / M_PI) + " deg";
    if (g->smoothing) s += ", smoothing " + mm(g->smoothing->si);
    return s;
  }
  if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture)) {
    std::string s = "height map " + h->stated_path + ", " + mm(h->width.si) + " x " + mm(h->height.si);
    if (h->smoothing) s += ", smoothing " + mm(h->smoothing->si);
    if (h->stylus()) s += ", stylus relief " + mm(h->depth->si) + " pressed " + num(h->press->si) + " N";
    return s;
  }
  if (const auto* p = std::get_if<ResolvedPattern>(&m.texture)) {
    std::string s = std::string("pattern ") + pattern_kind_name(p->kind) + ", pixel " + mm(p->pixel.si);
    if (p->valley) s += ", valley " + mm(p->valley->si);
    if (p->hill) s += ", hill " + mm(p->hill->si);
    if (p->feature) s += ", feature " + mm(p->feature->si);
    if (p->kernel) s += ", kernel " + num(p->kernel->si) + " px";
    return s;
  }
  return "";
}

}  // namespace

double spatial_scale_m(const compiler::RecoveredHeightField& t) {
  const std::size_t nx = static_cast<std::size_t>(std::max(t.nx, 0)), ny = static_cast<std::size_t>(std::max(t.ny, 0));
  if (nx < 4 || ny < 4 || t.h_m.size() != nx * ny || !(t.spacing_m[0] > 0) || !(t.spacing_m[1] > 0)) return 0;
  double mean = 0;
  for (const double v : t.h_m) mean += v;
  mean /= static_cast<double>(t.h_m.size());
  // The heights' autocorrelation (mean removed) at a lag of d samples along one axis, over the
  // cells that have a neighbour there.
  const auto correlation = [&](std::size_t d, bool along_x) {
    double c = 0, c0 = 0;
    const std::size_t ex = along_x ? nx - d : nx, ey = along_x ? ny : ny - d;
    for (std::size_t y = 0; y < ey; ++y)
      for (std::size_t x = 0; x < ex; ++x) {
        const std::size_t i = y * nx + x, j = along_x ? i + d : i + d * nx;
        c += (t.h_m[i] - mean) * (t.h_m[j] - mean);
        c0 += (t.h_m[i] - mean) * (t.h_m[i] - mean);
      }
    return c0 > 0 ? c / c0 : 0.0;
  };
  double best = 0;
  for (const bool along_x : {true, false}) {
    const std::size_t n = along_x ? nx : ny;
    double previous = 1;
    for (std::size_t d = 1; d <= n / 2; ++d) {
      const double c = correlation(d, along_x);
      if (c <= 0) {
        // The first zero, between d - 1 and d, interpolated.
        const double zero = (static_cast<double>(d) - c / (c - previous)) * t.spacing_m[along_x ? 0 : 1];
        if (best == 0 || 4 * zero < best) best = 4 * zero;
        break;
      }
      previous = c;
    }
  }
  return best;
}

Percepts percepts_of(const compiler::ResolvedMaterial& m, const schema::PatchProgram& p, const calibration::CalibrationSet& cal) {
  Percepts r;
  r.max_lateral_force_N = p.max_lateral_force_N;
  r.roughness = p.max_lateral_force_N > 0 ? p.roughness : 0;
  const auto k = compiler::assess_knowledge(m, p, cal);
  if (p.max_lateral_force_N > 0) {
    r.texture_kind = k.texture.kind;
    r.period_m = k.texture.period_m;
    // A photograph has no period but has a scale: its height field's, so that `near` tells a
    // close-up of gravel from a wide view by size as well as by force.
    if (r.texture_kind == "image" && r.period_m <= 0) {
      std::string why;
      if (const auto heights = compiler::recover_height_field(p, &m, why)) r.period_m = spatial_scale_m(*heights);
    }
  }
  if (k.period_class && k.period_class->hit.group) r.period_class = k.period_class->hit.group->id;
  if (k.character && k.character->hit.group) r.character = k.character->hit.group->id;
  const auto j = schema::to_json(p);
  for (const auto& t : j["terms"]) {
    const auto kind = t.value("kind", std::string("?"));
    r.terms += (r.terms.empty() ? "" : "+") + kind;
    if (kind == "grating" || kind == "height_field") continue;
    for (const auto& [field, v] : t.items())
      if (v.is_number()) r.term_params.emplace_back(kind + "." + field, v.get<double>());
  }
  for (const auto& t : m.percepts) r.others.emplace_back(t.percept, t.value.si);
  return r;
}

std::string physical_summary(const compiler::ResolvedMaterial& m, const schema::PatchProgram& p) {
  std::vector<std::string> parts;
  if (auto t = texture_text(m); !t.empty()) parts.push_back(t);
  if (p.max_lateral_force_N > 0) parts.push_back("maximum lateral force " + num(p.max_lateral_force_N) + " N");
  if (m.quantize_bits) parts.push_back("heights quantized to " + num(m.quantize_bits->si) + " bits");
  if (m.spring) parts.push_back("spring " + num(m.spring->si) + " N/m");
  if (m.damper) parts.push_back("damper " + num(m.damper->si) + " N*s/m");
  if (m.friction_coefficient) parts.push_back("friction coefficient " + num(m.friction_coefficient->si) + ", pressed with 1 N");
  for (const auto& l : m.laws) parts.push_back(l.text.empty() ? std::string(l.physics ? "physics " : "force ") + l.name : l.text);
  if (m.energy_budget) parts.push_back("energy budget " + num(m.energy_budget->si) + " J");
  parts.push_back("patch " + mm(p.size_m[0]) + " x " + mm(p.size_m[1]));
  std::string s;
  for (const auto& x : parts) s += (s.empty() ? "" : "; ") + x;
  return s;
}

bool indistinguishable(const Percepts& a, const Percepts& b, const calibration::ForceJndData& jnd, double* steps) {
  if (!a.has_texture() || !b.has_texture()) return false;
  if (a.texture_kind != b.texture_kind || a.terms != b.terms) return false;
  // Kinds without a period never (image textures have a spatial scale, not a period): their pictures differ.
  if (a.period_m <= 0 || b.period_m <= 0 || a.texture_kind == "image") return false;
  if (a.period_class != b.period_class) return false;
  const double s = jnd.steps_between(a.max_lateral_force_N, b.max_lateral_force_N);
  if (steps) *steps = s;
  return std::abs(s) < 1.0;
}

}  // namespace sandpaper::curation
