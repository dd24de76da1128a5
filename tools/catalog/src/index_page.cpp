// The catalog's index page (index_page.hpp).
#include "sandpaper/catalog/index_page.hpp"

#include <map>
#include <sstream>

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
    << " \xE2\x80\x94 catalog</title>\n<link rel=\"stylesheet\" href=\"assets/catalog.css\">\n</head>\n<body class=\"index\">\n";
  o << "<header><h1>" << html_escape(name) << "</h1>\n<p>" << (version.empty() ? "" : "Version " + html_escape(version) + " \xC2\xB7 ")
    << entries.size() << " entries, each a material in three layers (representative, perceptual, physical) with the "
       "source of every number. Roughness is on the calibrated ratio scale (0.1 very fine \xE2\x80\xA6 1 the strongest "
       "calibrated stimulus).</p>\n</header>\n";
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
  o << "<p id=\"count\" aria-live=\"polite\">" << entries.size() << " entries</p>\n";
  o << "<table id=\"entries\">\n<thead><tr><th scope=\"col\">picture</th><th scope=\"col\">name</th><th scope=\"col\">family</th>"
       "<th scope=\"col\" class=\"num\">roughness</th><th scope=\"col\">describes</th></tr></thead>\n<tbody>\n";
  for (const auto& e : entries) {
    const std::string n = e["name"].get<std::string>();
    const std::string page = e["page"].get<std::string>();
    o << "<tr data-name=\"" << html_escape(n) << "\"" << (e["deprecated_by"].get<std::string>().empty() ? "" : " class=\"deprecated\"")
      << ">\n<td class=\"thumb\">";
    if (e["thumbnail"].is_string())
      o << "<a href=\"" << html_escape(page) << "\" tabindex=\"-1\"><img src=\"" << html_escape(e["thumbnail"].get<std::string>())
        << "\" alt=\"\"></a>";
    else
      o << "<span class=\"no-thumb\" title=\"no position-dependent force to draw\">\xE2\x80\x94</span>";
    o << "</td>\n<td class=\"name\"><a href=\"" << html_escape(page) << "\">" << html_escape(n) << "</a>";
    if (!e["aliases"].empty()) {
      o << "<div class=\"aliases\">";
      bool first = true;
      for (const auto& a : e["aliases"]) {
        o << (first ? "" : ", ") << html_escape(a.get<std::string>());
        first = false;
      }
      o << "</div>";
    }
    if (!e["deprecated_by"].get<std::string>().empty())
      o << "<div class=\"deprecated-tag\">deprecated: use " << html_escape(e["deprecated_by"].get<std::string>()) << "</div>";
    const std::string ftitle = e["family_title"].get<std::string>();
    o << "</td>\n<td class=\"family\">" << (ftitle.empty() ? "<span class=\"muted\">\xE2\x80\x94</span>" : html_escape(ftitle)) << "</td>\n<td class=\"num\">"
      << (e["roughness"].is_number() ? format_number(e["roughness"].get<double>(), 3) : "\xE2\x80\x94") << "</td>\n<td>"
      << html_escape(e["describes"].get<std::string>()) << "</td>\n</tr>\n";
  }
  o << "</tbody>\n</table>\n<p id=\"none\" hidden>No entry matches these filters.</p>\n";
  o << "<script type=\"application/json\" id=\"catalog-data\">" << json_for_script(data) << "</script>\n"
    << "<script src=\"assets/index.js\"></script>\n</body>\n</html>\n";
  return o.str();
}

}  // namespace sandpaper::catalog
