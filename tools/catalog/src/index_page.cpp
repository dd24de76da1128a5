// The catalog's index page (index_page.hpp).
#include "sandpaper/catalog/index_page.hpp"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sandpaper/catalog/html.hpp"

namespace sandpaper::catalog {

nlohmann::json index_data(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows) {
  using nlohmann::json;
  std::map<std::string, int> count;
  for (const auto& r : rows) ++count[r.family];
  json families = json::array();
  std::map<std::string, std::string> titles;
  for (const auto& f : manifest.families) {
    families.push_back({{"id", f.id}, {"title", f.title}, {"describes", f.describes}, {"count", count[f.id]}});
    titles[f.id] = f.title;
  }
  for (const auto& [id, n] : count)
    if (!id.empty() && !titles.count(id)) {
      families.push_back({{"id", id}, {"title", id}, {"describes", ""}, {"count", n}});
      titles[id] = id;
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

std::string index_page_html(const nlohmann::json& data) {
  const std::string name = data["library"]["name"].get<std::string>().empty() ? "Sandpaper library"
                                                                              : data["library"]["name"].get<std::string>();
  const std::string version = data["library"]["version"].get<std::string>();
  const auto& entries = data["entries"];
  bool unfiled = false;
  for (const auto& e : entries) unfiled = unfiled || e["family"].get<std::string>().empty();
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" << html_escape(name)
    << " \xE2\x80\x94 catalog</title>\n<link rel=\"stylesheet\" href=\"assets/catalog.css\">\n"
    // Without JavaScript nothing fills the table, so the filters and the empty table would only mislead.
    << "<noscript><style>#filters, #count, #entries { display: none; }</style></noscript>\n"
    << "</head>\n<body class=\"index\">\n";
  o << "<header><h1>" << html_escape(name) << "</h1>\n<p>" << (version.empty() ? "" : "Version " + html_escape(version) + " \xC2\xB7 ")
    << grouped(entries.size()) << " entries, each a material in three layers (representative, perceptual, physical) with the "
       "source of every number. Roughness is on the calibrated ratio scale (0.1 very fine \xE2\x80\xA6 1 the strongest "
       "calibrated stimulus).</p>\n</header>\n";
  o << "<noscript><p class=\"noscript\">This index needs JavaScript to list, filter and page through the entries. "
       "Without it, open the entries' own pages: each is <code>entries/&lt;name&gt;.html</code> beside this page "
       "(<a href=\"entries/\">entries/</a>).</p></noscript>\n";
  o << "<form id=\"filters\" role=\"search\" onsubmit=\"return false\">\n"
    << "<label>Family <select id=\"family\" name=\"family\">\n<option value=\"\">all families</option>\n";
  for (const auto& f : data["families"])
    o << "<option value=\"" << html_escape(f["id"].get<std::string>()) << "\">" << html_escape(f["title"].get<std::string>())
      << " (" << f["count"].get<int>() << ")</option>\n";
  if (unfiled) o << "<option value=\"(none)\">no family</option>\n";
  o << "</select></label>\n"
    << "<fieldset class=\"range\"><legend>Roughness</legend><label>from <input id=\"rmin\" name=\"rmin\" type=\"number\" "
       "min=\"0\" step=\"0.01\" inputmode=\"decimal\" placeholder=\"0\"></label> <label>to <input id=\"rmax\" name=\"rmax\" "
       "type=\"number\" min=\"0\" step=\"0.01\" inputmode=\"decimal\" placeholder=\"any\"></label></fieldset>\n"
    << "<label>Words <input id=\"q\" name=\"q\" type=\"search\" placeholder=\"name, alias or description\"></label>\n"
    << "<button type=\"button\" id=\"clear\">Show all</button>\n</form>\n";
  o << "<p id=\"count\" aria-live=\"polite\">" << grouped(entries.size()) << " entries</p>\n";
  pager(o, "pager-top", true);
  o << "<table id=\"entries\">\n<thead><tr><th scope=\"col\">picture</th><th scope=\"col\">name</th><th scope=\"col\">family</th>"
       "<th scope=\"col\" class=\"num\">roughness</th><th scope=\"col\">describes</th></tr></thead>\n<tbody>\n</tbody>\n</table>\n"
       "<p id=\"none\" hidden>No entry matches these filters.</p>\n";
  pager(o, "pager-bottom", false);
  o << "<script src=\"" << kIndexDataFile << "\"></script>\n<script src=\"assets/index.js\"></script>\n</body>\n</html>\n";
  return o.str();
}

std::string index_data_script(const nlohmann::json& data) {
  using nlohmann::json;
  json families = json::array();
  std::map<std::string, int> family_index;
  for (const auto& f : data["families"]) {
    family_index[f["id"].get<std::string>()] = static_cast<int>(families.size());
    families.push_back({{"id", f["id"]}, {"title", f["title"]}});
  }
  json names = json::array(), family = json::array(), roughness = json::array(), describes = json::array();
  json aliases = json::object(), deprecated_by = json::object(), no_thumbnail = json::array();
  int i = 0;
  for (const auto& e : data["entries"]) {
    const std::string n = e["name"].get<std::string>();
    if (e["page"].get<std::string>() != "entries/" + n + ".html")
      throw std::invalid_argument("index_data_script: " + n + "'s page is not entries/" + n + ".html");
    if (e["thumbnail"].is_null()) no_thumbnail.push_back(i);
    else if (e["thumbnail"].get<std::string>() != "entries/" + n + "-thumb.png")
      throw std::invalid_argument("index_data_script: " + n + "'s thumbnail is not entries/" + n + "-thumb.png");
    names.push_back(n);
    const std::string f = e["family"].get<std::string>();
    family.push_back(f.empty() ? -1 : family_index.at(f));
    if (e["roughness"].is_number()) {
      // Six significant digits: the page shows three and filters on bounds typed to two decimals, while
      // a computed roughness written exactly often takes 17, which would double this column's size.
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", e["roughness"].get<double>());
      roughness.push_back(std::strtod(buf, nullptr));
    } else {
      roughness.push_back(nullptr);
    }
    describes.push_back(e["describes"]);
    if (!e["aliases"].empty()) aliases[std::to_string(i)] = e["aliases"];
    if (!e["deprecated_by"].get<std::string>().empty()) deprecated_by[std::to_string(i)] = e["deprecated_by"];
    ++i;
  }
  const json compact = {{"format", 1},
                        {"library", data["library"]},
                        {"families", families},
                        {"name", names},
                        {"family", family},
                        {"roughness", roughness},
                        {"describes", describes},
                        {"aliases", aliases},
                        {"deprecated_by", deprecated_by},
                        {"no_thumbnail", no_thumbnail}};
  // JSON.parse of a string literal rather than an object literal: V8 parses JSON faster than
  // JavaScript (a third less time to the first rows at 100,000 entries). The JSON is ASCII (\uXXXX
  // escapes), so that the file reads the same whatever encoding the browser assumes for it, and has no
  // < or >, so that it could be put inside a <script> element unchanged.
  std::string out = "window.sandpaperCatalog = JSON.parse('";
  for (char c : compact.dump(-1, ' ', true)) {
    if (c == '<') out += "\\\\u003c";  // \u003c in the JSON, its backslash escaped for the string literal
    else if (c == '>') out += "\\\\u003e";
    else if (c == '\\' || c == '\'') out += {'\\', c};
    else out += c;
  }
  out += "');\n";
  return out;
}

}  // namespace sandpaper::catalog
