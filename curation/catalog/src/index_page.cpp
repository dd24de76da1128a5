// The catalog's index page (index_page.hpp).
#include "sandpaper/catalog/index_page.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <charconv>
#include <map>
#include <set>
#include <string_view>
#include <sstream>
#include <stdexcept>

#include "index_parts.hpp"
#include "sandpaper/catalog/html.hpp"

namespace sandpaper::catalog {

using namespace index_parts;

namespace index_parts {

// The manifest's families in its order, then any family an entry names that the manifest lacks (by id).
std::vector<FamilyCount> families_of(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  std::map<std::string, int> count;
  for (const auto& r : rows) ++count[r.family];
  std::vector<FamilyCount> out;
  std::set<std::string> listed;
  for (const auto& f : manifest.families) {
    out.push_back({f.id, f.title, f.describes, count[f.id], f.stimulus_set});
    listed.insert(f.id);
  }
  for (const auto& [id, n] : count)
    if (!id.empty() && listed.insert(id).second) out.push_back({id, id, "", n, false});
  return out;
}

std::string json_string(const std::string& s) { return nlohmann::json(s).dump(-1, ' ', true); }

}  // namespace index_parts

nlohmann::json index_data(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  using nlohmann::json;
  json families = json::array();
  std::map<std::string, std::string> titles;
  for (const auto& f : families_of(manifest, rows)) {
    families.push_back({{"id", f.id}, {"title", f.title}, {"describes", f.describes}, {"count", f.count}});
    if (f.stimulus) families.back()["stimulus"] = true;
    titles[f.id] = f.title;
  }
  json entries = json::array();
  for (const auto& r : rows)
    entries.push_back({{"name", r.name},
                       {"family", r.family},
                       {"family_title", r.family.empty() ? "" : titles[r.family]},
                       {"aliases", r.aliases},
                       {"describes", r.describes},
                       {"roughness", r.roughness ? json(*r.roughness) : json(nullptr)},
                       {"max_lateral_force_N", r.max_lateral_force_N},
                       {"period_m", r.period_m},
                       {"kind", r.kind},
                       {"source_kinds", r.source_kinds},
                       {"root", r.root},
                       {"licence", r.licence},
                       {"deprecated_by", r.deprecated_by},
                       {"page", r.page},
                       {"thumbnail", r.thumbnail.empty() ? json(nullptr) : json(r.thumbnail)}});
  return {{"library", {{"name", manifest.name}, {"version", manifest.version}}},
          {"families", families},
          {"entries", entries}};
}

namespace index_parts {

// The source filter's words for the `source` kinds (syntax.hpp), as a reader would pick them.
const char* source_kind_label(compiler::SourceKind k) {
  switch (k) {
    case compiler::SourceKind::Measurement: return "measured";
    case compiler::SourceKind::Standard: return "from a standard";
    case compiler::SourceKind::Publication: return "published";
    case compiler::SourceKind::Derived: return "derived";
    case compiler::SourceKind::ByEar: return "by ear";
  }
  return "";
}

// 100000 -> "100,000", as index.js writes counts.
std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// Two pagers, above and below the rows, so that a page of 100 rows need not be scrolled back up to
// turn; the top one announces the page to screen readers, the bottom one would repeat it.
void pager(std::ostringstream& o, const char* id, bool announce) {
  o << "<nav class=\"pager\" id=\"" << id << "\" aria-label=\"" << (announce ? "Pages" : "Pages (bottom)")
    << "\" hidden>\n<button type=\"button\" class=\"prev\">\xE2\x86\x90 previous</button>\n<span class=\"page-of\""
    << (announce ? " aria-live=\"polite\"" : "") << "></span>\n<button type=\"button\" class=\"next\">next \xE2\x86\x92</button>\n</nav>\n";
}

}  // namespace index_parts

namespace index_parts {

std::string page_html(const std::string& library_name, const std::string& version, const std::vector<FamilyCount>& families,
                      std::size_t entries, bool unfiled, std::size_t parts) {
  const std::string name = library_name.empty() ? "Sandpaper library" : library_name;
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" << html_escape(name)
    << " \xE2\x80\x94 catalog</title>\n<link rel=\"stylesheet\" href=\"assets/catalog.css\">\n"
    // Without JavaScript nothing fills the table, so the filters and the empty table would only mislead.
    << "<noscript><style>#filters, #count, #entries { display: none; }</style></noscript>\n"
    << "</head>\n<body class=\"index\">\n";
  o << "<header><h1>" << html_escape(name) << "</h1>\n<p>" << (version.empty() ? "" : "Version " + html_escape(version) + " \xC2\xB7 ")
    << grouped(entries) << (entries == 1 ? " entry" : " entries") << ", each a material in three layers (representative, perceptual, physical) with the "
       "source of every number. Roughness is on the calibrated ratio scale (0.1 very fine \xE2\x80\xA6 1 the strongest "
       "calibrated stimulus).</p>\n</header>\n";
  o << "<noscript><p class=\"noscript\">This index needs JavaScript to list, filter and page through the entries. "
       "Without it, open the entries' own pages: each is <code>entries/&lt;name&gt;.html</code> beside this page "
       "(<a href=\"entries/\">entries/</a>).</p></noscript>\n";
  o << "<form id=\"filters\" role=\"search\" onsubmit=\"return false\">\n"
    << "<label>Family <select id=\"family\" name=\"family\">\n<option value=\"\">all families</option>\n";
  for (const auto& f : families)
    o << "<option value=\"" << html_escape(f.id) << "\">" << html_escape(f.title) << " (" << f.count << ")</option>\n";
  if (unfiled) o << "<option value=\"(none)\">no family</option>\n";
  o << "</select></label>\n"
    << "<fieldset class=\"range\"><legend>Roughness</legend><label>from <input id=\"rmin\" name=\"rmin\" type=\"number\" "
       "min=\"0\" step=\"0.01\" inputmode=\"decimal\" placeholder=\"0\"></label> <label>to <input id=\"rmax\" name=\"rmax\" "
       "type=\"number\" min=\"0\" step=\"0.01\" inputmode=\"decimal\" placeholder=\"any\"></label></fieldset>\n"
    << "<label>Words <input id=\"q\" name=\"q\" type=\"search\" placeholder=\"name, alias or description\"></label>\n"
    // The licences are the entries' own: index.js lists them with their counts from the data.
    << "<label>Licence <select id=\"licence\" name=\"licence\">\n<option value=\"\">any licence</option>\n</select></label>\n"
    << "<label>Sources <select id=\"source\" name=\"source\">\n<option value=\"\">any</option>\n";
  for (const auto k : {compiler::SourceKind::Measurement, compiler::SourceKind::Standard, compiler::SourceKind::Publication,
                       compiler::SourceKind::Derived, compiler::SourceKind::ByEar})
    o << "<option value=\"" << compiler::source_kind_word(k) << "\">" << source_kind_label(k) << "</option>\n";
  o << "<option value=\"none\">none stated</option>\n</select></label>\n"
    << "<label>Order <select id=\"order\" name=\"order\">\n<option value=\"\">by name</option>\n"
       "<option value=\"roughness\">roughness, smoothest first</option>\n"
       "<option value=\"-roughness\">roughness, roughest first</option>\n</select></label>\n"
    << "<button type=\"button\" id=\"clear\">Show all</button>\n</form>\n"
    << "<div id=\"compare-bar\" hidden><span id=\"compare-count\" aria-live=\"polite\"></span>\n"
       "<a id=\"compare-go\" href=\"assets/compare.html\">Compare side by side</a>\n"
       "<button type=\"button\" id=\"compare-clear\">Untick all</button></div>\n";
  o << "<p id=\"count\" aria-live=\"polite\">" << grouped(entries) << (entries == 1 ? " entry" : " entries") << "</p>\n";
  pager(o, "pager-top", true);
  o << "<table id=\"entries\">\n<thead><tr><th scope=\"col\"><span class=\"visually-hidden\">compare</span></th><th scope=\"col\">picture</th><th scope=\"col\">name</th><th scope=\"col\">family</th>"
       "<th scope=\"col\" class=\"num\">roughness</th><th scope=\"col\">describes</th></tr></thead>\n<tbody>\n</tbody>\n</table>\n"
       "<p id=\"none\" hidden>No entry matches these filters.</p>\n";
  pager(o, "pager-bottom", false);
  // The head first, then the parts in order: classic scripts run in document order.
  o << "<script src=\"" << kIndexDataFile << "\"></script>\n";
  for (std::size_t k = 0; k < parts; ++k) o << "<script src=\"" << index_part_file(k) << "\"></script>\n";
  o << "<script src=\"assets/index.js\"></script>\n</body>\n</html>\n";
  return o.str();
}

// The JSON inside a file json_statement wrote (its escapes \\ and \' undone), or nullopt.
std::optional<std::string> json_inside(const std::string& script, std::string_view start, std::string_view end) {
  if (script.size() < start.size() + end.size() || script.compare(0, start.size(), start) != 0 ||
      script.compare(script.size() - end.size(), end.size(), end) != 0)
    return std::nullopt;
  std::string t;
  t.reserve(script.size());
  const std::size_t stop = script.size() - end.size();
  for (std::size_t k = start.size(); k < stop;) {
    const std::size_t q = std::min(script.find('\\', k), stop);
    t.append(script, k, q - k);
    if (q == stop) break;
    if (q + 1 == stop) return std::nullopt;
    t += script[q + 1];
    k = q + 2;
  }
  return t;
}

// Six significant digits: the page shows three and filters on bounds typed to two decimals, while a
// computed roughness written exactly often takes 17, which would double this column's size.
std::string roughness_text(const std::optional<double>& r) {
  if (!r) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", *r);
  return nlohmann::json(std::strtod(buf, nullptr)).dump();
}
// Forces and periods to the same six digits: the page compares them in JND steps (12.5 %).
std::string six_digits(double v) { return roughness_text(std::isfinite(v) ? v : 0.0); }

std::string joined(const std::vector<std::string>& values) {
  std::size_t n = 0;
  for (const auto& v : values) n += v.size() + 1;
  std::string out = "[";
  out.reserve(n + 2);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) out += ',';
    out += values[i];
  }
  return out + "]";
}

