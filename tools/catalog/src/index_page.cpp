// The catalog's index page (index_page.hpp).
#include "sandpaper/catalog/index_page.hpp"

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sandpaper/catalog/html.hpp"

namespace sandpaper::catalog {

namespace {

struct FamilyCount {
  std::string id, title, describes;
  int count = 0;
};

// The manifest's families in its order, then any family an entry names that the manifest lacks (by id).
std::vector<FamilyCount> families_of(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  std::map<std::string, int> count;
  for (const auto& r : rows) ++count[r.family];
  std::vector<FamilyCount> out;
  std::set<std::string> listed;
  for (const auto& f : manifest.families) {
    out.push_back({f.id, f.title, f.describes, count[f.id]});
    listed.insert(f.id);
  }
  for (const auto& [id, n] : count)
    if (!id.empty() && listed.insert(id).second) out.push_back({id, id, "", n});
  return out;
}

std::string json_string(const std::string& s) { return nlohmann::json(s).dump(-1, ' ', true); }

}  // namespace

nlohmann::json index_data(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  using nlohmann::json;
  json families = json::array();
  std::map<std::string, std::string> titles;
  for (const auto& f : families_of(manifest, rows)) {
    families.push_back({{"id", f.id}, {"title", f.title}, {"describes", f.describes}, {"count", f.count}});
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
                       {"licence", r.licence},
                       {"deprecated_by", r.deprecated_by},
                       {"page", r.page},
                       {"thumbnail", r.thumbnail.empty() ? json(nullptr) : json(r.thumbnail)}});
  return {{"library", {{"name", manifest.name}, {"version", manifest.version}}},
          {"families", families},
          {"entries", entries}};
}

namespace {

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

}  // namespace

