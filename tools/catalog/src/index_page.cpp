// The catalog's index page (index_page.hpp).
#include "sandpaper/catalog/index_page.hpp"

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <charconv>
#include <map>
#include <set>
#include <string_view>
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

constexpr std::string_view kScriptHead = "window.sandpaperCatalog = JSON.parse('", kScriptTail = "');\n";

// The data file's text for its JSON.
std::string js_literal(const std::string& json_text) {
  std::string out(kScriptHead);
  out.reserve(json_text.size() + json_text.size() / 16 + 64);
  // Copied in runs between the characters that need escaping (a 4.7 MB file has few of them).
  for (std::size_t p = 0; p < json_text.size();) {
    const std::size_t q = std::min(json_text.find_first_of("<>\\'", p), json_text.size());
    out.append(json_text, p, q - p);
    if (q == json_text.size()) break;
    const char c = json_text[q];
    if (c == '<') out += "\\\\u003c";  // \u003c in the JSON, its backslash escaped for the string literal
    else if (c == '>') out += "\\\\u003e";
    else out += {'\\', c};
    p = q + 1;
  }
  out += kScriptTail;
  return out;
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
  return js_literal(j);
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

namespace {

// Reading the data file's JSON as text: nlohmann's dump(-1) writes no whitespace, so a value's
// extent is found by scanning it, without building a tree of 100,000 entries (0.6 s).
struct BadText : std::runtime_error {
  BadText() : std::runtime_error("not a data file of this format") {}
};

// The position just past the JSON value that starts at `p`. The format nests three deep; a file
// nested deeper is not one (and would otherwise take the stack).
std::size_t skip_value(const std::string& t, std::size_t p, int depth = 0) {
  if (p >= t.size() || depth > 8) throw BadText();
  const char c = t[p];
  if (c == '"') {
    for (++p; p < t.size() && t[p] != '"'; ++p)
      if (t[p] == '\\') ++p;
    if (p >= t.size()) throw BadText();
    return p + 1;
  }
  if (c == '[' || c == '{') {
    const char close = c == '[' ? ']' : '}';
    ++p;
    while (p < t.size() && t[p] != close) {
      if (c == '{') {  // "key":
        p = skip_value(t, p, depth + 1);
        if (p >= t.size() || t[p] != ':') throw BadText();
        ++p;
      }
      p = skip_value(t, p, depth + 1);
      if (p < t.size() && t[p] == ',') ++p;
      else if (p >= t.size() || t[p] != close) throw BadText();
    }
    if (p >= t.size()) throw BadText();
    return p + 1;
  }
  const std::size_t start = p;
  while (p < t.size() && t[p] != ',' && t[p] != ']' && t[p] != '}') ++p;
  if (p == start) throw BadText();
  return p;
}

// The [begin, end) of every top-level key's value, in one walk over the text.
std::map<std::string, std::pair<std::size_t, std::size_t>> top_level(const std::string& t) {
  if (t.empty() || t[0] != '{') throw BadText();
  std::map<std::string, std::pair<std::size_t, std::size_t>> out;
  std::size_t p = 1;
  while (p < t.size() && t[p] != '}') {
    const std::size_t key_end = skip_value(t, p);
    if (key_end >= t.size() || t[key_end] != ':' || key_end < p + 2) throw BadText();
    const std::size_t v = key_end + 1, v_end = skip_value(t, v);
    out[t.substr(p + 1, key_end - p - 2)] = {v, v_end};
    p = v_end < t.size() && t[v_end] == ',' ? v_end + 1 : v_end;
  }
  return out;
}

// The integer at [b, e), read in place (a substring and std::stoi for each of 100,000 rows cost
// more than the rest of the patch).
template <class Int>
Int integer_at(const std::string& t, std::size_t b, std::size_t e) {
  Int v{};
  const auto [end, ec] = std::from_chars(t.data() + b, t.data() + e, v);
  if (ec != std::errc() || end != t.data() + e) throw BadText();
  return v;
}

// The elements of the array at [b, e) as [begin, end) pairs.
std::vector<std::pair<std::size_t, std::size_t>> elements(const std::string& t, std::size_t b, std::size_t e) {
  if (t[b] != '[') throw BadText();
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t p = b + 1; p < e - 1;) {
    const std::size_t q = skip_value(t, p);
    out.emplace_back(p, q);
    p = q + 1;
  }
  return out;
}

// The members of the object at [b, e): key (unquoted, as the index is written) -> value text.
std::map<std::string, std::string> members(const std::string& t, std::size_t b, std::size_t e) {
  if (t[b] != '{') throw BadText();
  std::map<std::string, std::string> out;
  for (std::size_t p = b + 1; p < e - 1;) {
    const std::size_t k = skip_value(t, p);
    const std::size_t v = skip_value(t, k + 1);
    out.emplace(t.substr(p + 1, k - p - 2), t.substr(k + 1, v - k - 1));
    p = v + 1;
  }
  return out;
}

}  // namespace