std::string object_text(const std::map<std::size_t, std::string>& m) {
  std::string o = "{";
  for (const auto& [k, v] : m) o += (o.size() > 1 ? ",\"" : "\"") + std::to_string(k) + "\":" + v;
  return o + "}";
}

std::string part_script(std::size_t k, const PartColumns& c) {
  std::string thumbs = "[";
  for (const auto i : c.no_thumbnail) thumbs += (thumbs.size() > 1 ? "," : "") + std::to_string(i);
  thumbs += "]";
  const std::string j = "{\"aliases\":" + object_text(c.aliases) + ",\"deprecated_by\":" + object_text(c.deprecated_by) +
                        ",\"describes\":" + joined(c.describes) + ",\"family\":" + joined(c.family) +
                        ",\"force_N\":" + joined(c.force) + ",\"format\":3,\"kind\":" + joined(c.kind) +
                        ",\"licence\":" + joined(c.licence) + ",\"name\":" + joined(c.name) +
                        ",\"no_thumbnail\":" + thumbs + ",\"part\":" + std::to_string(k) +
                        ",\"period_m\":" + joined(c.period) + ",\"root\":" + object_text(c.root) +
                        ",\"roughness\":" + joined(c.roughness) + ",\"sources\":" + joined(c.sources) + "}";
  return json_statement(kPartStart, j, kPartEnd);
}

