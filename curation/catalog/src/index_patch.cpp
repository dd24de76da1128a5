// Rewriting only the parts of the catalog index that a change touches (index_page.hpp, patch_index).
#include <algorithm>
#include <charconv>
#include <map>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "index_parts.hpp"
#include "sandpaper/catalog/index_page.hpp"

namespace sandpaper::catalog {

using namespace index_parts;

namespace {

// Reading a data file's JSON as text: nlohmann's dump(-1) writes no whitespace, so a value's
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

// The part at index k from its text, or BadText.
PartColumns parse_part(const std::string& script, std::size_t k, std::size_t rows) {
  const auto t = json_inside(script, kPartStart, kPartEnd);
  if (!t) throw BadText();
  const auto top = top_level(*t);
  const auto value_of = [&](const char* key) {
    const auto it = top.find(key);
    if (it == top.end()) throw BadText();
    return it->second;
  };
  const auto text_at = [&](std::pair<std::size_t, std::size_t> v) { return t->substr(v.first, v.second - v.first); };
  if (text_at(value_of("format")) != "3" || text_at(value_of("part")) != std::to_string(k)) throw BadText();
  PartColumns c;
  const auto column = [&](const char* key, std::vector<std::string>& out) {
    const auto [b, e] = value_of(key);
    for (const auto& [vb, ve] : elements(*t, b, e)) out.push_back(t->substr(vb, ve - vb));
    if (out.size() != rows) throw BadText();
  };
  column("name", c.name);
  column("family", c.family);
  column("roughness", c.roughness);
  column("describes", c.describes);
  column("licence", c.licence);
  column("sources", c.sources);
  column("force_N", c.force);
  column("period_m", c.period);
  column("kind", c.kind);
  const auto by_row = [&](const char* key, std::map<std::size_t, std::string>& out) {
    const auto [b, e] = value_of(key);
    for (const auto& [row, text] : members(*t, b, e)) {
      const auto i = integer_at<std::size_t>(row, 0, row.size());
      if (i >= rows || std::to_string(i) != row) throw BadText();
      out[i] = text;
    }
  };
  by_row("aliases", c.aliases);
  by_row("deprecated_by", c.deprecated_by);
  by_row("root", c.root);
  const auto [tb, te] = value_of("no_thumbnail");
  for (const auto& [b, e] : elements(*t, tb, te)) {
    const auto i = integer_at<std::size_t>(*t, b, e);
    if (i >= rows) throw BadText();
    c.no_thumbnail.insert(i);
  }
  return c;
}

// A count in the head: a whole number no larger than a library holds. Anything else (a float, a
// negative, 3e78) is not this format; nlohmann's get<int> of such a number would be undefined.
int count_at(const nlohmann::json& v) {
  constexpr std::uint64_t kMaxCount = 1u << 30;
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > kMaxCount) throw BadText();
  return static_cast<int>(v.get<std::uint64_t>());
}

// The head file's contents, or BadText. Checked for depth by the scanner before nlohmann builds it.
Head parse_head(const std::string& script) {
  const auto t = json_inside(script, kHeadStart, kHeadEnd);
  if (!t || t->empty() || skip_value(*t, 0) != t->size()) throw BadText();
  const auto j = nlohmann::json::parse(*t);
  if (j.at("format") != 3 || j.at("part_rows") != kIndexPartRows) throw BadText();
  Head h;
  h.library_name = j.at("library").at("name").get<std::string>();
  h.version = j.at("library").at("version").get<std::string>();
  for (const auto& f : j.at("families"))
    h.families.push_back({f.at("id").get<std::string>(), f.at("title").get<std::string>(), "", count_at(f.at("count")),
                          f.contains("stimulus") && f.at("stimulus").get<bool>()});
  h.entries = static_cast<std::size_t>(count_at(j.at("entries")));
  const auto unfiled = static_cast<std::size_t>(count_at(j.at("unfiled")));
  h.sorted = j.at("sorted").get<bool>();
  std::size_t rows_in_parts = 0;
  for (const auto& p : j.at("parts")) {
    std::vector<int> counts;
    for (const auto& c : p.at("families")) counts.push_back(count_at(c));
    h.parts.push_back({p.at("first").get<std::string>(), p.at("last").get<std::string>(),
                       static_cast<std::size_t>(count_at(p.at("rows"))), std::move(counts),
                       static_cast<std::size_t>(count_at(p.at("unfiled")))});
    if (h.parts.back().counts.size() != h.families.size()) throw BadText();
    // Every part but the last is full, as the whole writer makes them.
    if (h.parts.back().rows == 0 || h.parts.back().rows > kIndexPartRows ||
        (h.parts.size() > 1 && h.parts[h.parts.size() - 2].rows != kIndexPartRows))
      throw BadText();
    rows_in_parts += h.parts.back().rows;
  }
  if (rows_in_parts != h.entries) throw BadText();
  // The totals are the parts' sums (a head whose totals disagree is not one this program wrote).
  Head summed = h;
  total(summed);
  for (std::size_t f = 0; f < h.families.size(); ++f)
    if (summed.families[f].count != h.families[f].count) throw BadText();
  if (summed.unfiled != unfiled) throw BadText();
  h.unfiled = unfiled;
  return h;
}

}  // namespace