std::optional<PatchedIndex> patch_index(const std::string& script, const compiler::LibraryManifest& manifest,
                                        const std::vector<IndexRow>& changed) {
  using nlohmann::json;
  if (script.size() < kScriptHead.size() + kScriptTail.size() || script.compare(0, kScriptHead.size(), kScriptHead) != 0 ||
      script.compare(script.size() - kScriptTail.size(), kScriptTail.size(), kScriptTail) != 0)
    return std::nullopt;
  // The string literal's escapes undone: \\ and \' (js_literal writes no other).
  std::string t;
  t.reserve(script.size());
  const std::size_t end = script.size() - kScriptTail.size();
  for (std::size_t k = kScriptHead.size(); k < end;) {
    const std::size_t q = std::min(script.find('\\', k), end);
    t.append(script, k, q - k);
    if (q == end) break;
    if (q + 1 == end) return std::nullopt;
    t += script[q + 1];
    k = q + 2;
  }
  try {
    const auto top = top_level(t);
    const auto value_of = [&](const char* key) { return top.at(key); };  // std::out_of_range: not this format
    const auto [fb, fe] = value_of("families");
    const json families = json::parse(t.substr(fb, fe - fb));
    if (families.size() < manifest.families.size()) return std::nullopt;
    std::map<std::string, int> family_index;
    for (std::size_t f = 0; f < families.size(); ++f) {
      if (f < manifest.families.size() &&
          (families[f].at("id") != manifest.families[f].id || families[f].at("title") != manifest.families[f].title))
        return std::nullopt;
      family_index.emplace(families[f].at("id").get<std::string>(), static_cast<int>(f));
    }
    if (const auto [ob, oe] = value_of("format"); t.compare(ob, oe - ob, "1") != 0) return std::nullopt;
    const auto [nb, ne] = value_of("name");
    const auto [cb, ce] = value_of("family");
    const auto [rb, re] = value_of("roughness");
    const auto [db, de] = value_of("describes");
    const auto [ab, ae] = value_of("aliases");
    const auto [xb, xe] = value_of("deprecated_by");
    const auto [tb, te] = value_of("no_thumbnail");
    const auto names = elements(t, nb, ne);
    auto family = elements(t, cb, ce);
    const auto roughness = elements(t, rb, re), describes = elements(t, db, de);
    if (family.size() != names.size() || roughness.size() != names.size() || describes.size() != names.size()) return std::nullopt;
    // Only the changed rows' names are looked for: a map of all 100,000 cost more than the scan.
    std::map<std::string, std::size_t, std::less<>> at;
    for (const auto& r : changed) at.emplace(json_string(r.name), names.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string_view name(t.data() + names[i].first, names[i].second - names[i].first);
      if (const auto it = at.find(name); it != at.end() && it->second == names.size()) it->second = i;
    }
    auto aliases = members(t, ab, ae), deprecated = members(t, xb, xe);
    std::set<std::size_t> thumbless;
    for (const auto& [b, e] : elements(t, tb, te)) thumbless.insert(integer_at<std::size_t>(t, b, e));

    std::map<std::size_t, std::pair<std::size_t, std::string>> edits;  // begin -> (end, new text)
    std::map<std::size_t, int> new_family;
    for (const auto& r : changed) {
      const auto it = at.find(json_string(r.name));  // names as the file has them: JSON strings
      if (it == at.end() || it->second == names.size() || r.page != "entries/" + r.name + ".html") return std::nullopt;
      if (!r.thumbnail.empty() && r.thumbnail != "entries/" + r.name + "-thumb.png") return std::nullopt;
      const std::size_t i = it->second;
      const std::string key = std::to_string(i);
      int f = -1;
      if (!r.family.empty()) {
        const auto fi = family_index.find(r.family);
        if (fi == family_index.end()) return std::nullopt;  // a family the list lacks: the whole file is written
        f = fi->second;
      }
      new_family[i] = f;
      edits[family[i].first] = {family[i].second, std::to_string(f)};
      std::string rough = "null";
      if (r.roughness) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", *r.roughness);
        rough = json(std::strtod(buf, nullptr)).dump();
      }
      edits[roughness[i].first] = {roughness[i].second, rough};
      edits[describes[i].first] = {describes[i].second, json_string(r.describes)};
      if (r.aliases.empty()) aliases.erase(key);
      else aliases[key] = json(r.aliases).dump(-1, ' ', true);
      if (r.deprecated_by.empty()) deprecated.erase(key);
      else deprecated[key] = json_string(r.deprecated_by);
      if (r.thumbnail.empty()) thumbless.insert(i);
      else thumbless.erase(i);
    }
    auto object = [](const std::map<std::string, std::string>& m) {
      std::string o = "{";
      for (const auto& [k, v] : m) o += (o.size() > 1 ? ",\"" : "\"") + k + "\":" + v;
      return o + "}";
    };
    std::string thumbs = "[";
    for (const auto i : thumbless) thumbs += (thumbs.size() > 1 ? "," : "") + std::to_string(i);
    thumbs += "]";
    edits[ab] = {ae, object(aliases)};
    edits[xb] = {xe, object(deprecated)};
    edits[tb] = {te, thumbs};
    std::string out;
    out.reserve(t.size() + 4096);
    std::size_t p = 0;
    for (const auto& [b, e_text] : edits) {
      out.append(t, p, b - p);
      out += e_text.second;
      p = e_text.first;
    }
    out.append(t, p, std::string::npos);

    // The page's family counts; a family only entries named that now has none: the whole file is written.
    std::vector<FamilyCount> counts;
    for (const auto& f : families) counts.push_back({f.at("id").get<std::string>(), f.at("title").get<std::string>(), "", 0});
    bool unfiled = false;
    for (std::size_t i = 0; i < family.size(); ++i) {
      const auto nf = new_family.find(i);
      const int v = nf != new_family.end() ? nf->second : integer_at<int>(t, family[i].first, family[i].second);
      if (v < 0) unfiled = true;
      else if (static_cast<std::size_t>(v) < counts.size()) ++counts[static_cast<std::size_t>(v)].count;
      else return std::nullopt;
    }
    for (std::size_t f = manifest.families.size(); f < counts.size(); ++f)
      if (counts[f].count == 0) return std::nullopt;
    const auto [lb, le] = value_of("library");
    const json library = json::parse(t.substr(lb, le - lb));
    PatchedIndex result;
    result.script = js_literal(out);
    result.page = page_html(library.at("name").get<std::string>(), library.at("version").get<std::string>(), counts, names.size(), unfiled);
    return result;
  } catch (const std::exception&) {
    return std::nullopt;  // not a data file of this format
  }
}

}  // namespace sandpaper::catalog