// Counts c's rows into span's counts (over `families` families); std::invalid_argument for a family
// index outside them.
void tally(const PartColumns& c, std::size_t families, PartSpan& span) {
  span.counts.assign(families, 0);
  span.unfiled = 0;
  for (const auto& text : c.family) {
    int f = -2;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), f);
    if (ec != std::errc() || end != text.data() + text.size() || f < -1 || f >= static_cast<int>(families))
      throw std::invalid_argument("a family index outside the list");
    if (f < 0) ++span.unfiled;
    else ++span.counts[static_cast<std::size_t>(f)];
  }
}

// The head's family counts and unfiled entries: the sums over its parts.
void total(Head& h) {
  for (auto& f : h.families) f.count = 0;
  h.unfiled = 0;
  for (const auto& p : h.parts) {
    for (std::size_t f = 0; f < h.families.size(); ++f) h.families[f].count += p.counts.at(f);
    h.unfiled += p.unfiled;
  }
}

std::string head_script(const Head& h) {
  std::string j = "{\"entries\":" + std::to_string(h.entries) + ",\"families\":[";
  for (std::size_t k = 0; k < h.families.size(); ++k)
    j += std::string(k ? "," : "") + "{\"count\":" + std::to_string(h.families[k].count) +
         ",\"id\":" + json_string(h.families[k].id) + (h.families[k].stimulus ? ",\"stimulus\":true" : "") +
         ",\"title\":" + json_string(h.families[k].title) + "}";
  j += "],\"format\":3,\"library\":{\"name\":" + json_string(h.library_name) + ",\"version\":" + json_string(h.version) +
       "},\"part_rows\":" + std::to_string(kIndexPartRows) + ",\"parts\":[";
  for (std::size_t k = 0; k < h.parts.size(); ++k)
  {
    std::string counts;
    for (const int c : h.parts[k].counts) counts += (counts.empty() ? "" : ",") + std::to_string(c);
    j += std::string(k ? "," : "") + "{\"families\":[" + counts + "],\"first\":" + json_string(h.parts[k].first) +
         ",\"last\":" + json_string(h.parts[k].last) + ",\"rows\":" + std::to_string(h.parts[k].rows) +
         ",\"unfiled\":" + std::to_string(h.parts[k].unfiled) + "}";
  }
  j += std::string("],\"sorted\":") + (h.sorted ? "true" : "false") + ",\"unfiled\":" + std::to_string(h.unfiled) + "}";
  return json_statement(kHeadStart, j, kHeadEnd);
}

