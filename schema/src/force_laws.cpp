#include "sandpaper/schema/force_laws.hpp"

#include <array>

namespace sandpaper::schema {
namespace {

using K = LawParamKind;
using D = Dimension;

constexpr LawParam req(std::string_view name, D d) { return {name, K::Quantity, d, true, 0, "", false}; }
constexpr LawParam opt(std::string_view name, D d, double si, std::string_view text) {
  return {name, K::Quantity, d, false, si, text, false};
}
constexpr LawParam signed_opt(std::string_view name, D d) { return {name, K::Quantity, d, false, 0, "0", true}; }
constexpr LawParam axes() { return {"axes", K::Axes, D::Fraction, false, 3, "xy", false}; }

constexpr std::array<LawParam, 0> kNone{};
constexpr std::array kStiffness{req("stiffness", D::Stiffness)};
constexpr std::array kDamping{req("damping", D::Damping)};
constexpr std::array kFollower{req("stiffness", D::Stiffness), opt("lag", D::Time, 0.1, "100 ms")};
constexpr std::array kBowl{req("stiffness", D::Stiffness), opt("radius", D::Length, 0.02, "20 mm")};
constexpr std::array kPeriodic{req("amplitude", D::Force), req("period", D::Length), axes()};
constexpr std::array kConst{signed_opt("x", D::Force), signed_opt("y", D::Force)};
constexpr std::array kRidge{req("stiffness", D::Stiffness), req("wavelength", D::Length), req("width", D::Length)};
constexpr std::array kMinus{req("stiffness", D::Stiffness), opt("lead", D::Time, 0.02, "20 ms")};
constexpr std::array kBuckle{signed_opt("radial", D::Stiffness), signed_opt("tangential", D::Stiffness)};
constexpr std::array kMass{req("mass", D::Mass), req("stiffness", D::Stiffness), opt("damping", D::Damping, 0, "0"),
                           opt("friction", D::Damping, 0, "0")};
constexpr std::array kTwoMasses{req("mass", D::Mass),          req("stiffness", D::Stiffness),
                                req("mass2", D::Mass),         req("stiffness2", D::Stiffness),
                                opt("damping", D::Damping, 0, "0"), opt("friction", D::Damping, 0, "0")};
constexpr std::array kBrick{req("mass", D::Mass), req("stiffness", D::Stiffness), opt("damping", D::Damping, 0, "0")};
constexpr std::array kLinearSpring{req("stiffness", D::Stiffness), opt("orientation", D::Angle, 0, "0 deg")};
constexpr std::array kAttractor{req("stiffness", D::Stiffness), opt("radius", D::Length, 0.02, "20 mm"),
                                opt("period", D::Time, 2.0, "2 s"),
                                LawParam{"swirl", K::Number, D::Fraction, false, 0.3, "0.3", false}};

// Friction's coefficients are plain numbers (K::Number: zero allowed); the kinetic one is checked
// against the static one by the runtime's term checks.
constexpr std::array kFriction{LawParam{"static", K::Number, D::Fraction, true, 0, "", false},
                               LawParam{"kinetic", K::Number, D::Fraction, true, 0, "", false},
                               req("press", D::Force), opt("stiffness", D::Stiffness, 2000, "2000 N/m"),
                               opt("stick_speed", D::Speed, 0.002, "2 mm/s")};

// NapFriction: the with-the-nap pair, the against-the-nap pair, then as Friction, and the way the nap
// lies (Appendix B's Nap lies toward +y: F_y = |b v_y| helps a hand moving toward +y).
constexpr std::array kNapFriction{LawParam{"static", K::Number, D::Fraction, true, 0, "", false},
                                  LawParam{"kinetic", K::Number, D::Fraction, true, 0, "", false},
                                  LawParam{"against_static", K::Number, D::Fraction, true, 0, "", false},
                                  LawParam{"against_kinetic", K::Number, D::Fraction, true, 0, "", false},
                                  req("press", D::Force), opt("stiffness", D::Stiffness, 2000, "2000 N/m"),
                                  opt("stick_speed", D::Speed, 0.002, "2 mm/s"),
                                  LawParam{"nap", K::Quantity, D::Angle, false, 1.5707963267948966, "90 deg", true}};

constexpr const char* kTextureMenu = "Minsky 1995, Appendix B (Texture menu)";
constexpr const char* kReading = "Minsky 1995, Appendix B (Texture menu; OCR garbled, reading in docs/TEXTURES.md)";
constexpr const char* kPhysics = "Minsky 1995, 3.2.2 (dynamic modules)";

const std::array kLaws{
    LawDef{LawFamily::Force, "Nothing", kNone, "F = 0", kTextureMenu},
    LawDef{LawFamily::Force, "Null", kNone, "F = 0", kTextureMenu},
    LawDef{LawFamily::Force, "Spring", kStiffness, "F = -k p (feels like a bowl)", kTextureMenu},
    LawDef{LawFamily::Force, "Bump", kStiffness, "F = k p (feels convex)", kTextureMenu},
    LawDef{LawFamily::Force, "Viscous", kDamping, "F = -b v (oil, mud)", kTextureMenu},
    LawDef{LawFamily::Force, "AntiViscous", kDamping, "F = b v (feels like ice; not passive)", kTextureMenu},
    LawDef{LawFamily::Force, "ATNSpring", kFollower, "F = k (p - m), m follows p with a first-order lag (pushes along the recent motion; not passive)", kReading},
    LawDef{LawFamily::Force, "Nap", kDamping, "F_x = -b v_x, F_y = |b v_y| (like velvet; not passive)", kTextureMenu},
    LawDef{LawFamily::Force, "Bowl", kBowl, "F = -k p sqrt(|p| / r) (force grows as |p|^1.5)", kReading},
    LawDef{LawFamily::Force, "Wave", kPeriodic, "F = -A sin(2 pi p / P) on each axis", kTextureMenu},
    LawDef{LawFamily::Force, "Cusp", kPeriodic, "F = A (2 frac(|p| / P) - 1) on each axis", kTextureMenu},
    LawDef{LawFamily::Force, "Triangle", kPeriodic, "F = -A (2 frac(p / P) - 1): toward each local wave centre",
           "Minsky 1995, 3.4 (procedural triangle wave, Figure 6)"},
    LawDef{LawFamily::Force, "Const", kConst, "F = (x, y)", kTextureMenu},
    LawDef{LawFamily::Force, "Ridge", kRidge, "F_x = k ((p_x mod wavelength) - width), F_y = 0", kTextureMenu},
    LawDef{LawFamily::Force, "Minus", kMinus, "F = k (p - m) = -k (v lead + a lead^2 / 2), m the predicted position (a damper and an added mass; metered)", kReading},
    LawDef{LawFamily::Force, "Circle", kStiffness, "F = k R90 p, a field turning a quarter turn (not passive)", kReading},
    LawDef{LawFamily::Force, "Buckle", kBuckle, "F = radial p + tangential R90 p", kReading},
    LawDef{LawFamily::Physics, "Mass", kMass, "a point mass tied to the hand by a spring (and damper)", kPhysics},
    LawDef{LawFamily::Physics, "TwoMasses", kTwoMasses, "hand - spring - mass - spring - mass", kPhysics},
    LawDef{LawFamily::Physics, "Brick", kBrick, "a brick hanging from the hand by a spring, gravity toward -y",
           "Minsky 1995, 3.2.2 and Appendix C (\"to throw bricks\")"},
    LawDef{LawFamily::Physics, "LinearSpring", kLinearSpring, "F = -k (p . n) n: a spring along one line", kPhysics},
    LawDef{LawFamily::Physics, "RadialSpring", kStiffness, "F = -k p: a spring in all directions from the centre", kPhysics},
    LawDef{LawFamily::Physics, "Friction", kFriction,
           "F = -k (p - w): Coulomb friction mu P with stick-slip, w an adhesion point (passive)",
           "Karnopp 1985 (stick band); Hayward & Armstrong 2000 (adhesion point); docs/FORCE_LAWS.md"},
    LawDef{LawFamily::Physics, "NapFriction", kNapFriction,
           "Friction whose coefficients depend on the way the hand slides: static/kinetic with the nap (toward `nap`), "
           "against_static/against_kinetic against it (velvet, fur; passive)",
           "Minsky 1995, 7.4.1 (napped materials) and Appendix B (Nap); the friction as Friction's"},
    LawDef{LawFamily::Physics, "Attractor", kAttractor,
           "F = -k (p - q(t)), q a light object on a swirling path (not passive)", kPhysics},
};

}  // namespace

std::span<const LawDef> all_laws() { return kLaws; }

const LawDef* find_law(LawFamily family, std::string_view name) {
  for (const auto& l : kLaws)
    if (l.family == family && l.name == name) return &l;
  return nullptr;
}

const LawParam* find_param(const LawDef& law, std::string_view name) {
  for (const auto& p : law.params)
    if (p.name == name) return &p;
  return nullptr;
}

std::string_view family_keyword(LawFamily f) { return f == LawFamily::Force ? "force" : "physics"; }

}  // namespace sandpaper::schema
