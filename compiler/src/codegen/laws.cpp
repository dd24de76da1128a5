// Codegen for `force` and `physics` statements: Sandpaper's force laws (Appendix B Texture menu,
// thesis 3.2.2 dynamic modules) become patch-program terms, in the order written.
#include "sandpaper/compiler/laws.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "sandpaper/schema/force_laws.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::compiler {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2, ISO 80000-4; the Brick hangs toward -y

// Energy bound defaults for non-passive laws (docs/RUNTIME.md, "Energy bound"). Refill 10 mW: what
// a hand moving at 5 cm/s dissipates with a damping of 4 N*s/m, inside the few N*s/m measured for
// the human hand at rest posture (Tsuji, Morasso, Goto and Ito 1995, Biol. Cybern. 72). Budget
// 50 mJ: the kinetic energy of a 1 kg hand and handle at 0.32 m/s.
constexpr double kDefaultEnergyBudget_J = 0.05;
constexpr double kDefaultEnergyRefill_W = 0.01;

std::string num(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

double si(const ResolvedLaw& law, const char* name) {
  const Param* p = law.find(name);
  if (!p) throw InternalError("laws: " + law.name + " has no resolved parameter '" + name + "'");
  return p->si;
}

schema::PeriodicTerm periodic(const ResolvedLaw& law, schema::PeriodicShape shape) {
  schema::PeriodicTerm t;
  t.shape = shape;
  t.amplitude_N = si(law, "amplitude");
  t.period_m = si(law, "period");
  t.on_x = (law.axes & 1) != 0;
  t.on_y = (law.axes & 2) != 0;
  return t;
}

// The term a law compiles to; nullopt for the laws that exert no force (Nothing, Null).
std::optional<schema::Term> term_of(const ResolvedLaw& l) {
  const std::string& n = l.name;
  if (n == "Nothing" || n == "Null") return std::nullopt;
  if (n == "Spring" || n == "RadialSpring") return schema::SpringTerm{si(l, "stiffness"), {0, 0}};
  if (n == "Bump") return schema::LinearFieldTerm{si(l, "stiffness"), 0};
  if (n == "Viscous") return schema::DamperTerm{si(l, "damping")};
  if (n == "AntiViscous") return schema::DamperTerm{-si(l, "damping")};
  if (n == "ATNSpring") return schema::FollowerSpringTerm{si(l, "stiffness"), si(l, "lag")};
  if (n == "Nap") return schema::NapTerm{si(l, "damping")};
  if (n == "Bowl") return schema::BowlTerm{si(l, "stiffness"), si(l, "radius")};
  if (n == "Wave") return periodic(l, schema::PeriodicShape::Sine);
  if (n == "Cusp") return periodic(l, schema::PeriodicShape::Sawtooth);
  if (n == "Triangle") return periodic(l, schema::PeriodicShape::Triangle);
  if (n == "Const") return schema::ConstantForceTerm{{si(l, "x"), si(l, "y")}};
  if (n == "Ridge") return schema::RidgeTerm{si(l, "stiffness"), si(l, "wavelength"), si(l, "width")};
  if (n == "Minus") return schema::MinusTerm{si(l, "stiffness"), si(l, "lead")};
  if (n == "Circle") return schema::LinearFieldTerm{0, si(l, "stiffness")};
  if (n == "Buckle") return schema::LinearFieldTerm{si(l, "radial"), si(l, "tangential")};
  if (n == "LinearSpring") return schema::LinearSpringTerm{si(l, "stiffness"), si(l, "orientation"), {0, 0}};
  if (n == "Friction")
    return schema::FrictionTerm{si(l, "static"), si(l, "kinetic"), si(l, "press"), si(l, "stiffness"), si(l, "stick_speed")};
  if (n == "NapFriction")
    return schema::NapFrictionTerm{si(l, "static"),   si(l, "kinetic"),   si(l, "against_static"), si(l, "against_kinetic"),
                                   si(l, "press"),    si(l, "stiffness"), si(l, "stick_speed"),    si(l, "nap")};
  if (n == "Attractor")
    return schema::AttractorTerm{si(l, "stiffness"), si(l, "radius"), si(l, "period"), si(l, "swirl"), {0, 0}};
  if (n == "Mass" || n == "Brick" || n == "TwoMasses") {
    schema::PointMassesTerm t;
    t.count = n == "TwoMasses" ? 2 : 1;
    t.mass_kg[0] = si(l, "mass");
    t.stiffness_N_per_m[0] = si(l, "stiffness");
    t.damping_Ns_per_m[0] = si(l, "damping");
    if (n == "TwoMasses") {
      t.mass_kg[1] = si(l, "mass2");
      t.stiffness_N_per_m[1] = si(l, "stiffness2");
      t.damping_Ns_per_m[1] = si(l, "damping");
    }
    if (n != "Brick") t.ground_damping_Ns_per_m = si(l, "friction");
    if (n == "Brick") t.gravity_m_s2[1] = -kStandardGravity;
    return t;
  }
  throw InternalError("laws: no term for law '" + n + "'");
}

const char* si_unit_of(const schema::LawDef& def, const std::string& param) {
  const auto* p = schema::find_param(def, param);
  if (!p || p->kind == schema::LawParamKind::Number) return "1";
  return std::string_view(schema::si_unit_name(p->dimension)).data();
}

}  // namespace

