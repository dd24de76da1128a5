#pragma once
// One entry per term kind: its patch tag, its names, whether it is passive or keeps state, and the
// list of its fields. The patch writer and reader (patch_io.cpp), the JSON view (patch_json.cpp),
// the runtime's parameter checks (runtime/src/term_checks.cpp), is_passive and has_state all read
// these entries. A new kind also needs its struct in the Term variant, its evaluator, the
// language's line in compiler/src/codegen/laws.cpp and its picture in the catalog; the evaluator's
// and the catalog's visits have no fallback, so the build stops until they handle it
// (docs/PATCH_FORMAT.md, "Adding a term kind", and docs/ARCHITECTURE.md list every place). Kinds
// with variable-size tables (grating, height field) or a count that selects fields (point masses)
// have no field list; their code is written by hand beside the generic code.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::schema::terms {

// What the runtime demands of a number before it plays it. Bools and enumerations are not checked
// (an enumeration's range is checked by the reader and the runtime from its names).
enum class Check : std::uint8_t { Any, Finite, Positive, NonNegative };

// One parameter. In the patch it is stored in list order as its member's type: double as f64,
// double[2] as two f64 (x then y), bool as u8 0/1, an enumeration as u8. In JSON it is `json` (the
// key carries the SI unit), a pair as [x, y], an enumeration by name. Diagnostics call it `label`;
// a pair's halves are "<label> x" and "<label> y".
template <class T, class M>
struct Field {
  std::string_view json;
  std::string_view label;
  M T::*member;
  Check check;
};

template <class T, class M>
constexpr Field<T, M> field(std::string_view json, std::string_view label, M T::*member, Check check = Check::Finite) {
  return {json, label, member, check};
}

// The names of an enumeration's values, in value order (its u8 in the patch indexes this list).
template <class E>
struct EnumNames;
template <>
struct EnumNames<PeriodicShape> {
  static constexpr std::array<std::string_view, 3> names = {"sine", "sawtooth", "triangle"};
};

// Passivity that does not depend on the parameters.
struct AlwaysPassive {
  template <class T>
  constexpr bool operator()(const T&) const { return true; }
};
struct NeverPassive {
  template <class T>
  constexpr bool operator()(const T&) const { return false; }
};
// A cross-field rule the runtime checks after the fields' own checks: a message when broken.
struct NoRule {
  template <class T>
  constexpr const char* operator()(const T&) const { return nullptr; }
};

// The entry of one term kind. Members: tag (u32 in the patch, stable across versions), json (the
// JSON "kind"), label (diagnostics), passive(term) (schema::is_passive), has_state, and for kinds
// with fixed-size parameters `fields` and `rule`.
template <class T>
struct Kind;

