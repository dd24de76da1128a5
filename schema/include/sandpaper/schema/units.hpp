#pragma once
// The units the material language accepts, as data: each unit's dimension and its factor to SI.
// Everything inside Sandpaper is SI (m, N, N/m, N*s/m, rad, fraction 0..1); units exist only at
// the boundaries (files, CLI, JSON). See schema/LANGUAGE.md, "Units".
#include <optional>
#include <span>
#include <string_view>

namespace sandpaper::schema {

enum class Dimension { Length, Force, Stiffness, Damping, Angle, Fraction, Mass, Time, Energy, Power, Speed };

// Name of the SI unit a dimension is stored in ("m", "N", "N/m", "N*s/m", "rad", "1").
std::string_view si_unit_name(Dimension d);
// Human name of a dimension ("length", "force", ...), for diagnostics.
std::string_view dimension_name(Dimension d);

struct UnitDef {
  std::string_view name;   // as written in a material file: "mm", "ozf", "N*s/m", "%"
  Dimension dimension;
  double to_si;            // value_in_si = value * to_si
};

// Every unit the language accepts. gf and ozf use standard gravity 9.80665 m/s^2 (ISO 80000-4);
// 1 in = 25.4 mm and 1 oz = 28.349523125 g (international yard and pound, 1959).
// `ju` and `pu` are the thesis joystick's force units (Minsky 1995 Table 6: 1 program unit = 4
// joystick units): 1 ju = 0.490909 gf, fitted to Table 6 (calibration/devices/sandpaper-1995.toml).
std::span<const UnitDef> all_units();
// The unit named `name` (exact, case-sensitive: "mN" is not "MN"); nullopt if unknown.
std::optional<UnitDef> find_unit(std::string_view name);
// Comma-separated list of the unit names of one dimension, for "expected one of ..." messages.
std::string units_of(Dimension d);

}  // namespace sandpaper::schema

namespace sandpaper::schema {

// A quantity written as text with its unit, "382 gf", "2.5 mm", "-0.5N": a number, optional spaces,
// a unit from all_units(). nullopt if the text is not of that form or the unit is unknown. Used for
// quantities in data files (calibration, library), where the unit travels with the number.
struct ParsedQuantity {
  double value = 0;   // as written
  UnitDef unit;
  double si() const { return value * unit.to_si; }
};
std::optional<ParsedQuantity> parse_quantity(std::string_view text);

}  // namespace sandpaper::schema
