// One entry's page (entry_page.hpp).
#include "sandpaper/catalog/entry_page.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <sstream>
#include <system_error>

#include "sandpaper/catalog/html.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/licences.hpp"
#include "sandpaper/schema/force_laws.hpp"

namespace sandpaper::catalog {
namespace {

using compiler::Param;

std::string esc(const std::string& s) { return html_escape(s); }

// Where a number came from, as shown: a library file relative to the folder that holds its root
// ("library/textiles/corduroy.hmat:7:3"; "world/textiles/..." in a layered library), whether the
// compiler named it (an entry reached by `like`) or was given its path (the entry itself): the
// text `library check`, `explain` and `library show` print when run from that folder.
std::string shown_source(const compiler::Library& lib, const std::string& s) {
  return compiler::DisplayPaths(lib, compiler::DisplayPaths::FromRootsParent{}).in_text(s);
}

std::string entry_link(const compiler::Library& lib, const std::string& name) {
  if (const auto* e = lib.entry(name))
    return "<a href=\"" + url_segment(e->name) + ".html\">" + esc(name) + "</a>";
  return esc(name);
}

// One row of a layer table: what, value as written and in display units, layer, where it came from.
// Sources are shown relative to `lib`'s folder.
std::string param_row(const compiler::Library& lib, const std::string& what, const Param& p, double factor, const std::string& unit) {
  std::string value = format_number(p.si * factor, 4) + (unit.empty() ? "" : "\xC2\xA0" + unit);
  return "<tr><th scope=\"row\">" + esc(what) + "</th><td class=\"value\">" + esc(value) + "</td><td>" + esc(p.stated) +
         "</td><td>" + esc(compiler::layer_name(p.layer)) + "</td><td class=\"src\">" +
         esc(shown_source(lib, p.source)) + "</td></tr>\n";
}
std::string opt_row(const compiler::Library& lib, const std::string& what, const std::optional<Param>& p, double factor,
                    const std::string& unit) {
  return p ? param_row(lib, what, *p, factor, unit) : "";
}
std::string text_row(const std::string& what, const std::string& html_value) {
  return "<tr><th scope=\"row\">" + esc(what) + "</th><td colspan=\"4\">" + html_value + "</td></tr>\n";
}

const char* kLayerHead =
    "<thead><tr><th scope=\"col\">parameter</th><th scope=\"col\">value</th><th scope=\"col\">as written</th>"
    "<th scope=\"col\">layer</th><th scope=\"col\">source</th></tr></thead>\n";

std::string representative(const EntryView& v) {
  const auto& m = *v.material;
  const auto& e = *v.entry;
  std::ostringstream o;
  o << "<section id=\"representative\"><h2>Representative layer</h2>\n<dl>\n";
  o << "<dt>describes</dt><dd>" << esc(m.describes.empty() ? e.describes : m.describes) << "</dd>\n";
  const auto* fam = v.library->manifest().family(e.family);
  o << "<dt>family</dt><dd>"
    << (e.family.empty() ? std::string("(none)") : esc(fam ? fam->title + " (" + e.family + ")" : e.family)) << "</dd>\n";
  o << "<dt>aliases</dt><dd>";
  if (e.aliases.empty()) o << "(none)";
  for (std::size_t i = 0; i < e.aliases.size(); ++i) o << (i ? ", " : "") << "<code>" << esc(e.aliases[i]) << "</code>";
  o << "</dd>\n<dt>like chain</dt><dd>";
  if (m.like_chain.empty()) o << "(starts from nothing: every layer is its own)";
  for (std::size_t i = 0; i < m.like_chain.size(); ++i) {
    o << (i ? " \xE2\x86\x90 " : "") << entry_link(*v.library, m.like_chain[i]);
    if (i < m.like_origins.size())
      o << " <span class=\"origin\">(" << esc(shown_source(*v.library, m.like_origins[i])) << ")</span>";
  }
  o << "</dd>\n<dt>file</dt><dd><code>" << esc(e.relative_path) << "</code></dd>\n";
  if (!v.root.empty())
    o << "<dt>root</dt><dd class=\"root\"><code>" << esc(v.root) << "</code>"
      << (v.hides.empty() ? std::string(" (hides no entry below it)")
                          : ", in front of <code>" + esc(v.hides) + "</code>, which it hides") << "</dd>\n";
  o << "</dl>\n</section>\n";
  return o.str();
}

// The commands that play the entry: what a reader who found it here types next.
std::string how_to_feel(const EntryView& v) {
  const std::string name = esc(v.entry->name);
  std::ostringstream o;
  o << "<section id=\"feel\"><h2>How to feel it</h2>\n"
    << "<p>On the simulated joystick, with a hand moving over the patch, and the force it feels printed:</p>\n"
    << "<pre><code>sandpaper run -e " << name << " --device sim</code></pre>\n"
    << "<p>On a force-feedback joystick (an OpenFFBoard over USB; <code>sandpaper devices</code> lists what is plugged in):</p>\n"
    << "<pre><code>sandpaper run -e " << name << " --device usb</code></pre>\n"
    << "<p>In the studio, to feel it while changing its numbers: <code>sandpaper studio</code>, then a material that says "
    << "<code>like " << name << "</code>.";
  if (!v.root.empty())
    o << " This library is layered: give its folders with <code>--library</code>, front first, as it was drawn.";
  o << "</p>\n</section>\n";
  return o.str();
}

// Filled in the browser from the index's data (assets/similar.js): the same distance as `sandpaper
// library near` over what the index holds (force, spatial period, texture kind and terms).
std::string similar(const EntryView& v) {
  std::ostringstream o;
  o << "<section id=\"similar\"><h2>Similar entries</h2>\n<p class=\"similar-how\">The nearest entries in force JND "
       "steps (Weber fraction " << format_number(v.weber_fraction, 3) << "), as <code>sandpaper library near "
    << esc(v.entry->name) << "</code> measures them from the texture: maximum lateral force, spatial period and "
       "texture kind.</p>\n<ol id=\"similar-list\"><li class=\"muted\">Reading the index\xE2\x80\xA6</li></ol>\n"
       "<noscript><p>The list needs JavaScript.</p></noscript>\n</section>\n";
  return o.str();
}

std::string perceptual(const EntryView& v) {
  const auto& m = *v.material;
  const auto& lib = *v.library;
  const auto& p = *v.program;
  std::ostringstream o;
  o << "<section id=\"perceptual\"><h2>Perceptual layer</h2>\n";
  o << "<table class=\"layer\">" << kLayerHead << "<tbody>\n";
  if (m.roughness) o << param_row(lib, "roughness asked for", *m.roughness, 1, "");
  if (p.max_lateral_force_N > 0)
    o << text_row("roughness compiled",
                  "<strong class=\"roughness\">" + format_number(p.roughness, 3) +
                      "</strong> on the calibrated ratio scale, predicted by the map <code>" + esc(p.roughness_map) +
                      "</code> from the texture's maximum lateral force " + format_number(p.max_lateral_force_N, 4) + " N");
  else
    o << text_row("roughness compiled", "none: the entry has no texture, so no lateral-force roughness");
  for (const auto& t : m.percepts)
    o << param_row(lib, t.word + (t.word != t.percept ? " (" + t.percept + ")" : ""), t.value, 1, "") +
             text_row("", "sets <code>" + esc(t.parameter) + "</code> through the map <code>" + esc(t.map_id) + "</code>" +
                              (t.provisional ? " <em>(provisional: not yet measured)</em>" : ""));
  o << "</tbody></table>\n</section>\n";
  return o.str();
}

// The image's own licence and credit, from its REUSE sidecar (curation/licences.hpp): each SPDX id
// linked to its licence text at spdx.org, then the credit.
std::string image_licence_html(const std::string& image) {
  const auto side = curation::read_image_licence(image);
  if (!side || side->licence.empty()) return "<em>not stated</em> (no <code>" + esc(std::filesystem::path(image).filename().string()) + ".license</code>)";
  std::string html = esc(side->licence);
  const auto ex = curation::parse_licence_expression(side->licence);
  if (ex.ok()) {
    html.clear();
    std::size_t from = 0;
    for (const auto& id : ex.ids) {
      const auto at = side->licence.find(id, from);
      if (at == std::string::npos) continue;
      html += esc(side->licence.substr(from, at - from));
      html += id.rfind("LicenseRef-", 0) == 0 || id.find(':') != std::string::npos
                  ? "<span class=\"licence\">" + esc(id) + "</span>"
                  : "<a class=\"licence\" href=\"https://spdx.org/licenses/" + esc(id) + ".html\">" + esc(id) + "</a>";
      from = at + id.size();
    }
    html += esc(side->licence.substr(from));
  }
  return html + (side->credit.empty() ? "" : " \xC2\xB7 " + esc(side->credit));
}

std::string texture_rows(const compiler::Library& lib, const compiler::ResolvedMaterial& m) {
  constexpr double deg = 180 / std::numbers::pi;
  std::string s;
  if (const auto* g = std::get_if<compiler::ResolvedGrating>(&m.texture)) {
    s += text_row("texture", "grating (version-2 recipe, thesis 3.5.2)");
    s += param_row(lib, "period", g->period, 1e3, "mm") + param_row(lib, "hill", g->hill, 100, "%") +
         param_row(lib, "orientation", g->orientation, deg, "\xC2\xB0") + opt_row(lib, "smoothing (sigma)", g->smoothing, 1e3, "mm");
  } else if (const auto* h = std::get_if<compiler::ResolvedHeightmap>(&m.texture)) {
    s += text_row("texture", "height map from the image <code>" + esc(h->stated_path) + "</code>" +
                                 (h->repeat ? ", repeated" : "") + (h->invert ? ", inverted (dark = high)" : "") +
                                 (h->channel.empty() ? "" : ", channel " + esc(h->channel)));
    s += text_row("image licence", image_licence_html(h->path));
    s += param_row(lib, "width", h->width, 1e3, "mm") + param_row(lib, "height", h->height, 1e3, "mm") +
         opt_row(lib, "smoothing (sigma)", h->smoothing, 1e3, "mm") + opt_row(lib, "sampling", h->sampling, 1e3, "mm") +
         opt_row(lib, "relief depth", h->depth, 1e3, "mm") + opt_row(lib, "press", h->press, 1, "N");
  } else if (const auto* pt = std::get_if<compiler::ResolvedPattern>(&m.texture)) {
    s += text_row("texture", std::string("version-1 pattern: ") + compiler::pattern_kind_name(pt->kind) + " (thesis 3.5.1)");
    s += param_row(lib, "pixel", pt->pixel, 1e3, "mm") + opt_row(lib, "valley", pt->valley, 1e3, "mm") +
         opt_row(lib, "hill", pt->hill, 1e3, "mm") + opt_row(lib, "offset", pt->offset, 1e3, "mm") +
         opt_row(lib, "feature", pt->feature, 1e3, "mm") + opt_row(lib, "kernel", pt->kernel, 1, "px") +
         opt_row(lib, "refilter", pt->refilter, 1, "px") + opt_row(lib, "seed", pt->seed, 1, "") + opt_row(lib, "count", pt->count, 1, "");
  }
  return s;
}

std::string physical(const EntryView& v) {
  const auto& m = *v.material;
  const auto& lib = *v.library;
  const auto& p = *v.program;
  std::ostringstream o;
  o << "<section id=\"physical\"><h2>Physical layer</h2>\n";
  o << "<table class=\"layer\">" << kLayerHead << "<tbody>\n";
  o << texture_rows(lib, m);
  o << opt_row(lib, "height quantization", m.quantize_bits, 1, "bits") << opt_row(lib, "maximum lateral force", m.max_lateral_force, 1, "N")
    << opt_row(lib, "spring stiffness", m.spring, 1, "N/m") << opt_row(lib, "damping", m.damper, 1, "N\xC2\xB7s/m")
    << opt_row(lib, "friction coefficient (pressed with 1 N)", m.friction_coefficient, 1, "");
  for (const auto& law : m.laws) {
    o << text_row(std::string(law.physics ? "physics " : "force ") + law.name, "<code>" + esc(law.text) + "</code>");
    const auto* def = schema::find_law(law.physics ? schema::LawFamily::Physics : schema::LawFamily::Force, law.name);
    for (const auto& [name, param] : law.params) {
      std::string unit;
      if (def)
        if (const auto* lp = schema::find_param(*def, name); lp && lp->kind == schema::LawParamKind::Quantity)
          unit = std::string(schema::si_unit_name(lp->dimension));
      o << param_row(lib, "\xC2\xA0\xC2\xA0" + name, param, 1, unit == "1" ? "" : unit);
    }
  }
  o << opt_row(lib, "energy budget", m.energy_budget, 1, "J") << opt_row(lib, "energy refill", m.energy_refill, 1, "W");
  o << param_row(lib, "patch width", m.size_width, 1e3, "mm") << param_row(lib, "patch height", m.size_height, 1e3, "mm");
  o << "</tbody></table>\n<p>Compiled for the device <code>" << esc(p.device) << "</code> into " << p.terms.size()
    << " term" << (p.terms.size() == 1 ? "" : "s") << ":";
  for (std::size_t i = 0; i < p.terms.size(); ++i) o << (i ? ", " : " ") << esc(term_kind(p.terms[i]));
  o << ".</p>\n</section>\n";
  return o.str();
}

std::string notes_html(const std::vector<compiler::SourceNote>& notes) {
  std::string s;
  for (const auto& n : notes)
    s += "<div class=\"note\"><span class=\"kind kind-" + esc(compiler::source_kind_word(n.kind)) + "\">" +
         esc(compiler::source_kind_word(n.kind)) + "</span> " + esc(n.text) + "</div>";
  return s;
}

std::string provenance(const EntryView& v) {
  std::ostringstream o;
  o << "<section id=\"provenance\"><h2>Provenance</h2>\n<p>Every number of the compiled program, where it came from, "
       "and the <code>source</code> notes of the statement that says it.</p>\n";
  o << "<table class=\"provenance\"><thead><tr><th scope=\"col\">parameter</th><th scope=\"col\">value</th>"
       "<th scope=\"col\">unit</th><th scope=\"col\">as written</th><th scope=\"col\">layer</th><th scope=\"col\">source</th>"
       "<th scope=\"col\">notes</th></tr></thead><tbody>\n";
  for (const auto& r : v.program->provenance)
    o << "<tr><td><code>" << esc(r.parameter) << "</code></td><td class=\"num\">" << esc(format_number(r.value_si, 6))
      << "</td><td>" << esc(r.si_unit) << "</td><td>" << esc(r.stated) << "</td><td>" << esc(r.layer)
      << "</td><td class=\"src\">" << esc(shown_source(*v.library, r.source)) << "</td><td>"
      << notes_html(notes_for(*v.library, r.source))
      << "</td></tr>\n";
  o << "</tbody></table>\n";
  // The entry's own notes, statement by statement, including those no compiled number points at.
  o << "<h3>Sources in <code>" << esc(v.entry->relative_path) << "</code></h3>\n<table class=\"sources\"><tbody>\n";
  int rows = 0;
  for (const auto& st : v.entry->syntax.statements) {
    if (st.sources.empty()) continue;
    ++rows;
    o << "<tr><td><code>" << esc(st.text) << "</code></td><td>" << notes_html(st.sources) << "</td></tr>\n";
  }
  if (!rows) o << "<tr><td colspan=\"2\">The entry carries no <code>source</code> notes.</td></tr>\n";
  o << "</tbody></table>\n</section>\n";
  return o.str();
}

std::string figure(const EntryView& v) {
  std::ostringstream o;
  const auto& pic = *v.picture;
  o << "<section id=\"picture\"><h2>Height field</h2>\n";
  if (!pic.empty()) {
    o << "<figure class=\"shade\"><img id=\"shade\" src=\"" << url_segment(v.picture_file) << "\" width=\"" << pic.nx
      << "\" height=\"" << pic.ny << "\" alt=\"" << esc("shaded height field of " + v.entry->name) << "\">\n<figcaption>"
      << esc(pic.caption);
    if (!v.shade_file.empty())
      o << " Also as Sandpaper's own array file: <a href=\"" << url_segment(v.shade_file) << "\">" << esc(v.shade_file)
        << "</a>.";
    o << "</figcaption></figure>\n";
  } else {
    o << "<p class=\"no-picture\">No picture: no force of this entry depends on the hand's position alone, so it has "
         "no surface to draw. The force plot below shows it under a moving hand.</p>\n";
  }
  if (!pic.left_out.empty()) {
    o << "<p class=\"left-out\">" << (pic.empty() ? "Its terms: " : "Not in the picture: ");
    for (std::size_t i = 0; i < pic.left_out.size(); ++i) o << (i ? "; " : "") << esc(pic.left_out[i]);
    o << ".</p>\n";
  }
  o << "</section>\n";
  return o.str();
}

std::string plot(const EntryView& v) {
  const auto& s = *v.scan;
  std::ostringstream o;
  o << "<section id=\"force\"><h2>Lateral force along a scan line</h2>\n<figure class=\"plot\">\n"
    << force_plot_svg(s, "lateral force on a hand moving " + s.description + " of " + v.entry->name) << "<figcaption>"
    << esc("The force the runtime's evaluator (the code the servo loop plays) returns as the hand moves " + s.description +
           " at " + format_number(s.speed_m_s * 1e3, 3) + " mm/s, " + std::to_string(s.s_m.size()) +
           " samples; positive is along the scan direction" +
           (s.has_across() ? ", the dashed line the component across it" : "") + ".")
    << "</figcaption></figure>\n</section>\n";
  return o.str();
}

}  // namespace

std::vector<compiler::SourceNote> notes_for(const compiler::Library& library, const std::string& provenance_source) {
  static const std::regex where(R"(([^\s()]+\.hmat):(\d+):(\d+))");
  std::smatch m;
  if (!std::regex_search(provenance_source, m, where)) return {};
  namespace fs = std::filesystem;
  const fs::path named = m[1].str();
  const int line = std::stoi(m[2].str());
  // The compiler names a library file "library/<path in its root>" ("library/<id>/..." when
  // layered): source_file() gives the root and the path; a name as given on a command line is a path.
  std::vector<fs::path> candidates{named, library.directory() / named, library.directory().parent_path() / named};
  const auto in_root = library.source_file(named.generic_string());
  if (in_root) candidates.insert(candidates.begin(), in_root->first / in_root->second);
  auto same = [&](const fs::path& file) {
    std::error_code ec;
    for (const auto& cand : candidates)
      if (fs::equivalent(cand, file, ec)) return true;
    return false;
  };
  auto notes_of = [&](const compiler::LibraryEntry& e) {
    // The statement the location falls in: the last one starting on or before its line.
    const compiler::Statement* hit = nullptr;
    for (const auto& st : e.syntax.statements)
      if (st.location.line <= line && (!hit || st.location.line >= hit->location.line)) hit = &st;
    return hit ? hit->sources : std::vector<compiler::SourceNote>{};
  };
  // An entry's file is named after it: look there first. Trying every entry (a few stats each)
  // for every provenance row of every page made a catalog of N entries take N^2 stats.
  if (const auto* e = library.entry(named.stem().string()); e && same(e->file)) return notes_of(*e);
  if (!in_root) return {};  // not a library file: no entry has it
  for (const auto& e : library.entries())
    if (same(e.file)) return notes_of(e);
  return {};
}

std::string entry_page_html(const EntryView& v) {
  const auto& e = *v.entry;
  const auto& lib = *v.library;
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" << esc(e.name) << " \xE2\x80\x94 "
    << esc(lib.manifest().name.empty() ? std::string("Sandpaper library") : lib.manifest().name) << "</title>\n"
    << "<link rel=\"stylesheet\" href=\"../assets/catalog.css\">\n</head>\n<body class=\"entry\" data-entry=\""
    << esc(e.name) << "\" data-weber=\"" << format_number(v.weber_fraction, 6) << "\">\n";
  o << "<nav><a href=\"../index.html\">\xE2\x86\x90 all entries</a></nav>\n";
  if (!e.deprecated_by.empty())
    o << "<div class=\"deprecated\" role=\"alert\">Deprecated: use " << entry_link(lib, e.deprecated_by)
      << " instead. Compiling this entry, or <code>like " << esc(e.name) << "</code>, warns W0340.</div>\n";
  o << "<header><h1>" << esc(e.name) << "</h1>\n<p class=\"describes\">" << esc(v.program->describes) << "</p>\n";
  o << "<p class=\"facts\">";
  if (v.program->max_lateral_force_N > 0)
    o << "roughness <strong>" << format_number(v.program->roughness, 3) << "</strong> \xC2\xB7 ";
  o << "licence <span class=\"licence\">" << (e.licence.empty() ? "not stated" : esc(e.licence)) << "</span></p>\n</header>\n";
  o << "<div class=\"figures\">\n" << figure(v) << plot(v) << "</div>\n";
  o << how_to_feel(v) << representative(v) << perceptual(v) << physical(v) << similar(v) << provenance(v);
  o << "<footer>Licence of this entry: <span class=\"licence\">" << (e.licence.empty() ? "not stated" : esc(e.licence))
    << "</span>. " << esc(lib.manifest().name) << (lib.manifest().version.empty() ? "" : " " + esc(lib.manifest().version))
    << ".</footer>\n<script src=\"../assets/load.js\"></script>\n<script src=\"../assets/similar.js\"></script>\n</body>\n</html>\n";
  return o.str();
}

}  // namespace sandpaper::catalog
