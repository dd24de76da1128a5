#pragma once
// The language's force laws as data: every `force` prototype of Sandpaper's Texture menu and every
// `physics` model (Minsky 1995, Appendix B and 3.2.2), with its parameters, their dimensions and
// defaults. The parser checks statements against this table; schema/LANGUAGE.md restates it.
#include <optional>
#include <span>
#include <string_view>

#include "sandpaper/schema/units.hpp"

namespace sandpaper::schema {

enum class LawFamily { Force, Physics };  // `force NAME ...` (no state) / `physics NAME ...` (state)

// Quantity: a number with a unit of `dimension`; Number: a plain number; Axes: the word x, y or xy.
enum class LawParamKind { Quantity, Number, Axes };

struct LawParam {
  std::string_view name;            // "stiffness"
  LawParamKind kind = LawParamKind::Quantity;
  Dimension dimension = Dimension::Length;  // for Quantity
  bool required = true;
  double default_si = 0;            // when not required (Axes: 3 = xy, 1 = x, 2 = y)
  std::string_view default_text;    // "20 mm", for explain and docs
  bool any_sign = false;            // otherwise the value must be > 0 (>= 0 for optional dampings)
};

struct LawDef {
  LawFamily family;
  std::string_view name;            // Sandpaper's name, e.g. "AntiViscous"
  std::span<const LawParam> params;
  std::string_view law;             // the force law in one line, e.g. "F = b v"
  std::string_view source;          // "Minsky 1995, Appendix B (Texture menu)"
};

std::span<const LawDef> all_laws();
// The law called `name` in `family` (exact, case-sensitive as Sandpaper spelled it); nullptr if none.
const LawDef* find_law(LawFamily family, std::string_view name);
const LawParam* find_param(const LawDef& law, std::string_view name);
std::string_view family_keyword(LawFamily f);  // "force" / "physics"

}  // namespace sandpaper::schema
