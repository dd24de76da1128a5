// `like NAME`: a library entry or a thesis stimulus as the base a material changes.
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

namespace sandpaper::compiler::resolve_detail {

ResolvedMaterial Resolver::from_library(const LikeStmt& like, bool reference) {
  ResolvedMaterial base = defaults();
  const LibraryEntry* lib_entry = ctx_.library.entry(like.name);
  auto path = ctx_.library.find(like.name);
  // No file: the name may be one of the thesis' stimuli, generated from the name.
  ThesisLookup generated;
  if (!path) generated = find_thesis_stimulus(like.name, ctx_.library.thesis_directory());
  if (!path && !generated.stimulus) {
    // ROOT:NAME with a ROOT the path does not have: say which roots it has.
    if (const auto colon = like.name.find(':'); colon != std::string::npos) {
      const auto id = like.name.substr(0, colon);
      std::vector<std::string> ids;
      std::string listed;
      for (const auto& r : ctx_.library.roots()) ids.push_back(r.id), listed += (listed.empty() ? "'" : ", '") + r.id + "'";
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
        const auto guess = closest_match(id, ids);
        diags_.error("E0301", like.name_location,
                     "no library root '" + id + "' (in '" + like.name + "'): the library path's root" + (ids.size() == 1 ? " is " : "s are ") +
                         listed,
                     (guess.empty() ? std::string() : "did you mean `" + guess + like.name.substr(colon) + "`? ") +
                         "A root's id is `id` in its library.toml, else its folder's name; NAME alone takes the first root that has it");
        return base;
      }
    }
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
                                  "see compiler/src/resolve/thesis_stimuli.cpp");
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
  inherit(m.friction_coefficient, label);
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

}  // namespace sandpaper::compiler::resolve_detail