template <>
struct Kind<SpringTerm> {
  static constexpr std::uint32_t tag = 1;
  static constexpr std::string_view json = "spring", label = "spring";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("stiffness_N_per_m", "stiffness", &SpringTerm::stiffness_N_per_m),
                                            field("centre_m", "centre", &SpringTerm::centre_m)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<DamperTerm> {
  static constexpr std::uint32_t tag = 2;
  static constexpr std::string_view json = "damper", label = "damper";
  // Negative damping (AntiViscous, Slick) feeds the hand energy.
  static constexpr auto passive = [](const DamperTerm& t) { return t.damping_Ns_per_m >= 0; };
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("damping_Ns_per_m", "damping", &DamperTerm::damping_Ns_per_m)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<GratingTerm> {
  static constexpr std::uint32_t tag = 3;
  static constexpr std::string_view json = "grating", label = "grating";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
};

template <>
struct Kind<HeightFieldTerm> {
  static constexpr std::uint32_t tag = 4;
  static constexpr std::uint32_t compact_tag = 16;  // binary16 grids (PatchWriteOptions::compact_grids)
  static constexpr std::string_view json = "height_field", label = "height field";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
};

template <>
struct Kind<ConstantForceTerm> {
  static constexpr std::uint32_t tag = 5;
  static constexpr std::string_view json = "constant_force", label = "constant force";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("force_N", "force", &ConstantForceTerm::force_N)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<NapTerm> {
  static constexpr std::uint32_t tag = 6;
  static constexpr std::string_view json = "nap", label = "nap";
  static constexpr NeverPassive passive{};  // F_y = |b v_y| pushes a hand moving toward +y
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("damping_Ns_per_m", "damping", &NapTerm::damping_Ns_per_m)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<PeriodicTerm> {
  static constexpr std::uint32_t tag = 7;
  static constexpr std::string_view json = "periodic", label = "periodic";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("shape", "shape", &PeriodicTerm::shape, Check::Any),
                                            field("amplitude_N", "amplitude", &PeriodicTerm::amplitude_N),
                                            field("period_m", "period", &PeriodicTerm::period_m, Check::Positive),
                                            field("on_x", "on x", &PeriodicTerm::on_x, Check::Any),
                                            field("on_y", "on y", &PeriodicTerm::on_y, Check::Any)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<RidgeTerm> {
  static constexpr std::uint32_t tag = 8;
  static constexpr std::string_view json = "ridge", label = "ridge";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("stiffness_N_per_m", "stiffness", &RidgeTerm::stiffness_N_per_m),
                                            field("wavelength_m", "wavelength", &RidgeTerm::wavelength_m, Check::Positive),
                                            field("ridge_width_m", "ridge width", &RidgeTerm::ridge_width_m)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<BowlTerm> {
  static constexpr std::uint32_t tag = 9;
  static constexpr std::string_view json = "bowl", label = "bowl";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("stiffness_N_per_m", "stiffness", &BowlTerm::stiffness_N_per_m),
                                            field("radius_m", "radius", &BowlTerm::radius_m, Check::Positive)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<LinearFieldTerm> {
  static constexpr std::uint32_t tag = 10;
  static constexpr std::string_view json = "linear_field", label = "linear field";
  // A tangential gain (Circle, Buckle) circulates: no potential, so it can feed the hand energy.
  static constexpr auto passive = [](const LinearFieldTerm& t) { return t.tangential_N_per_m == 0; };
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("radial_N_per_m", "radial gain", &LinearFieldTerm::radial_N_per_m),
                                            field("tangential_N_per_m", "tangential gain", &LinearFieldTerm::tangential_N_per_m)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<LinearSpringTerm> {
  static constexpr std::uint32_t tag = 11;
  static constexpr std::string_view json = "linear_spring", label = "linear spring";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("stiffness_N_per_m", "stiffness", &LinearSpringTerm::stiffness_N_per_m),
                                            field("orientation_rad", "orientation", &LinearSpringTerm::orientation_rad),
                                            field("centre_m", "centre", &LinearSpringTerm::centre_m)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<MinusTerm> {
  static constexpr std::uint32_t tag = 12;
  static constexpr std::string_view json = "minus", label = "minus";
  // A damper plus an added mass, passive in continuous time; metered all the same because its
  // acceleration is a finite difference of sampled positions, and delayed acceleration feedback
  // can put energy in (docs/TEXTURES.md, "Minus and ATNSpring").
  static constexpr NeverPassive passive{};
  static constexpr bool has_state = false;
  static constexpr auto fields = std::tuple{field("stiffness_N_per_m", "stiffness", &MinusTerm::stiffness_N_per_m),
                                            field("lead_s", "lead", &MinusTerm::lead_s, Check::NonNegative)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<FollowerSpringTerm> {
  static constexpr std::uint32_t tag = 13;
  static constexpr std::string_view json = "follower_spring", label = "follower spring";
  // The point trails the hand, so the force pushes along the hand's recent motion: active.
  static constexpr NeverPassive passive{};
  static constexpr bool has_state = true;
  // A negative stiffness would be a different law (a spring in series with a damper) the library
  // does not name.
  static constexpr auto fields = std::tuple{
      field("stiffness_N_per_m", "stiffness", &FollowerSpringTerm::stiffness_N_per_m, Check::NonNegative),
      field("lag_s", "lag", &FollowerSpringTerm::lag_s, Check::Positive)};
  static constexpr NoRule rule{};
};

template <>
struct Kind<PointMassesTerm> {
  static constexpr std::uint32_t tag = 14;
  static constexpr std::string_view json = "point_masses", label = "point masses";
  static constexpr AlwaysPassive passive{};
  static constexpr bool has_state = true;
};

template <>
struct Kind<AttractorTerm> {
  static constexpr std::uint32_t tag = 15;
  static constexpr std::string_view json = "attractor", label = "attractor";
  static constexpr NeverPassive passive{};  // its target moves on its own and drags the hand
  static constexpr bool has_state = true;
  static constexpr auto fields = std::tuple{field("stiffness_N_per_m", "stiffness", &AttractorTerm::stiffness_N_per_m),
                                            field("radius_m", "radius", &AttractorTerm::radius_m, Check::NonNegative),
                                            field("period_s", "period", &AttractorTerm::period_s, Check::Positive),
                                            field("swirl", "swirl", &AttractorTerm::swirl),
                                            field("centre_m", "centre", &AttractorTerm::centre_m)};
  static constexpr auto rule = [](const AttractorTerm& t) -> const char* {
    return t.swirl > -1 ? nullptr : "swirl must be greater than -1 (the path's radius divides by 1 + swirl)";
  };
};

template <>
struct Kind<FrictionTerm> {
  static constexpr std::uint32_t tag = 17;
  static constexpr std::string_view json = "friction", label = "friction";
  static constexpr AlwaysPassive passive{};  // the adhesion point only ever moves toward the hand
  static constexpr bool has_state = true;
  static constexpr auto fields = std::tuple{
      field("static_coefficient", "static coefficient", &FrictionTerm::static_coefficient, Check::NonNegative),
      field("kinetic_coefficient", "kinetic coefficient", &FrictionTerm::kinetic_coefficient, Check::NonNegative),
      field("press_N", "press", &FrictionTerm::press_N, Check::Positive),
      field("stiffness_N_per_m", "stiffness", &FrictionTerm::stiffness_N_per_m, Check::Positive),
      field("stick_speed_m_s", "stick speed", &FrictionTerm::stick_speed_m_s, Check::NonNegative)};
  // Sliding at more force than it took to break loose is not Coulomb friction (docs/FORCE_LAWS.md).
  static constexpr auto rule = [](const FrictionTerm& t) -> const char* {
    return t.kinetic_coefficient > t.static_coefficient ? "kinetic coefficient must not exceed the static one" : nullptr;
  };
};

template <>
struct Kind<NapFrictionTerm> {
  static constexpr std::uint32_t tag = 18;
  static constexpr std::string_view json = "nap_friction", label = "nap friction";
  static constexpr AlwaysPassive passive{};  // as friction: the adhesion point only moves toward the hand
  static constexpr bool has_state = true;
  static constexpr auto fields = std::tuple{
      field("static_coefficient", "static coefficient", &NapFrictionTerm::static_coefficient, Check::NonNegative),
      field("kinetic_coefficient", "kinetic coefficient", &NapFrictionTerm::kinetic_coefficient, Check::NonNegative),
      field("against_static_coefficient", "against static coefficient", &NapFrictionTerm::against_static_coefficient,
            Check::NonNegative),
      field("against_kinetic_coefficient", "against kinetic coefficient", &NapFrictionTerm::against_kinetic_coefficient,
            Check::NonNegative),
      field("press_N", "press", &NapFrictionTerm::press_N, Check::Positive),
      field("stiffness_N_per_m", "stiffness", &NapFrictionTerm::stiffness_N_per_m, Check::Positive),
      field("stick_speed_m_s", "stick speed", &NapFrictionTerm::stick_speed_m_s, Check::NonNegative),
      field("nap_orientation_rad", "nap orientation", &NapFrictionTerm::nap_orientation_rad)};
  static constexpr auto rule = [](const NapFrictionTerm& t) -> const char* {
    if (t.kinetic_coefficient > t.static_coefficient) return "kinetic coefficient must not exceed the static one";
    if (t.against_kinetic_coefficient > t.against_static_coefficient)
      return "against kinetic coefficient must not exceed the against static one";
    return nullptr;
  };
};

// Whether a kind's parameters are a field list (else its code is written by hand).
template <class T>
concept Listed = requires { Kind<T>::fields; };

// Calls f(std::type_identity<T>{}) for every alternative T of Term, in variant order.
template <class F>
constexpr void for_each_kind(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(std::type_identity<std::variant_alternative_t<I, Term>>{}), ...);
  }(std::make_index_sequence<std::variant_size_v<Term>>{});
}

// Calls f(field) for each field of a listed kind, in patch order.
template <Listed T, class F>
constexpr void for_each_field(F&& f) {
  std::apply([&](const auto&... each) { (f(each), ...); }, Kind<T>::fields);
}

// Every tag (and the compact height field's) names one kind only.
constexpr bool tags_are_unique() {
  std::array<std::uint32_t, std::variant_size_v<Term> + 1> tags{};
  std::size_t n = 0;
  for_each_kind([&]<class T>(std::type_identity<T>) { tags[n++] = Kind<T>::tag; });
  tags[n++] = Kind<HeightFieldTerm>::compact_tag;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (tags[i] == tags[j]) return false;
  return true;
}
static_assert(tags_are_unique(), "two term kinds share a patch tag");

// The entry of the kind `term` holds.
template <class F>
decltype(auto) visit_kind(const Term& term, F&& f) {
  return std::visit([&]<class T>(const T& t) -> decltype(auto) { return f(Kind<T>{}, t); }, term);
}

}  // namespace sandpaper::schema::terms
