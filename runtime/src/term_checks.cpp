#include "term_checks.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#include "sandpaper/schema/term_kinds.hpp"

namespace sandpaper::runtime {
namespace {

using namespace schema;

// Checks the parameters of one term; every failure names the term's index and kind.
class TermCheck {
 public:
  TermCheck(std::size_t index, std::string_view kind) : index_(index), kind_(kind) {}

  void finite(std::string_view what, double x) const {
    if (!std::isfinite(x)) fail(std::string(what) + " must be finite");
  }
  void positive(std::string_view what, double x) const {
    if (!(std::isfinite(x) && x > 0)) fail(std::string(what) + " must be positive and finite");
  }
  void non_negative(std::string_view what, double x) const {
    if (!(std::isfinite(x) && x >= 0)) fail(std::string(what) + " must be zero or more, and finite");
  }
  void demand(terms::Check check, std::string_view what, double x) const {
    switch (check) {
      case terms::Check::Any: return;
      case terms::Check::Finite: return finite(what, x);
      case terms::Check::Positive: return positive(what, x);
      case terms::Check::NonNegative: return non_negative(what, x);
    }
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw std::invalid_argument("term " + std::to_string(index_) + " (" + std::string(kind_) + "): " + why);
  }

 private:
  std::size_t index_;
  std::string_view kind_;
};

// A listed field, by its member's type: a pair's halves are checked as "<label> x" and "<label> y".
template <class T, class M>
void check_field(const TermCheck& c, const terms::Field<T, M>& f, const T& term) {
  const M& v = term.*(f.member);
  if constexpr (std::is_same_v<M, double>) {
    c.demand(f.check, f.label, v);
  } else if constexpr (std::is_same_v<M, double[2]>) {
    c.demand(f.check, std::string(f.label) + " x", v[0]);
    c.demand(f.check, std::string(f.label) + " y", v[1]);
  } else if constexpr (std::is_enum_v<M>) {
    if (static_cast<std::size_t>(v) >= terms::EnumNames<M>::names.size())
      c.fail("unknown " + std::string(f.label) + " " + std::to_string(static_cast<int>(v)));
  }
}

template <terms::Listed T>
void check(const TermCheck& c, const T& term) {
  terms::for_each_field<T>([&](const auto& f) { check_field(c, f, term); });
  if (const char* broken = terms::Kind<T>::rule(term)) c.fail(broken);
}

void check(const TermCheck& c, const GratingTerm& t) {
  c.positive("period", t.period_m);
  c.finite("orientation", t.orientation_rad);
  if (t.force_N.size() < 2) c.fail("force table needs at least 2 samples");
}

void check(const TermCheck& c, const HeightFieldTerm& t) {
  const std::size_t samples = std::size_t{t.nx} * t.ny;
  if (samples == 0) c.fail("grid is empty");
  if (!t.repeat && (t.nx < 2 || t.ny < 2)) c.fail("a field that does not repeat needs at least 2 x 2 samples");
  if (t.force_x_N.size() != samples || t.force_y_N.size() != samples)
    c.fail("force tables must hold nx * ny samples");
  c.positive("spacing x", t.spacing_m[0]);
  c.positive("spacing y", t.spacing_m[1]);
  c.finite("origin x", t.origin_m[0]);
  c.finite("origin y", t.origin_m[1]);
}

// Negative springs or dampers would make the masses' own motion grow without bound, which no energy
// bound on the hand could stop, and is_passive() counts this term as passive.
void check(const TermCheck& c, const PointMassesTerm& t) {
  if (t.count != 1 && t.count != 2) c.fail("count must be 1 or 2, not " + std::to_string(t.count));
  for (std::uint32_t i = 0; i < t.count; ++i) {
    const std::string n = " " + std::to_string(i);
    c.positive("mass" + n, t.mass_kg[i]);
    c.non_negative("stiffness" + n, t.stiffness_N_per_m[i]);
    c.non_negative("damping" + n, t.damping_Ns_per_m[i]);
  }
  c.non_negative("ground damping", t.ground_damping_Ns_per_m);
  c.finite("gravity x", t.gravity_m_s2[0]);
  c.finite("gravity y", t.gravity_m_s2[1]);
}

}  // namespace

void check_program(const PatchProgram& program) {
  for (int axis = 0; axis < 2; ++axis)
    if (!(std::isfinite(program.size_m[axis]) && program.size_m[axis] > 0))
      throw std::invalid_argument("patch size must be positive and finite");
  if (!(std::isfinite(program.energy_budget_J) && program.energy_budget_J >= 0))
    throw std::invalid_argument("energy budget must be zero or more, and finite (J)");
  if (!(std::isfinite(program.energy_refill_W) && program.energy_refill_W >= 0))
    throw std::invalid_argument("energy refill must be zero or more, and finite (W)");
  for (std::size_t i = 0; i < program.terms.size(); ++i) {
    const TermCheck c(i, terms::visit_kind(program.terms[i], [](const auto& kind, const auto&) { return kind.label; }));
    std::visit([&c](const auto& term) { check(c, term); }, program.terms[i]);
  }
}

}  // namespace sandpaper::runtime
