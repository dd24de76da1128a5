#pragma once
// The resolver's parts (syntax -> resolved material), one job a file: resolver.cpp runs the layers in
// order and checks conflicts and completeness; resolve_like.cpp inherits through `like`;
// resolve_percepts.cpp turns perceptual words into physical targets through their maps and warns
// where a map extrapolates; resolve_physical.cpp checks and keeps the physical statements (gratings,
// force laws, patterns); resolve_images.cpp reads height-map pictures from where a file may read them.
// Internal to the compiler library.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/resolver.hpp"
#include "sandpaper/schema/force_laws.hpp"

namespace sandpaper::compiler::resolve_detail {

// Numbers in messages: four significant digits.
std::string fmt_num(double v);
// A quantity as the file states it.
Param stated_param(const Quantity& q, Layer layer);
Param default_param(double si, std::string why);
// Marks everything a library entry resolved to as inherited through `like <entry>`; `label` is
// "library corduroy" or "thesis stimulus barsB15W20_2".
void inherit(Param& p, const std::string& label);
void inherit(std::optional<Param>& p, const std::string& label);
ResolvedMaterial defaults();
// The quantities a statement sets, for the one-statement-per-quantity rule.
std::vector<std::string> quantities_set(const Statement& st);
// A statement other than `like` and the entry's own metadata changes the material it inherits.
bool changes_what_it_inherits(const std::vector<const Statement*>& kept);

class Resolver {
 public:
  Resolver(const MaterialSyntax& syn, ResolveContext& ctx, Diagnostics& diags) : syn_(syn), ctx_(ctx), diags_(diags) {}

  ResolvedMaterial run();

 private:
  std::vector<const Statement*> check_conflicts();

  // The roughness statement of a material that has no texture and no `like` of its own, when the
  // library names a reference texture that is not this material's own entry; nullptr otherwise.
  const RoughnessStmt* bare_perceptual(const std::vector<const Statement*>& kept) const;

  ResolvedMaterial from_library(const LikeStmt& like, bool reference = false);

  void roughness(const RoughnessStmt& r, ResolvedMaterial& m);

  // A perceptual word through its percept's compile map (compiler/percepts.hpp): the ratio-scale
  // value, checked against the map's domain, becomes the SI parameter the word sets. Range rules as
  // for roughness: negative is E0304, above the top of the map's domain E0303 unless `extrapolate`
  // (then W0303), below its bottom W0301; inside a domain widened beyond the map's stimuli W0322.
  void percept(const PerceptStmt& s, const Statement& st, ResolvedMaterial& m);

  // W0322 at `at`: `si` (in `si_unit`) is inside the map's domain but outside its [domain] stimuli.
  void warn_beyond_stimuli(const calibration::PsychophysicalMap& map, const SourceLocation& at, const std::string& stated,
                           double si, const char* si_unit);

  // Forgets the perceptual targets that set `parameter`, when something else now sets it.
  static void drop_targets(ResolvedMaterial& m, const std::string& parameter);

  void physical(const Statement& st, ResolvedMaterial& m);

  void grating(const GratingStmt& g, const Statement& st, ResolvedMaterial& m);

  // Fills every parameter of the law: stated, or the table's default. Magnitudes must be positive
  // (optional dampings may be zero); signed parameters (Const, Buckle) take any finite value.
  void law(const LawStmt& l, const Statement& st, ResolvedMaterial& m);

  static std::string example_args(const schema::LawDef& def);

  static void inherit_pattern(ResolvedPattern& p, const std::string& label);

  // A length of a pattern as a whole number of pixels (at least `min_px`); the value keeps the
  // rounded length, the statement keeps what was written.
  std::optional<Param> whole_pixels(const Quantity& q, double pixel_m, int min_px, const char* what);

  // A plain number that must be a whole number in [lo, hi] (`integer`) or any number in it.
  std::optional<Param> plain(const PlainNumber& n, double lo, double hi, bool integer, const char* what,
                             const std::string& stated_prefix);

  void pattern(const PatternStmt& p, const Statement& st, ResolvedMaterial& m);

  void quantize(const QuantizeStmt& q, ResolvedMaterial& m);

  void heightmap(const HeightmapStmt& h, ResolvedMaterial& m);

  // A picture keeps its shape: `size W` alone sets the width and the height follows the picture's
  // px; both sides stated on a picture of another shape stretch it, which is said (W0307). An image
  // that cannot be opened is left to codegen, which says why.
  void image_shape(const HeightmapStmt& h, ResolvedHeightmap& r);

  void finish(ResolvedMaterial& m);

  SourceLocation texture_location(const ResolvedMaterial& m) const;

  bool positive(const Quantity& q, const char* what);

  bool non_negative(const Quantity& q, const char* what, const char* why);

  const MaterialSyntax& syn_;
  ResolveContext& ctx_;
  Diagnostics& diags_;
};

}  // namespace sandpaper::compiler::resolve_detail