std::string page_of(const Head& h) {
  return page_html(h.library_name, h.version, h.families, h.entries, h.unfiled > 0, h.parts.size());
}

std::map<std::string, int> index_of(const std::vector<FamilyCount>& families) {
  std::map<std::string, int> out;
  for (const auto& f : families) out.emplace(f.id, static_cast<int>(out.size()));
  return out;
}

// The rows and families of index_data's JSON.
std::vector<IndexRow> rows_of(const nlohmann::json& data) {
  std::vector<IndexRow> rows;
  for (const auto& e : data["entries"]) {
    IndexRow r;
    r.name = e["name"].get<std::string>();
    r.family = e["family"].get<std::string>();
    r.describes = e["describes"].get<std::string>();
    r.deprecated_by = e["deprecated_by"].get<std::string>();
    r.aliases = e["aliases"].get<std::vector<std::string>>();
    if (e["roughness"].is_number()) r.roughness = e["roughness"].get<double>();
    r.max_lateral_force_N = e.value("max_lateral_force_N", 0.0);
    r.period_m = e.value("period_m", 0.0);
    r.kind = e.value("kind", std::string());
    r.source_kinds = e.value("source_kinds", 0u);
    r.root = e.value("root", std::string());
    r.licence = e.value("licence", std::string());
    r.page = e["page"].get<std::string>();
    if (!e["thumbnail"].is_null()) r.thumbnail = e["thumbnail"].get<std::string>();
    rows.push_back(std::move(r));
  }
  return rows;
}

std::vector<FamilyCount> families_of(const nlohmann::json& data) {
  std::vector<FamilyCount> out;
  for (const auto& f : data["families"])
    out.push_back({f["id"].get<std::string>(), f["title"].get<std::string>(), f["describes"].get<std::string>(), f["count"].get<int>(),
                   f.value("stimulus", false)});
  return out;
}

IndexFiles files_of(const std::string& library_name, const std::string& version, std::vector<FamilyCount> families,
                    const std::vector<IndexRow>& rows) {
  Head h;
  h.library_name = library_name;
  h.version = version;
  h.entries = rows.size();
  const auto family_index = index_of(families);
  h.families = std::move(families);
  IndexFiles files;
  for (std::size_t start = 0; start < rows.size(); start += kIndexPartRows) {
    const std::size_t n = std::min(kIndexPartRows, rows.size() - start);
    PartColumns c;
    c.resize(n);
    for (std::size_t i = 0; i < n; ++i) c.set(i, rows[start + i], family_index);
    const std::size_t k = h.parts.size();
    h.parts.push_back({rows[start].name, rows[start + n - 1].name, n, {}, 0});
    tally(c, h.families.size(), h.parts.back());
    files[index_part_file(k)] = part_script(k, c);
  }
  total(h);
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (!(rows[i - 1].name < rows[i].name)) h.sorted = false;
  files[kIndexDataFile] = head_script(h);
  files["index.html"] = page_of(h);
  return files;
}

}  // namespace index_parts

std::string index_part_file(std::size_t part) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s/part-%05zu.js", kIndexPartsFolder, part);
  return buf;
}

IndexFiles index_files(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  return files_of(manifest.name, manifest.version, families_of(manifest, rows), rows);
}

IndexFiles index_files(const nlohmann::json& data) {
  return files_of(data["library"]["name"].get<std::string>(), data["library"]["version"].get<std::string>(), families_of(data),
                  rows_of(data));
}

}  // namespace sandpaper::catalog
