#pragma once
// Phase 2 output: the syntax of one material, statement by statement, with every quantity's value
// already in SI and every statement's location kept for later diagnostics.
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sandpaper/compiler/source.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::compiler {

// A number with its unit, e.g. "3.2 mm" -> value 3.2, unit "mm", si 0.0032.
struct Quantity {
  double value = 0;
  std::string unit;
  double si = 0;
  SourceLocation location;  // spans the number and the unit
  std::string text() const;  // "3.2 mm"
};

// Representative: the intent, kept verbatim in the output (thesis 1.5.2).
struct DescribesStmt { std::string text; };
// Representative: start from a library entry.
struct LikeStmt { std::string name; SourceLocation name_location; };
// Perceptual: ratio-scale roughness (a number) or a named level ("coarse").
struct RoughnessStmt {
  std::optional<double> value;
  std::string level;
  SourceLocation value_location;
};
// Perceptual, through a percept's compile map (compiler/percepts.hpp): `viscosity 0.4`,
// `stickiness 0.4`, `slipperiness 0.3`, `softness 0.5`, `springiness 0.5`, `bumpiness 0.6`; a ratio-scale
// number or a named level of that percept.
struct PerceptStmt {
  std::string word;      // as written: "stickiness"
  std::optional<double> value;
  std::string level;
  SourceLocation value_location;
};
// Physical: a grating (thesis 3.5.2 version-2 recipe).
struct GratingStmt {
  std::optional<Quantity> period;  // absent: inherited from the grating this file is `like` (LANGUAGE.md)
  std::optional<Quantity> hill, amplitude, orientation, smoothing;
  SourceLocation location;         // the `grating` keyword
};
// Physical: an image read as a height field (thesis 3.2.2, 3.4).
struct HeightmapStmt {
  std::string path;
  SourceLocation path_location;
  Quantity width;
  std::optional<Quantity> height, smoothing, amplitude;
  std::optional<Quantity> sampling;      // resample to this spacing
  std::optional<Quantity> depth, press;  // stylus reading (thesis 3.4 EQ 5-11): relief and downward force
  std::string channel;                   // empty: the luminance rule
  SourceLocation channel_location;
  bool repeat = false;
  bool invert = false;                   // dark = high
};
// A plain number with no unit (a count, a seed, a kernel size in pixels), as written.
struct PlainNumber {
  double value = 0;
  std::string text;
  SourceLocation location;
};
// Physical: a version-1 synthetic height map (thesis 3.5.1, Ch. 4): bars, grid, perlin, noise or
// stripes, generated at the pixel pitch and read through the lateral-force gradient.
struct PatternStmt {
  std::string kind;  // "bars", "grid", "perlin", "noise", "stripes"
  SourceLocation kind_location;
  std::optional<Quantity> valley, hill, offset, feature, pixel, amplitude;
  std::optional<PlainNumber> kernel, refilter, seed, count;
};
// Heights rounded to `bits` bits before the gradient (thesis 3.6.1: the thesis' arrays were 8-bit).
struct QuantizeStmt { PlainNumber bits; };
struct SpringStmt { Quantity stiffness; };
struct DamperStmt { Quantity damping; };
struct SizeStmt { Quantity width; std::optional<Quantity> height; };
// Permits roughness above 1, beyond the strongest calibrated stimulus.
struct ExtrapolateStmt {};
// Physical: one of Sandpaper's force laws or physics models (Appendix B, 3.2.2), by its name, with
// named parameters checked against schema/force_laws.hpp.
struct LawArg {
  std::string name;            // "stiffness"
  std::optional<Quantity> quantity;  // for quantity and plain-number parameters (unit "" for a number)
  std::string word;            // for axes: "x", "y", "xy"
  SourceLocation location;     // the parameter's name
};
struct LawStmt {
  bool physics = false;        // `physics` (a model with state) rather than `force`
  std::string name;            // "AntiViscous"
  SourceLocation name_location;
  std::vector<LawArg> args;
};
// Physical: the energy the material's non-passive laws may inject (docs/RUNTIME.md, "Energy bound").
struct EnergyStmt {
  Quantity budget;
  std::optional<Quantity> refill;
};

// Library metadata (representative layer; schema/LANGUAGE.md "Library entries"). They describe the
// entry itself, so they are not inherited through `like`.
struct FamilyStmt { std::string family; SourceLocation location; };  // `family textiles`
struct AliasStmt { std::string name; SourceLocation location; };     // `alias corduroy-wide-wale`
struct LicenceStmt { std::string licence; SourceLocation location; };  // `licence "CC0-1.0"` (SPDX id)
struct DeprecatedStmt { std::string replacement; SourceLocation location; };  // `deprecated replaced-by NAME`
// `overrides`: the entry means to hide an entry of the same name in a library root below it.
struct OverridesStmt { SourceLocation location; };
// `accept W0350 "the fine ribs are the point of this entry"`: the entry means a warning the compiler
// gives it; the warning becomes a note that shows the reason (library review does not fail on it).
struct AcceptStmt { std::string code, reason; SourceLocation location; };

using StatementNode = std::variant<DescribesStmt, LikeStmt, RoughnessStmt, GratingStmt, HeightmapStmt, SpringStmt,
                                   DamperStmt, SizeStmt, ExtrapolateStmt, LawStmt, EnergyStmt, PatternStmt,
                                   QuantizeStmt, PerceptStmt, FamilyStmt, AliasStmt, LicenceStmt, DeprecatedStmt,
                                   OverridesStmt, AcceptStmt>;

// Where a statement's numbers come from: `source standard "FEPA 43-1:2006: P80 median 201 um"`, written
// after the statement it sources (every number in the library names its source).
enum class SourceKind { Measurement, Standard, Publication, Derived, ByEar };
const char* source_kind_word(SourceKind k);     // "measurement", ..., "by-ear" (as written)
const char* source_kind_phrase(SourceKind k);   // "a measurement", ..., "designed by ear"
struct SourceNote {
  SourceKind kind = SourceKind::ByEar;
  std::string text;
  SourceLocation location;  // the `source` keyword
};

struct Statement {
  StatementNode node;
  std::string keyword;       // "grating"
  SourceLocation location;   // the keyword
  std::string text;          // the statement as written, for provenance ("grating period 3.2 mm hill 50%")
  std::vector<SourceNote> sources;  // the `source` statements that follow it
};

// Whether the statement is library metadata (family, alias, licence, deprecated).
bool is_metadata(const Statement& st);
// Whether the statement carries a number that a library entry must source (roughness, percepts,
// grating, heightmap, pattern, quantize, spring, damper, force/physics, energy, size).
bool carries_numbers(const Statement& st);

struct MaterialSyntax {
  std::string name;  // from `material "name" { }`; empty for a bare statement list
  SourceLocation name_location;
  std::vector<Statement> statements;
  std::shared_ptr<const SourceFile> file;
};

}  // namespace sandpaper::compiler