bool generate_laws(const ResolvedMaterial& m, const calibration::DeviceCalibration& device, schema::PatchProgram& out,
                   Diagnostics& diags) {
  bool ok = true;
  // Terms generated before the laws (slipperiness's anti-viscous damping) need the energy bound too.
  bool any_non_passive = std::any_of(out.terms.begin(), out.terms.end(), [](const auto& t) { return !schema::is_passive(t); });
  for (const auto& law : m.laws) {
    const auto family = law.physics ? schema::LawFamily::Physics : schema::LawFamily::Force;
    const schema::LawDef* def = schema::find_law(family, law.name);
    if (!def) throw InternalError("laws: '" + law.name + "' is not in the law table");
    const std::string prefix = std::string(schema::family_keyword(family)) + "." + law.name + ".";
    for (const auto& [name, p] : law.params)
      out.provenance.push_back({prefix + name, p.si, si_unit_of(*def, name), p.stated, layer_name(p.layer), p.source});
    auto term = term_of(law);
    if (!term) continue;
    if (const auto* masses = std::get_if<schema::PointMassesTerm>(&*term)) {
      // The integrator's substeps at the device's slowest servo rate must stay within the cap.
      const double dt = 1.0 / device.min_rate_hz;
      const auto n = schema::point_mass_substeps(*masses, dt);
      if (n > schema::kMaxPointMassSubsteps) {
        diags.error("E0312", law.location,
                    "physics " + law.name + " is too stiff for its mass to integrate at " + num(device.min_rate_hz) +
                        " Hz (device '" + device.name + "'): it needs " + std::to_string(n) + " substeps per tick, more than " +
                        std::to_string(schema::kMaxPointMassSubsteps),
                    "make the mass heavier or the spring and damping softer (natural frequency below about " +
                        num(device.min_rate_hz * 0.25 * schema::kMaxPointMassSubsteps / 6.2832) + " Hz)");
        ok = false;
        continue;
      }
    }
    // Sliding at more force than it took to break loose would push the hand on at breakaway.
    auto slides_harder = [&](const char* kinetic, double k, const char* static_, double s) {
      if (!(k > s)) return false;
      diags.error("E0304", law.location,
                  "physics " + law.name + "'s " + kinetic + " coefficient " + num(k) + " exceeds its " + static_ + " one " +
                      num(s) + ": a contact slides at no more force than it takes to break it loose",
                  std::string("give ") + kinetic + " at most " + num(s) + " (rubber on a dry surface: about 3/4 of static)");
      return true;
    };
    bool slides_too_hard = false;
    if (const auto* f = std::get_if<schema::FrictionTerm>(&*term))
      slides_too_hard = slides_harder("kinetic", f->kinetic_coefficient, "static", f->static_coefficient);
    if (const auto* f = std::get_if<schema::NapFrictionTerm>(&*term)) {
      const bool with = slides_harder("kinetic", f->kinetic_coefficient, "static", f->static_coefficient);
      const bool against = slides_harder("against_kinetic", f->against_kinetic_coefficient, "against_static",
                                         f->against_static_coefficient);
      slides_too_hard = with || against;
    }
    if (slides_too_hard) {
      ok = false;
      continue;
    }
    if (!schema::is_passive(*term)) {
      any_non_passive = true;
      diags.warning("W0306", law.location,
                    std::string(schema::family_keyword(family)) + " " + law.name +
                        " is not passive: it can put energy into the hand, as Sandpaper's non-physical materials did",
                    "the runtime bounds the energy it injects: `energy budget <J> refill <W>` sets the bound "
                    "(default 50 mJ, refill 10 mW)");
    }
    out.terms.push_back(std::move(*term));
  }
  if (any_non_passive || m.energy_budget) {
    const Param budget = m.energy_budget ? *m.energy_budget
                                         : Param{kDefaultEnergyBudget_J, "50 mJ (docs/RUNTIME.md, \"Energy bound\")",
                                                 Layer::Default, "default", {}};
    const Param refill = m.energy_refill ? *m.energy_refill
                                         : Param{m.energy_budget ? 0.0 : kDefaultEnergyRefill_W,
                                                 m.energy_budget ? "0 W (budget stated without refill)"
                                                                 : "10 mW (docs/RUNTIME.md, \"Energy bound\")",
                                                 Layer::Default, "default", {}};
    out.energy_budget_J = budget.si;
    out.energy_refill_W = refill.si;
    out.provenance.push_back({"energy.budget", budget.si, "J", budget.stated, layer_name(budget.layer), budget.source});
    out.provenance.push_back({"energy.refill", refill.si, "W", refill.stated, layer_name(refill.layer), refill.source});
  }
  return ok;
}

}  // namespace sandpaper::compiler
