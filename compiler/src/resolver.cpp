#include "sandpaper/compiler/resolver.hpp"

#include "sandpaper/schema/confined_path.hpp"
#include "sandpaper/schema/input_limits.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sandpaper/compiler/height_image.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/force_laws.hpp"
#include "sandpaper/schema/input_limits.hpp"
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

namespace {

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
  // A value that came through a map keeps naming it ("... via viscosity-provisional (calibration/...)").
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

class Resolver {
 public:
  Resolver(const MaterialSyntax& syn, ResolveContext& ctx, Diagnostics& diags) : syn_(syn), ctx_(ctx), diags_(diags) {}

  ResolvedMaterial run() {
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

 private:
  std::vector<const Statement*> check_conflicts() {
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

  // The roughness statement of a material that has no texture and no `like` of its own, when the
  // library names a reference texture that is not this material's own entry; nullptr otherwise.
  const RoughnessStmt* bare_perceptual(const std::vector<const Statement*>& kept) const {
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

  ResolvedMaterial from_library(const LikeStmt& like, bool reference = false) {
    ResolvedMaterial base = defaults();
    const LibraryEntry* lib_entry = ctx_.library.entry(like.name);
    auto path = ctx_.library.find(like.name);
    // No file: the name may be one of the thesis' stimuli, generated from the name.
    ThesisLookup generated;
    if (!path) generated = find_thesis_stimulus(like.name, ctx_.library.thesis_directory());
    if (!path && !generated.stimulus) {
      std::string guess = closest_match(like.name, ctx_.library.names());
      diags_.error("E0301", like.name_location,
                   "no library entry named '" + like.name + "'" +
                       (generated.error.empty() ? "" : ", and no thesis stimulus can be made from the name"),
                   !generated.error.empty() ? generated.error
                   : guess.empty()          ? "`sandpaper library` lists the entries; thesis stimuli are named as in "
                                              "schema/LANGUAGE.md (barsB15W20_2, perlin10, a10p25, ...)"
                                            : "did you mean `" + guess + "`?");
      return base;
    }
    // Aliases name the same entry, so cycles are found on entry names.
    // Qualified (world:corduroy) in a layered library, so that a lab's corduroy may build on the world's.
    const std::string entry_name = lib_entry ? ctx_.library.qualified_name(*lib_entry) : like.name;
    for (const auto& e : ctx_.entry_stack)
      if (e == entry_name) {
        diags_.error("E0305", like.name_location,
                     "library entry '" + entry_name + "'" + (entry_name != like.name ? " (as '" + like.name + "')" : "") +
                         " is built on itself (`like` cycle)",
                     "break the cycle: an entry must not, through `like`, start from itself");
        return base;
      }
    // Bounded, so that a chain of thousands of entries cannot exhaust the stack.
    if (ctx_.entry_stack.size() >= static_cast<std::size_t>(schema::limits::kMaxLikeDepth)) {
      std::string chain;
      const auto& st = ctx_.entry_stack;
      for (std::size_t i = 0; i < st.size(); ++i) {
        if (i == 3 && st.size() > 6) {
          chain += " -> ... (" + std::to_string(st.size() - 6) + " more)";
          i = st.size() - 3;
        }
        chain += (chain.empty() ? "" : " -> ") + st[i];
      }
      chain += " -> " + entry_name;
      diags_.error("E0313", like.name_location,
                   "`like` chain deeper than " + std::to_string(schema::limits::kMaxLikeDepth) + " entries: " + chain,
                   "start one of these entries from a library entry nearer the root, or give its numbers itself");
      return base;
    }
    std::string text, origin, label;
    if (path) {
      try {
        text = schema::read_input_file(*path, schema::limits::kMaxSourceBytes);
      } catch (const schema::InputFileError& e) {
        diags_.error("E0306", like.name_location, "library entry '" + entry_name + "' cannot be read: " + e.reason,
                     "fix or remove the entry's file");
        return base;
      }
      origin = ctx_.library.source_name(*lib_entry);
      // In a layered library the label says which root every inherited number came from.
      const std::string shown = ctx_.library.qualified_name(*lib_entry);
      label = reference ? "library " + shown + " (the library's reference texture for bare perceptual descriptions)"
                        : "library " + shown;
      if (!lib_entry->deprecated_by.empty())
        diags_.warning("W0340", like.name_location,
                       "library entry '" + entry_name + "' is deprecated; use '" + lib_entry->deprecated_by + "'",
                       "write like " + lib_entry->deprecated_by + " (library/" + lib_entry->relative_path + " says why)");
    } else {
      text = generated.stimulus->source_text;
      origin = generated.stimulus->origin;
      label = "thesis stimulus " + like.name;
    }
    auto file = std::make_shared<const SourceFile>(path ? origin : "<thesis stimulus " + like.name + ">", text);
    Diagnostics sub;
    auto toks = lex(file, sub);
    auto syn = parse(toks, file, sub);
    ctx_.entry_stack.push_back(entry_name);
    ResolvedMaterial entry = resolve(syn, ctx_, sub);
    ctx_.entry_stack.pop_back();
    if (sub.has_errors()) {
      auto& d = diags_.error("E0306", like.name_location,
                             (path ? "library entry '" : "thesis stimulus '") + like.name + "' has errors",
                             path ? "fix " + file->name + " (its errors follow)"
                                  : "the generated text does not compile in this build (its errors follow); "
                                    "see compiler/src/thesis_stimuli.cpp");
      for (const auto& s : sub.all()) {
        if (s.severity != Severity::Error) continue;
        d.notes.push_back({s.location, s.message});
        // Nested entries' own notes say what is wrong deeper down (e.g. a `like` cycle).
        for (const auto& n : s.notes) d.notes.push_back(n);
      }
      return base;
    }
    // Inherit everything the entry resolved to; this file's statements override below.
    ResolvedMaterial m = entry;
    if (auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
      inherit(g->period, label);
      inherit(g->hill, label);
      inherit(g->orientation, label);
      inherit(g->smoothing, label);
    } else if (auto* h = std::get_if<ResolvedHeightmap>(&m.texture)) {
      inherit(h->width, label);
      inherit(h->height, label);
      inherit(h->smoothing, label);
      inherit(h->sampling, label);
      inherit(h->depth, label);
      inherit(h->press, label);
      h->source = label + " (" + h->source + ")";
    } else if (auto* pt = std::get_if<ResolvedPattern>(&m.texture)) {
      inherit_pattern(*pt, label);
    }
    inherit(m.max_lateral_force, label);
    inherit(m.roughness, label);
    inherit(m.spring, label);
    inherit(m.damper, label);
    inherit(m.antiviscous, label);
    for (auto& t : m.percepts) inherit(t.value, label);
    inherit(m.quantize_bits, label);
    for (auto& law : m.laws)
      for (auto& [name, p] : law.params) inherit(p, label);
    inherit(m.energy_budget, label);
    inherit(m.energy_refill, label);
    if (m.size_width.layer != Layer::Default) inherit(m.size_width, label);
    if (m.size_height.layer != Layer::Default) inherit(m.size_height, label);
    m.like_chain.insert(m.like_chain.begin(), entry_name);
    m.like_origins.insert(m.like_origins.begin(), origin);
    // The entry's own metadata describes it, not what is built on it.
    m.family.clear();
    m.aliases.clear();
    m.licence.clear();
    m.deprecated_by.clear();
    if (m.name.empty() || reference) m.name = reference ? std::string() : lib_entry ? lib_entry->name : like.name;
    // A bare perceptual description is not the reference texture: it is felt on it.
    if (reference)
      m.describes = "felt on the library's reference texture, " + entry_name +
                    (m.describes.empty() ? std::string() : " (" + m.describes + ")");
    return m;
  }

  void roughness(const RoughnessStmt& r, ResolvedMaterial& m) {
    const auto& map = ctx_.calibration.roughness_map();
    double value = 0;
    std::string stated;
    if (r.value) {
      value = *r.value;
      stated = "roughness " + fmt_num(value);
      if (value < 0) {
        diags_.error("E0304", r.value_location, "roughness " + fmt_num(value) + " is negative",
                     "roughness runs from 0 (no lateral force) to 1 (" + fmt_num(map.reference_si) + " N, the strongest calibrated stimulus)");
        return;
      }
    } else {
      const auto* lv = ctx_.calibration.find_level(r.level);
      if (!lv) {
        std::vector<std::string> names;
        for (const auto& l : ctx_.calibration.roughness_levels()) names.push_back(l.name);
        std::string guess = closest_match(r.level, names);
        std::string all;
        for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
        diags_.error("E0307", r.value_location, "unknown roughness level '" + r.level + "'",
                     guess.empty() ? "levels are: " + all + " (or give a number, e.g. roughness 0.6)"
                                   : "did you mean `" + guess + "`?");
        return;
      }
      value = lv->value;
      stated = "roughness " + r.level + " (= " + fmt_num(value) + ")";
    }
    if (value > 1.0 && !m.extrapolate) {
      diags_.error("E0303", r.value_location,
                   "roughness " + fmt_num(value) + " is above 1, the strongest calibrated stimulus (" + fmt_num(map.reference_si) + " N = " + fmt_num(map.reference_si / 9.80665e-3) + " gf)",
                   "use a value up to 1, or add the statement `extrapolate` to go beyond the measured range");
      return;
    }
    double force = map.value_for(value);
    m.roughness = Param{value, stated, Layer::Perceptual, r.value_location.str(), r.value_location};
    m.max_lateral_force = Param{force, stated, Layer::Perceptual,
                                r.value_location.str() + " via " + map.provenance(), r.value_location};
    if (value > 1.0)
      diags_.warning("W0303", r.value_location,
                     "roughness " + fmt_num(value) + " extrapolates the " + map.id + " map beyond its strongest stimulus (" + fmt_num(map.reference_si) + " N)");
    else if (value > 0 && map.force && force < map.force->min * (1 - 1e-9))
      diags_.warning("W0301", r.value_location,
                     "roughness " + fmt_num(value) + " is below the weakest calibrated stimulus (roughness " +
                         fmt_num(map.percept_of(map.force->min)) + ", " + fmt_num(map.force->min) + " N = " + fmt_num(map.force->min / 9.80665e-3) + " gf); the " + map.id + " map extrapolates",
                     "the prediction is less certain here");
  }

  // A perceptual word through its percept's compile map (compiler/percepts.hpp): the ratio-scale
  // value, checked against the map's domain, becomes the SI parameter the word sets. Range rules as
  // for roughness: negative is E0304, above the top of the map's domain E0303 unless `extrapolate`
  // (then W0303), below its bottom W0301.
  void percept(const PerceptStmt& s, const Statement& st, ResolvedMaterial& m) {
    const PerceptWord* w = find_percept_word(s.word);
    if (!w) throw InternalError("resolver: perceptual word '" + s.word + "' passed the parser but is not in the table");
    const calibration::PsychophysicalMap* map = ctx_.calibration.compile_map(w->percept);
    if (!map) {
      diags_.error("E0320", st.location,
                   "no map to compile `" + s.word + "` through: the calibration has no map with percept = \"" +
                       w->percept + "\" and use = \"compile\"",
                   std::string("add one to calibration/maps/ (docs/CALIBRATION.md), or give it physically: ") + w->physical);
      return;
    }
    double value = 0;
    std::string stated;
    if (s.value) {
      value = *s.value;
      stated = s.word + " " + fmt_num(value);
    } else {
      const calibration::Level* level = nullptr;
      std::vector<std::string> names;
      for (const auto* l : ctx_.calibration.levels(w->percept)) {
        names.push_back(l->name);
        if (l->name == s.level) level = l;
      }
      if (!level) {
        std::string guess = closest_match(s.level, names), all;
        for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
        const std::string number = "give a number, e.g. " + s.word + " 0.5";
        diags_.error("E0307", s.value_location, "unknown " + s.word + " level '" + s.level + "'",
                     !guess.empty()  ? "did you mean `" + guess + "`?"
                     : names.empty() ? s.word + " has no named levels (calibration/levels/ has none for " + w->percept +
                                           "): " + number
                                     : "levels are: " + all + " (or " + number + ")");
        return;
      }
      value = level->value;
      stated = s.word + " " + s.level + " (= " + fmt_num(value) + ")";
    }
    const auto shown = [&](double si) { return schema::display_value(si, w->si_unit); };
    double top = 1, bottom = 0;
    if (const auto domain = ratio_domain(*map)) {
      const double a = map->percept_of(domain->min), b = map->percept_of(domain->max);
      top = std::max(a, b);
      bottom = std::min(a, b);
    }
    const std::string scale = "1 is " + shown(map->reference_si) + " on the " + map->id + " map";
    if (value < 0 || (value == 0 && w->zero_refused)) {
      diags_.error("E0304", s.value_location,
                   s.word + " " + fmt_num(value) + (value < 0 ? " is negative" : std::string(" ") + w->zero_refused),
                   "give a " + s.word + " above 0 (" + scale + "), or give it physically: " + w->physical);
      return;
    }
    if (value > top * (1 + 1e-9) && !m.extrapolate) {
      diags_.error("E0303", s.value_location,
                   s.word + " " + fmt_num(value) + " is above " + fmt_num(top) + ", the top of the " + map->id +
                       " map's domain (" + shown(map->value_for(top)) + ")",
                   "use a value up to " + fmt_num(top) + ", or add the statement `extrapolate` to go beyond the map's domain");
      return;
    }
    Param p{map->value_for(value), stated, Layer::Perceptual, s.value_location.str() + " via " + map->provenance(),
            s.value_location};
    if (value > top * (1 + 1e-9))
      diags_.warning("W0303", s.value_location,
                     s.word + " " + fmt_num(value) + " (" + shown(p.si) + ") extrapolates the " + map->id +
                         " map beyond the top of its domain (" + shown(map->value_for(top)) + ")");
    else if (value > 0 && value < bottom * (1 - 1e-9))
      diags_.warning("W0301", s.value_location,
                     s.word + " " + fmt_num(value) + " (" + shown(p.si) + ") is below the bottom of the " + map->id +
                         " map's domain (" + s.word + " " + fmt_num(bottom) + ", " + shown(map->value_for(bottom)) +
                         "); the map extrapolates",
                     "the prediction is less certain here");
    const std::string param = w->parameter;
    drop_targets(m, param);
    if (param == "damper.damping") m.damper = p;
    else if (param == "antiviscous.damping") m.antiviscous = p;
    else if (param == "spring.stiffness") m.spring = p;
    else if (param == "texture.period") {
      // The period of the grating this file inherits (its other parameters kept), or a new grating.
      ResolvedGrating g;
      if (const auto* base = std::get_if<ResolvedGrating>(&m.texture)) g = *base;
      else {
        g.hill = default_param(0.5, "50% (thesis 3.5.2: hill 128 px, valley 128 px)");
        g.orientation = default_param(0.0, "0 deg (ribs across x)");
      }
      g.period = p;
      g.location = st.location;
      m.texture = g;
    } else throw InternalError("resolver: no parameter '" + param + "' for perceptual word '" + s.word + "'");
    m.percepts.push_back({s.word, w->percept, param,
                          Param{value, stated, Layer::Perceptual, s.value_location.str(), s.value_location}, map->id,
                          map->file, map->provisional});
  }

  // Forgets the perceptual targets that set `parameter`, when something else now sets it.
  static void drop_targets(ResolvedMaterial& m, const std::string& parameter) {
    std::erase_if(m.percepts, [&](const PerceptTarget& t) { return t.parameter == parameter; });
  }

  void physical(const Statement& st, ResolvedMaterial& m) {
    // What the file states physically beats a perceptual target it inherits for the same parameter.
    if (std::holds_alternative<SpringStmt>(st.node)) drop_targets(m, "spring.stiffness");
    else if (std::holds_alternative<DamperStmt>(st.node)) drop_targets(m, "damper.damping");
    else if (std::holds_alternative<GratingStmt>(st.node) || std::holds_alternative<HeightmapStmt>(st.node) ||
             std::holds_alternative<PatternStmt>(st.node))
      drop_targets(m, "texture.period");
    if (const auto* g = std::get_if<GratingStmt>(&st.node)) grating(*g, st, m);
    else if (const auto* l = std::get_if<LawStmt>(&st.node)) law(*l, st, m);
    else if (const auto* e = std::get_if<EnergyStmt>(&st.node)) {
      if (non_negative(e->budget, "energy budget", "")) m.energy_budget = stated_param(e->budget, Layer::Physical);
      if (e->refill && non_negative(*e->refill, "refill power", "")) m.energy_refill = stated_param(*e->refill, Layer::Physical);
    }
    else if (const auto* h = std::get_if<HeightmapStmt>(&st.node)) heightmap(*h, m);
    else if (const auto* s = std::get_if<SpringStmt>(&st.node)) {
      if (non_negative(s->stiffness, "spring stiffness", "a negative spring pushes the hand away: write `force Bump stiffness ...`"))
        m.spring = stated_param(s->stiffness, Layer::Physical);
    } else if (const auto* d = std::get_if<DamperStmt>(&st.node)) {
      if (non_negative(d->damping, "damping", "negative damping injects energy: write `force AntiViscous damping ...` (its energy is bounded)"))
        m.damper = stated_param(d->damping, Layer::Physical);
    } else if (const auto* pt = std::get_if<PatternStmt>(&st.node)) {
      pattern(*pt, st, m);
    } else if (const auto* q = std::get_if<QuantizeStmt>(&st.node)) {
      quantize(*q, m);
    } else if (const auto* z = std::get_if<SizeStmt>(&st.node)) {
      if (!positive(z->width, "patch width")) return;
      m.size_width = stated_param(z->width, Layer::Physical);
      m.size_height = m.size_width;
      if (z->height) {
        if (!positive(*z->height, "patch height")) return;
        m.size_height = stated_param(*z->height, Layer::Physical);
      }
    }
  }

  void grating(const GratingStmt& g, const Statement& st, ResolvedMaterial& m) {
    const auto* base = std::get_if<ResolvedGrating>(&m.texture);
    if (!g.period && !base) {
      diags_.error("E0315", g.location, "this grating has no period, and the file inherits no grating to take it from",
                   "give it one: grating period 2.5 mm" + std::string(g.hill ? " " + g.hill->text() : std::string()) +
                       ", or start from a grating with `like corduroy`");
      return;
    }
    bool ok = !g.period || positive(*g.period, "grating period");
    if (g.hill && !(g.hill->si > 0 && g.hill->si < 1)) {
      diags_.error("E0304", g.hill->location, "hill " + g.hill->text() + " is outside 0-100 %",
                   "the hill is the fraction of each period that is raised: use a value between 0% and 100%, e.g. 50%");
      ok = false;
    }
    if (g.smoothing) ok = non_negative(*g.smoothing, "smoothing", "") && ok;
    if (g.amplitude) ok = non_negative(*g.amplitude, "force amplitude", "") && ok;
    if (!ok) return;
    // What this statement leaves out it inherits from an inherited grating, else the defaults.
    ResolvedGrating r;
    r.period = g.period ? stated_param(*g.period, Layer::Physical) : base->period;
    r.hill = g.hill ? stated_param(*g.hill, Layer::Physical)
                    : base ? base->hill : default_param(0.5, "50% (thesis 3.5.2: hill 128 px, valley 128 px)");
    r.orientation = g.orientation ? stated_param(*g.orientation, Layer::Physical)
                                  : base ? base->orientation : default_param(0.0, "0 deg (ribs across x)");
    if (g.smoothing) r.smoothing = stated_param(*g.smoothing, Layer::Physical);
    else if (base) r.smoothing = base->smoothing;
    r.location = st.location;
    m.texture = r;
    if (g.amplitude) m.max_lateral_force = stated_param(*g.amplitude, Layer::Physical);
  }

  // Fills every parameter of the law: stated, or the table's default. Magnitudes must be positive
  // (optional dampings may be zero); signed parameters (Const, Buckle) take any finite value.
  void law(const LawStmt& l, const Statement& st, ResolvedMaterial& m) {
    const auto family = l.physics ? schema::LawFamily::Physics : schema::LawFamily::Force;
    const schema::LawDef* def = schema::find_law(family, l.name);
    if (!def) throw InternalError("resolver: law '" + l.name + "' passed the parser but is not in the table");
    ResolvedLaw r;
    r.physics = l.physics;
    r.name = l.name;
    r.text = st.text;
    r.location = l.name_location;
    bool ok = true;
    for (const auto& p : def->params) {
      const LawArg* arg = nullptr;
      for (const auto& a : l.args)
        if (a.name == p.name) arg = &a;
      if (!arg) {
        if (p.required) {
          diags_.error("E0311", l.name_location,
                       std::string(schema::family_keyword(family)) + " " + l.name + " needs its " + std::string(p.name),
                       "add " + std::string(p.name) + " <value>, e.g. `" + std::string(schema::family_keyword(family)) +
                           " " + l.name + " " + example_args(*def) + "`");
          ok = false;
          continue;
        }
        if (p.kind == schema::LawParamKind::Axes) continue;
        r.params.emplace_back(std::string(p.name), default_param(p.default_si, std::string(p.default_text)));
        continue;
      }
      if (p.kind == schema::LawParamKind::Axes) {
        r.axes = arg->word == "x" ? 1 : arg->word == "y" ? 2 : 3;
        continue;
      }
      const Quantity& q = *arg->quantity;
      const std::string what = l.name + " " + std::string(p.name);
      if (!p.any_sign) {
        const bool zero_ok = (!p.required && p.default_si == 0) || p.kind == schema::LawParamKind::Number;
        if (zero_ok ? !non_negative(q, what.c_str(), "") : !positive(q, what.c_str())) {
          ok = false;
          continue;
        }
      }
      Param v = stated_param(q, Layer::Physical);
      if (q.unit.empty()) v.stated = fmt_num(q.value);
      r.params.emplace_back(std::string(p.name), v);
    }
    if (ok) m.laws.push_back(std::move(r));
  }

  static std::string example_args(const schema::LawDef& def) {
    std::string out;
    for (const auto& p : def.params) {
      if (!p.required) continue;
      if (!out.empty()) out += ' ';
      out += std::string(p.name) + " ";
      switch (p.dimension) {
        case schema::Dimension::Stiffness: out += "200 N/m"; break;
        case schema::Dimension::Damping: out += "2 N*s/m"; break;
        case schema::Dimension::Force: out += "0.5 N"; break;
        case schema::Dimension::Length: out += "5 mm"; break;
        case schema::Dimension::Mass: out += "50 g"; break;
        case schema::Dimension::Time: out += "20 ms"; break;
        default: out += "1"; break;
      }
    }
    return out;
  }

  static void inherit_pattern(ResolvedPattern& p, const std::string& label) {
    inherit(p.pixel, label);
    for (auto* o : {&p.valley, &p.hill, &p.offset, &p.feature, &p.kernel, &p.refilter, &p.seed, &p.count}) inherit(*o, label);
  }

  // A length of a pattern as a whole number of pixels (at least `min_px`); the value keeps the
  // rounded length, the statement keeps what was written.
  std::optional<Param> whole_pixels(const Quantity& q, double pixel_m, int min_px, const char* what) {
    double px = std::round(q.si / pixel_m);
    if (!(q.si >= 0) || px < min_px || px > kMaxPatternPixels) {
      diags_.error("E0304", q.location,
                   std::string(what) + " " + q.text() + " is " + fmt_num(q.si / pixel_m) + " pixels of " +
                       fmt_num(pixel_m * 1e3) + " mm",
                   "give " + std::string(what) + " of " + (min_px > 0 ? "at least one pixel" : "zero or more pixels") +
                       " and at most " + std::to_string(kMaxPatternPixels) + " pixels");
      return std::nullopt;
    }
    Param p = stated_param(q, Layer::Physical);
    p.si = px * pixel_m;
    if (std::abs(q.si / pixel_m - px) > 1e-6) p.stated += " (rounded to " + fmt_num(px) + " px)";
    return p;
  }

  // A plain number that must be a whole number in [lo, hi] (`integer`) or any number in it.
  std::optional<Param> plain(const PlainNumber& n, double lo, double hi, bool integer, const char* what,
                             const std::string& stated_prefix) {
    bool whole = std::floor(n.value) == n.value;
    if (n.value < lo || n.value > hi || (integer && !whole)) {
      diags_.error("E0304", n.location, std::string(what) + " " + n.text + " is out of range",
                   std::string("give ") + (integer ? "a whole number" : "a number") + " from " + fmt_num(lo) + " to " +
                       fmt_num(hi));
      return std::nullopt;
    }
    return Param{n.value, stated_prefix + " " + n.text, Layer::Physical, n.location.str(), n.location};
  }

  void pattern(const PatternStmt& p, const Statement& st, ResolvedMaterial& m) {
    ResolvedPattern r;
    if (p.kind == "bars") r.kind = PatternKind::Bars;
    else if (p.kind == "grid") r.kind = PatternKind::Grid;
    else if (p.kind == "perlin") r.kind = PatternKind::Perlin;
    else if (p.kind == "noise") r.kind = PatternKind::Noise;
    else r.kind = PatternKind::Stripes;
    r.location = st.location;
    if (p.pixel) {
      if (!positive(*p.pixel, "pixel pitch")) return;
      r.pixel = stated_param(*p.pixel, Layer::Physical);
    } else {
      r.pixel = default_param(kThesisPixel_m, "0.37 mm (thesis 3.5.1 and Appendix A: 1 pixel = .37 mm)");
    }
    const double px = r.pixel.si;
    bool ok = true;
    auto length = [&](const std::optional<Quantity>& q, std::optional<Param>& slot, int min_px, const char* what) {
      if (!q) return;
      slot = whole_pixels(*q, px, min_px, what);
      ok = ok && slot.has_value();
    };
    length(p.valley, r.valley, 1, "the valley width");
    length(p.hill, r.hill, 1, "the hill width");
    length(p.offset, r.offset, 0, "the row offset");
    length(p.feature, r.feature, 1, "the feature size");
    auto number = [&](const std::optional<PlainNumber>& n, std::optional<Param>& slot, double lo, double hi, bool integer,
                      const char* what, const char* prefix) {
      if (!n) return;
      slot = plain(*n, lo, hi, integer, what, prefix);
      ok = ok && slot.has_value();
    };
    number(p.kernel, r.kernel, 0, kMaxPatternKernel, false, "the kernel size", "kernel");
    number(p.refilter, r.refilter, 0, kMaxPatternKernel, false, "the second pass's kernel size", "refilter");
    number(p.seed, r.seed, 0, 9007199254740991.0, true, "the seed", "seed");  // 2^53 - 1: exact in a double
    number(p.count, r.count, 1, 64, true, "the stripe count", "count");
    if (p.amplitude) ok = non_negative(*p.amplitude, "force amplitude", "") && ok;
    if (!ok) return;
    if (r.kind == PatternKind::Noise && !r.feature)
      r.feature = default_param(px, "one pixel (thesis 4.3: Noise alternates high forces closely)");
    if ((r.kind == PatternKind::Perlin || r.kind == PatternKind::Noise) && !r.seed)
      r.seed = default_param(1, "1 (thesis 4.3: the Perlins share one seed pattern)");
    m.texture = r;
    if (p.amplitude) m.max_lateral_force = stated_param(*p.amplitude, Layer::Physical);
  }

  void quantize(const QuantizeStmt& q, ResolvedMaterial& m) {
    if (auto bits = plain(q.bits, 1, 16, true, "the number of bits", "quantize")) {
      bits->stated += " bit";
      m.quantize_bits = bits;
    }
  }

  void heightmap(const HeightmapStmt& h, ResolvedMaterial& m) {
    bool ok = positive(h.width, "image width");
    if (h.height) ok = positive(*h.height, "image height") && ok;
    if (h.smoothing) ok = non_negative(*h.smoothing, "smoothing", "") && ok;
    if (h.amplitude) ok = non_negative(*h.amplitude, "force amplitude", "") && ok;
    if (h.sampling) ok = positive(*h.sampling, "sampling") && ok;
    if (h.depth) ok = positive(*h.depth, "relief depth") && ok;
    if (h.press) ok = positive(*h.press, "downward force (press)") && ok;
    if (h.amplitude && (h.depth || h.press)) {
      const Quantity& other = h.depth ? *h.depth : *h.press;
      auto& d = diags_.error("E0302", h.amplitude->location,
                             "`amplitude " + h.amplitude->text() + "` and `" + std::string(h.depth ? "depth " : "press ") +
                                 other.text() + "` both set the maximum lateral force of this height map",
                             "keep amplitude (a target force) or depth and press (the stylus reading), not both");
      d.notes.push_back({other.location, "the stylus reading sets the force here"});
      ok = false;
    } else if (h.depth.has_value() != h.press.has_value()) {
      const Quantity& given = h.depth ? *h.depth : *h.press;
      diags_.error("E0407", given.location,
                   h.depth ? "`depth " + given.text() + "` without `press`: the relief alone gives no force"
                           : "`press " + given.text() + "` without `depth`: the force needs the relief's height",
                   "give both, e.g. depth 0.5 mm press 1 N (lateral force = press x slope, thesis 3.4), "
                   "or a target force with roughness or amplitude");
      ok = false;
    }
    if (!ok) return;
    ResolvedHeightmap r;
    std::filesystem::path p(h.path);
    // A library entry reaches only inside its library: the library is shared, and an entry that
    // named "/srv/x.exr" or "../../x.exr" would read whatever the machine it is compiled on has there.
    const auto in_library = syn_.file ? ctx_.library.source_file(syn_.file->name) : std::nullopt;
    if (in_library) {
      const auto inside = (std::filesystem::path(in_library->second).parent_path() / p).lexically_normal();
      bool leaves = p.is_absolute() || inside.empty() || *inside.begin() == "..";
      // A symbolic link inside the library that leads out leaves it as surely as "..".
      if (!leaves) try {
          schema::confined_path(in_library->first, inside.generic_string(), "the library");
        } catch (const schema::OutsideFolder&) {
          leaves = true;
        }
      if (leaves) {
        diags_.error("E0314", h.path_location,
                     "library entry's image '" + h.path + "' is outside the library (symbolic links followed)",
                     "put the image in the library (library/images/) and name it relative to the entry's folder");
        return;
      }
    }
    if (p.is_relative() && syn_.file) {
      // Relative to the material file's folder; for -e text, to the working directory.
      std::filesystem::path dir;
      if (in_library) dir = (in_library->first / in_library->second).parent_path();
      else if (syn_.file->name != "<-e>") dir = std::filesystem::path(syn_.file->name).parent_path();
      p = dir / p;
    }
    r.path = p.string();
    r.stated_path = h.path;
    r.width = stated_param(h.width, Layer::Physical);
    r.height = h.height ? stated_param(*h.height, Layer::Physical) : r.width;
    image_shape(h, r);
    if (h.smoothing) r.smoothing = stated_param(*h.smoothing, Layer::Physical);
    if (h.sampling) r.sampling = stated_param(*h.sampling, Layer::Physical);
    if (h.depth) r.depth = stated_param(*h.depth, Layer::Physical);
    if (h.press) r.press = stated_param(*h.press, Layer::Physical);
    r.channel = h.channel;
    r.repeat = h.repeat;
    r.invert = h.invert;
    r.source = h.path_location.str();
    r.location = h.path_location;
    m.texture = r;
    if (h.amplitude) m.max_lateral_force = stated_param(*h.amplitude, Layer::Physical);
    if (r.stylus()) {
      // The file's stylus reading beats an inherited roughness or amplitude.
      m.max_lateral_force.reset();
      m.roughness.reset();
    }
  }

  // A picture keeps its shape: `size W` alone sets the width and the height follows the picture's
  // px; both sides stated on a picture of another shape stretch it, which is said (W0307). An image
  // that cannot be opened is left to codegen, which says why.
  void image_shape(const HeightmapStmt& h, ResolvedHeightmap& r) {
    const auto px = height_image_size(r.path);
    if (!px || px->first < 1 || px->second < 1) return;
    const auto [nx, ny] = *px;
    const std::string shape = std::to_string(nx) + " x " + std::to_string(ny) + " px";
    if (!h.height) {
      r.height.si = r.width.si * ny / nx;
      r.height.stated = fmt_num(r.height.si * 1e3) + " mm (" + h.width.text() + " across the picture's " + shape + ")";
      return;
    }
    const double dx = r.width.si / nx, dy = r.height.si / ny;
    if (std::abs(dx / dy - 1) <= 0.01) return;
    diags_.warning("W0307", h.height->location,
                   "the picture is stretched: " + shape + " over " + h.width.text() + " x " + h.height->text() + " is " +
                       fmt_num(dx * 1e3) + " mm per px across and " + fmt_num(dy * 1e3) + " mm per px down",
                   "write `size " + h.width.text() + "` alone to keep the picture's shape (" + h.width.text() + " x " +
                       fmt_num(r.width.si * ny / nx * 1e3) + " mm), or crop the picture to the patch's shape");
  }

  void finish(ResolvedMaterial& m) {
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
    else if (!has_texture && !m.spring && !m.damper && !m.antiviscous && !has_force_law && !diags_.has_errors())
      diags_.warning("W0305", start,
                     "the material has no force terms; it will feel like nothing",
                     "add a texture, a spring or a damper");
  }

  SourceLocation texture_location(const ResolvedMaterial& m) const {
    if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) return g->location;
    if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture)) return h->location;
    if (const auto* p = std::get_if<ResolvedPattern>(&m.texture)) return p->location;
    return {};
  }