namespace {

std::string page_html(const std::string& library_name, const std::string& version, const std::vector<FamilyCount>& families,
                      std::size_t entries, bool unfiled) {
  const std::string name = library_name.empty() ? "Sandpaper library" : library_name;
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" << html_escape(name)
    << " \xE2\x80\x94 catalog</title>\n<link rel=\"stylesheet\" href=\"assets/catalog.css\">\n"
    // Without JavaScript nothing fills the table, so the filters and the empty table would only mislead.
    << "<noscript><style>#filters, #count, #entries { display: none; }</style></noscript>\n"
    << "</head>\n<body class=\"index\">\n";
  o << "<header><h1>" << html_escape(name) << "</h1>\n<p>" << (version.empty() ? "" : "Version " + html_escape(version) + " \xC2\xB7 ")
    << grouped(entries) << " entries, each a material in three layers (representative, perceptual, physical) with the "
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
    << "<button type=\"button\" id=\"clear\">Show all</button>\n</form>\n";
  o << "<p id=\"count\" aria-live=\"polite\">" << grouped(entries) << " entries</p>\n";
  pager(o, "pager-top", true);
  o << "<table id=\"entries\">\n<thead><tr><th scope=\"col\">picture</th><th scope=\"col\">name</th><th scope=\"col\">family</th>"
       "<th scope=\"col\" class=\"num\">roughness</th><th scope=\"col\">describes</th></tr></thead>\n<tbody>\n</tbody>\n</table>\n"
       "<p id=\"none\" hidden>No entry matches these filters.</p>\n";
  pager(o, "pager-bottom", false);
  o << "<script src=\"" << kIndexDataFile << "\"></script>\n<script src=\"assets/index.js\"></script>\n</body>\n</html>\n";
  return o.str();
}

// The data file's text, written straight from the rows: a JSON tree of 100,000 entries took 2 s
// and 500 MB. The same text as nlohmann's dump(-1, ' ', ensure_ascii) of the object the header
// describes: keys in sorted order, each string and number as nlohmann writes it.
std::string data_script(const std::string& library_name, const std::string& version, const std::vector<FamilyCount>& families,
                        const std::vector<IndexRow>& rows) {
  std::map<std::string, int> family_index;
  for (const auto& f : families) family_index.emplace(f.id, static_cast<int>(family_index.size()));
  std::vector<std::pair<std::string, std::size_t>> aliased, deprecated;  // ("<entry index>", row), sorted as JSON keys are
  std::string names, family, roughness, describes, no_thumbnail;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (r.page != "entries/" + r.name + ".html")
      throw std::invalid_argument("index_data_script: " + r.name + "'s page is not entries/" + r.name + ".html");
    const char* sep = i == 0 ? "" : ",";
    if (r.thumbnail.empty()) no_thumbnail += (no_thumbnail.empty() ? "" : ",") + std::to_string(i);
    else if (r.thumbnail != "entries/" + r.name + "-thumb.png")
      throw std::invalid_argument("index_data_script: " + r.name + "'s thumbnail is not entries/" + r.name + "-thumb.png");
    names += sep + json_string(r.name);
    family += sep + std::to_string(r.family.empty() ? -1 : family_index.at(r.family));
    if (r.roughness) {
      // Six significant digits: the page shows three and filters on bounds typed to two decimals, while
      // a computed roughness written exactly often takes 17, which would double this column's size.
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", *r.roughness);
      roughness += sep + nlohmann::json(std::strtod(buf, nullptr)).dump();
    } else {
      roughness += std::string(sep) + "null";
    }
    describes += sep + json_string(r.describes);
    if (!r.aliases.empty()) aliased.emplace_back(std::to_string(i), i);
    if (!r.deprecated_by.empty()) deprecated.emplace_back(std::to_string(i), i);
  }
  std::sort(aliased.begin(), aliased.end());
  std::sort(deprecated.begin(), deprecated.end());
  std::string j = "{\"aliases\":{";
  for (std::size_t k = 0; k < aliased.size(); ++k) {
    j += (k ? ",\"" : "\"") + aliased[k].first + "\":[";
    const auto& a = rows[aliased[k].second].aliases;
    for (std::size_t m = 0; m < a.size(); ++m) j += (m ? "," : "") + json_string(a[m]);
    j += "]";
  }
  j += "},\"deprecated_by\":{";
  for (std::size_t k = 0; k < deprecated.size(); ++k)
    j += (k ? ",\"" : "\"") + deprecated[k].first + "\":" + json_string(rows[deprecated[k].second].deprecated_by);
  j += "},\"describes\":[" + describes + "],\"families\":[";
  for (std::size_t k = 0; k < families.size(); ++k)
    j += std::string(k ? "," : "") + "{\"id\":" + json_string(families[k].id) + ",\"title\":" + json_string(families[k].title) + "}";
  j += "],\"family\":[" + family + "],\"format\":1,\"library\":{\"name\":" + json_string(library_name) +
       ",\"version\":" + json_string(version) + "},\"name\":[" + names + "],\"no_thumbnail\":[" + no_thumbnail +
       "],\"roughness\":[" + roughness + "]}";
  // JSON.parse of a string literal rather than an object literal: V8 parses JSON faster than
  // JavaScript (a third less time to the first rows at 100,000 entries). The JSON is ASCII (\uXXXX
  // escapes), so that the file reads the same whatever encoding the browser assumes for it, and has no
  // < or >, so that it could be put inside a <script> element unchanged.
  std::string out = "window.sandpaperCatalog = JSON.parse('";
  out.reserve(j.size() + j.size() / 16 + 64);
  for (char c : j) {
    if (c == '<') out += "\\\\u003c";  // \u003c in the JSON, its backslash escaped for the string literal
    else if (c == '>') out += "\\\\u003e";
    else if (c == '\\' || c == '\'') out += {'\\', c};
    else out += c;
  }
  out += "');\n";
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
    r.page = e["page"].get<std::string>();
    if (!e["thumbnail"].is_null()) r.thumbnail = e["thumbnail"].get<std::string>();
    rows.push_back(std::move(r));
  }
  return rows;
}

std::vector<FamilyCount> families_of(const nlohmann::json& data) {
  std::vector<FamilyCount> out;
  for (const auto& f : data["families"])
    out.push_back({f["id"].get<std::string>(), f["title"].get<std::string>(), f["describes"].get<std::string>(), f["count"].get<int>()});
  return out;
}

bool any_unfiled(const std::vector<IndexRow>& rows) {
  return std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.family.empty(); });
}

}  // namespace

std::string index_page_html(const nlohmann::json& data) {
  const auto rows = rows_of(data);
  return page_html(data["library"]["name"].get<std::string>(), data["library"]["version"].get<std::string>(), families_of(data),
                   rows.size(), any_unfiled(rows));
}

std::string index_page_html(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  return page_html(manifest.name, manifest.version, families_of(manifest, rows), rows.size(), any_unfiled(rows));
}

std::string index_data_script(const nlohmann::json& data) {
  return data_script(data["library"]["name"].get<std::string>(), data["library"]["version"].get<std::string>(), families_of(data),
                     rows_of(data));
}

std::string index_data_script(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  return data_script(manifest.name, manifest.version, families_of(manifest, rows), rows);
}

}  // namespace sandpaper::catalog