std::optional<IndexFiles> patch_index(const ReadIndexFile& read, const compiler::LibraryManifest& manifest,
                                      const std::vector<IndexRow>& changed) {
  try {
    const auto head_text = read(kIndexDataFile);
    if (!head_text) return std::nullopt;
    Head h = parse_head(*head_text);
    if (h.library_name != manifest.name || h.version != manifest.version || h.families.size() < manifest.families.size())
      return std::nullopt;
    for (std::size_t f = 0; f < manifest.families.size(); ++f)
      if (h.families[f].id != manifest.families[f].id || h.families[f].title != manifest.families[f].title ||
          h.families[f].stimulus != manifest.families[f].stimulus_set)
        return std::nullopt;
    const auto family_index = index_of(h.families);
    if (family_index.size() != h.families.size()) return std::nullopt;

    std::map<std::size_t, PartColumns> parts;  // read as needed
    const auto part = [&](std::size_t k) -> PartColumns& {
      auto it = parts.find(k);
      if (it == parts.end()) {
        const auto text = read(index_part_file(k));
        if (!text) throw BadText();
        it = parts.emplace(k, parse_part(*text, k, h.parts[k].rows)).first;
        // The span the head names is the part's own.
        if (it->second.name.front() != json_string(h.parts[k].first) || it->second.name.back() != json_string(h.parts[k].last))
          throw BadText();
      }
      return it->second;
    };
    for (const auto& r : changed) {
      if (!r.family.empty() && !family_index.count(r.family)) return std::nullopt;  // a family the list lacks
      // Sorted names: the one part whose span holds the name. Otherwise each part in turn.
      std::size_t k = 0, k_end = h.parts.size();
      if (h.sorted) {
        const auto it = std::partition_point(h.parts.begin(), h.parts.end(), [&](const PartSpan& p) { return p.last < r.name; });
        if (it == h.parts.end() || r.name < it->first) return std::nullopt;
        k = static_cast<std::size_t>(it - h.parts.begin());
        k_end = k + 1;
      }
      const std::string quoted = json_string(r.name);
      bool found = false;
      for (; k < k_end && !found; ++k) {
        auto& c = part(k);
        const auto at = std::find(c.name.begin(), c.name.end(), quoted);
        if (at == c.name.end()) continue;
        c.set(static_cast<std::size_t>(at - c.name.begin()), r, family_index);
        found = true;
      }
      if (!found) return std::nullopt;
    }
    // The rewritten parts recounted from their rows, the totals summed again.
    for (const auto& [k, c] : parts) tally(c, h.families.size(), h.parts[k]);
    total(h);
    // A family that only entries named and that now has none would leave the list: the whole file is written.
    for (std::size_t f = manifest.families.size(); f < h.families.size(); ++f)
      if (h.families[f].count == 0) return std::nullopt;
    IndexFiles out;
    for (const auto& [k, c] : parts) out[index_part_file(k)] = part_script(k, c);
    out[kIndexDataFile] = head_script(h);
    out["index.html"] = page_of(h);
    return out;
  } catch (const std::exception&) {
    return std::nullopt;  // not files of this format
  }
}

}  // namespace sandpaper::catalog
