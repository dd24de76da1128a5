// The resolver: syntax -> resolved material, layer by layer (resolver_impl.hpp says which file does what).
#include "resolver_impl.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sandpaper/schema/confined_path.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/compiler/height_field_image.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/force_laws.hpp"
#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/compiler/thesis_stimuli.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler {

const char* pattern_kind_name(PatternKind k) {
  switch (k) {
    case PatternKind::Bars: return "bars";
    case PatternKind::Grid: return "grid";
    case PatternKind::Perlin: return "perlin";
    case PatternKind::Noise: return "noise";
    case PatternKind::Stripes: return "stripes";
  }
  return "?";
}

const char* layer_name(Layer l) {
  switch (l) {
    case Layer::Representative: return "representative";
    case Layer::Perceptual: return "perceptual";
    case Layer::Physical: return "physical";
    case Layer::Default: return "default";
  }
  return "?";
}

}  // namespace sandpaper::compiler

namespace sandpaper::compiler::resolve_detail {

std::string fmt_num(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

Param stated_param(const Quantity& q, Layer layer) {
  return Param{q.si, q.text(), layer, q.location.str(), q.location};
}

Param default_param(double si, std::string why) { return Param{si, std::move(why), Layer::Default, "default", {}}; }

// Marks everything a library entry resolved to as inherited through `like <entry>`; `label` is
// "library corduroy" or "thesis stimulus barsB15W20_2".
void inherit(Param& p, const std::string& label) {
  if (p.layer == Layer::Default) return;  // a default stays a default, wherever it came through
  // A value that came through a map keeps naming it ("... via stevens-guirao1964 (calibration/...)").
  const auto via = p.source.find(" via ");
  const std::string map = p.location.file && via != std::string::npos ? p.source.substr(via) : "";
  p.source = label + " (" + (p.location.file ? p.location.str() : p.source) + ")" + map;
  p.layer = Layer::Representative;
}
void inherit(std::optional<Param>& p, const std::string& label) {
  if (p) inherit(*p, label);
}

ResolvedMaterial defaults() {
  ResolvedMaterial m;
  m.size_width = default_param(kDefaultPatchSize_m, "95 mm (thesis 5.2.3: stimuli were 9.5 cm squares)");
  m.size_height = m.size_width;
  return m;
}

// The quantities a statement sets, for the one-statement-per-quantity rule.
std::vector<std::string> quantities_set(const Statement& st) {
  return std::visit(
      [](const auto& n) -> std::vector<std::string> {
        using T = std::decay_t<decltype(n)>;
        if constexpr (std::is_same_v<T, DescribesStmt>) return {"the description"};
        else if constexpr (std::is_same_v<T, LikeStmt>) return {"the library entry to start from"};
        else if constexpr (std::is_same_v<T, RoughnessStmt>) return {"the maximum lateral force"};
        else if constexpr (std::is_same_v<T, PerceptStmt>) {
          const PerceptWord* w = find_percept_word(n.word);
          return {w ? w->quantity : n.word};
        }
        else if constexpr (std::is_same_v<T, GratingStmt>) {
          std::vector<std::string> q{"the texture"};
          if (n.amplitude) q.push_back("the maximum lateral force");
          return q;
        } else if constexpr (std::is_same_v<T, HeightmapStmt>) {
          std::vector<std::string> q{"the texture"};
          // depth + press set the force through the stylus reading (thesis 3.4).
          if (n.amplitude || n.depth || n.press) q.push_back("the maximum lateral force");
          return q;
        } else if constexpr (std::is_same_v<T, PatternStmt>) {
          std::vector<std::string> q{"the texture"};
          if (n.amplitude) q.push_back("the maximum lateral force");
          return q;
        } else if constexpr (std::is_same_v<T, QuantizeStmt>) return {"the height quantization"};
        else if constexpr (std::is_same_v<T, SpringStmt>) return {"the spring stiffness"};
        else if constexpr (std::is_same_v<T, DamperStmt>) return {"the damping"};
        else if constexpr (std::is_same_v<T, SizeStmt>) return {"the patch size"};
        else if constexpr (std::is_same_v<T, EnergyStmt>) return {"the energy budget"};
        else if constexpr (std::is_same_v<T, FamilyStmt>) return {"the family"};
        else if constexpr (std::is_same_v<T, LicenceStmt>) return {"the licence"};
        else if constexpr (std::is_same_v<T, DeprecatedStmt>) return {"the replacement"};
        else return {};
      },
      st.node);
}

// A statement other than `like` and the entry's own metadata (describes, family, alias, licence,
// deprecated, overrides) changes the material it inherits.
bool changes_what_it_inherits(const std::vector<const Statement*>& kept) {
  for (const auto* st : kept)
    if (!std::holds_alternative<LikeStmt>(st->node) && !std::holds_alternative<DescribesStmt>(st->node) &&
        !std::holds_alternative<FamilyStmt>(st->node) && !std::holds_alternative<AliasStmt>(st->node) &&
        !std::holds_alternative<LicenceStmt>(st->node) && !std::holds_alternative<DeprecatedStmt>(st->node) &&
        !std::holds_alternative<OverridesStmt>(st->node) && !std::holds_alternative<AcceptStmt>(st->node))
      return true;
  return false;
}

ResolvedMaterial Resolver::run() {
  std::vector<const Statement*> kept = check_conflicts();
  ResolvedMaterial m = defaults();
  // Representative layer.
  bool has_like = false;
  for (const auto* st : kept)
    if (const auto* like = std::get_if<LikeStmt>(&st->node)) m = from_library(*like), has_like = true;
  if (!has_like) {
    if (const RoughnessStmt* bare = bare_perceptual(kept)) {
      // A bare perceptual description (`roughness 0.6`) is felt on the library's reference texture,
      // the grating the roughness map was measured on (library/library.toml `reference`).
      LikeStmt ref{ctx_.library.manifest().reference, bare->value_location};
      m = from_library(ref, /*reference=*/true);
      // An unnamed one-line description is named by what it says ("roughness coarse"), not "<-e>".
      if (syn_.name.empty() && syn_.file && syn_.file->name.rfind('<', 0) == 0 && syn_.file->text.size() <= 80) {
        std::string t = syn_.file->text;
        t.erase(0, t.find_first_not_of(" \t\n;"));
        t.erase(t.find_last_not_of(" \t\n;") + 1);
        m.name = t;
      }
    }
  }
  for (const auto* st : kept)
    if (const auto* d = std::get_if<DescribesStmt>(&st->node)) m.describes = d->text;
  for (const auto* st : kept) {
    if (const auto* f = std::get_if<FamilyStmt>(&st->node)) m.family = f->family;
    else if (const auto* a = std::get_if<AliasStmt>(&st->node)) m.aliases.push_back(a->name);
    else if (const auto* l = std::get_if<LicenceStmt>(&st->node)) m.licence = l->licence;
    else if (const auto* x = std::get_if<DeprecatedStmt>(&st->node)) m.deprecated_by = x->replacement;
  }
  if (!syn_.name.empty()) m.name = syn_.name;
  else if (has_like && syn_.file && syn_.file->name.rfind('<', 0) == 0 && changes_what_it_inherits(kept)) {
    // "playing corduroy" would say the library entry itself is playing: an unnamed inline description
    // that changes what it inherits is named by what it says ("like corduroy; roughness 0.7"),
    // or, when that is too long to read as a name, as the entry modified.
    std::string t = syn_.file->text;
    for (auto& c : t)
      if (c == '\n' || c == '\t' || c == '\r') c = ' ';
    t.erase(0, t.find_first_not_of(" ;"));
    t.erase(t.find_last_not_of(" ;") + 1);
    m.name = !t.empty() && t.size() <= 80 ? t : m.name + ", modified";
  }
  for (const auto* st : kept)
    if (std::holds_alternative<ExtrapolateStmt>(st->node)) m.extrapolate = true;
  // Perceptual layer.
  for (const auto* st : kept) {
    if (const auto* r = std::get_if<RoughnessStmt>(&st->node)) roughness(*r, m);
    else if (const auto* p = std::get_if<PerceptStmt>(&st->node)) percept(*p, *st, m);
  }
  // Physical layer. The file's force laws, if it has any, replace the inherited ones.
  bool own_laws = false;
  for (const auto* st : kept)
    if (std::holds_alternative<LawStmt>(st->node)) own_laws = true;
  if (own_laws) m.laws.clear();
  for (const auto* st : kept) physical(*st, m);
  finish(m);
  return m;
}

std::vector<const Statement*> Resolver::check_conflicts() {
  std::map<std::string, const Statement*> first;
  std::vector<const Statement*> kept;
  for (const auto& st : syn_.statements) {
    bool clash = false;
    for (const auto& q : quantities_set(st)) {
      auto [it, inserted] = first.emplace(q, &st);
      if (inserted) continue;
      const Statement& a = *it->second;
      auto& d = diags_.error("E0302", st.location,
                             "`" + st.text + "` sets " + q + ", which line " + std::to_string(a.location.line) +
                                 " already sets (`" + a.text + "`)",
                             "keep one of the two statements");
      d.notes.push_back({a.location, q + " is first set here"});
      clash = true;
    }
    if (!clash) kept.push_back(&st);
  }
  return kept;
}

const RoughnessStmt* Resolver::bare_perceptual(const std::vector<const Statement*>& kept) const {
  const std::string& ref = ctx_.library.manifest().reference;
  if (ref.empty() || !ctx_.library.entry(ref)) return nullptr;
  for (const auto& e : ctx_.entry_stack)
    if (ctx_.library.canonical_name(e) == ctx_.library.canonical_name(ref)) return nullptr;
  const RoughnessStmt* r = nullptr;
  for (const auto* st : kept) {
    if (std::holds_alternative<GratingStmt>(st->node) || std::holds_alternative<HeightmapStmt>(st->node) ||
        std::holds_alternative<PatternStmt>(st->node))
      return nullptr;
    // `bumpiness` makes a grating of its own (bumpiness-provisional).
    if (const auto* p = std::get_if<PerceptStmt>(&st->node)) {
      const PerceptWord* w = find_percept_word(p->word);
      if (w && w->percept == std::string("bumpiness")) return nullptr;
    }
    if (const auto* rs = std::get_if<RoughnessStmt>(&st->node)) r = rs;
  }
  return r;
}

void Resolver::finish(ResolvedMaterial& m) {
  if (m.name.empty()) m.name = syn_.file ? syn_.file->name : "material";
  // An image without `repeat` sets the patch's size unless something else did.
  if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture); h && !h->repeat) {
    if (m.size_width.layer == Layer::Default) {
      m.size_width = h->width;
      m.size_height = h->height;
    }
  }
  // A height map's stylus reading (depth + press) is its force; a target this file gives beats
  // an inherited stylus reading.
  bool stylus = false;
  if (auto* h = std::get_if<ResolvedHeightmap>(&m.texture); h && h->stylus()) {
    if (m.max_lateral_force) h->depth.reset(), h->press.reset();
    else stylus = true;
  }
  bool has_texture = !std::holds_alternative<std::monostate>(m.texture);
  if (m.quantize_bits && m.quantize_bits->layer == Layer::Physical && std::holds_alternative<ResolvedHeightmap>(m.texture))
    diags_.error("E0304", m.quantize_bits->location,
                 "quantize applies to grating and pattern textures; an image's heights are its pixel values already",
                 "remove `quantize`, or save the image with fewer grey levels");
  // After an error the missing force is usually that error's echo: report it only on its own.
  if (has_texture && !m.max_lateral_force && !stylus && !diags_.has_errors()) {
    SourceLocation at = texture_location(m);
    diags_.error("E0308", at, "the texture has no force: nothing says how strong its lateral force is",
                 "add a perceptual `roughness 0.5` (or `roughness medium`), or a physical `amplitude 1.5 N` on the texture");
  }
  if (!has_texture && m.max_lateral_force && m.max_lateral_force->layer != Layer::Representative && !diags_.has_errors())
    diags_.error("E0309", m.max_lateral_force->location, "roughness or amplitude given, but there is no texture to carry it",
                 "add a texture, e.g. `grating period 2.5 mm`, or start from one with `like corduroy`");
  bool has_force_law = false;
  for (const auto& l : m.laws)
    if (l.name != "Nothing" && l.name != "Null") has_force_law = true;
  const SourceLocation start = syn_.name_location.file ? syn_.name_location : SourceLocation{syn_.file, 1, 1, 1};
  // No statement at all is a slip (an empty file, a blank -e, Python's compile("")), not a
  // material that feels like nothing: that is `force Nothing`.
  if (syn_.statements.empty() && !diags_.has_errors())
    diags_.error("E0316", start, "the material is empty: it has no statement",
                 "describe it, e.g. `like corduroy`, `roughness medium` or `grating period 2.5 mm`; a material "
                 "meant to feel like nothing says `force Nothing`");
  else if (!has_texture && !m.spring && !m.damper && !m.friction_coefficient && !has_force_law && !diags_.has_errors())
    diags_.warning("W0305", start,
                   "the material has no force terms; it will feel like nothing",
                   "add a texture, a spring or a damper");
}

SourceLocation Resolver::texture_location(const ResolvedMaterial& m) const {
  if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) return g->location;
  if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture)) return h->location;
  if (const auto* p = std::get_if<ResolvedPattern>(&m.texture)) return p->location;
  return {};
}

bool Resolver::positive(const Quantity& q, const char* what) {
  if (q.si > 0) return true;
  diags_.error("E0304", q.location, std::string(what) + " " + q.text() + " must be greater than zero",
               "give a positive " + std::string(what));
  return false;
}

bool Resolver::non_negative(const Quantity& q, const char* what, const char* why) {
  if (q.si >= 0) return true;
  diags_.error("E0304", q.location, std::string(what) + " " + q.text() + " is negative",
               *why ? std::string(why) : "give zero or a positive " + std::string(what));
  return false;
}

}  // namespace sandpaper::compiler::resolve_detail

namespace sandpaper::compiler {

ResolvedMaterial resolve(const MaterialSyntax& syntax, ResolveContext& ctx, Diagnostics& diags) {
  return resolve_detail::Resolver(syntax, ctx, diags).run();
}

}  // namespace sandpaper::compiler