  bool positive(const Quantity& q, const char* what) {
    if (q.si > 0) return true;
    diags_.error("E0304", q.location, std::string(what) + " " + q.text() + " must be greater than zero",
                 "give a positive " + std::string(what));
    return false;
  }

  bool non_negative(const Quantity& q, const char* what, const char* why) {
    if (q.si >= 0) return true;
    diags_.error("E0304", q.location, std::string(what) + " " + q.text() + " is negative",
                 *why ? std::string(why) : "give zero or a positive " + std::string(what));
    return false;
  }

  const MaterialSyntax& syn_;
  ResolveContext& ctx_;
  Diagnostics& diags_;
};

}  // namespace

// The roughness map's domain: warn where a roughness target extrapolates it. Called once the
// texture has compiled, so an image that cannot be read reports only its E0401.
void warn_roughness_domain(const ResolvedMaterial& m, const calibration::CalibrationSet& cal, Diagnostics& diags) {
  const auto& map = cal.roughness_map();
  if (m.roughness && m.roughness->layer == Layer::Perceptual) {
    if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
      double p = g->period.si;
      if (map.period && !map.period->contains(p))
        diags.warning("W0302", m.roughness->location,
                       "grating period " + fmt_num(p * 1e3) + " mm is outside the periods the " + map.id +
                           " map was measured on (" + fmt_num(map.period->min * 1e3) + "-" +
                           fmt_num(map.period->max * 1e3) + " mm); the roughness extrapolates",
                       "periods from " + fmt_num(map.period->min * 1e3) + " mm to " + fmt_num(map.period->max * 1e3) +
                           " mm keep the prediction inside the data");
    } else if (std::holds_alternative<ResolvedHeightmap>(m.texture)) {
      diags.warning("W0304", m.roughness->location,
                     "the " + map.id + " map was measured on gratings; for an image texture the roughness extrapolates",
                     "treat the roughness of image textures as approximate");
    } else if (std::holds_alternative<ResolvedPattern>(m.texture)) {
      diags.warning("W0304", m.roughness->location,
                     "the " + map.id + " map was measured on version-2 gratings; for a pattern texture the roughness extrapolates",
                     "treat the roughness of pattern textures as approximate, or give the force with `amplitude`");
    }
  }
}

ResolvedMaterial resolve(const MaterialSyntax& syntax, ResolveContext& ctx, Diagnostics& diags) {
  return Resolver(syntax, ctx, diags).run();
}

}  // namespace sandpaper::compiler
