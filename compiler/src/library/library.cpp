#include "sandpaper/compiler/library.hpp"
#include "sandpaper/compiler/library_layers.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <toml++/toml.h>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {

const LibraryFamily* LibraryManifest::family(const std::string& family_id) const {
  for (const auto& f : families)
    if (f.id == family_id) return &f;
  return nullptr;
}

void read_entry_metadata(LibraryEntry& e) {
  for (const auto& st : e.syntax.statements) {
    if (const auto* d = std::get_if<DescribesStmt>(&st.node)) e.describes = d->text;
    else if (const auto* f = std::get_if<FamilyStmt>(&st.node)) e.family = f->family;
    else if (const auto* a = std::get_if<AliasStmt>(&st.node)) e.aliases.push_back(a->name);
    else if (const auto* l = std::get_if<LicenceStmt>(&st.node)) e.licence = l->licence;
    else if (const auto* x = std::get_if<DeprecatedStmt>(&st.node)) e.deprecated_by = x->replacement;
    else if (const auto* k = std::get_if<LikeStmt>(&st.node)) e.likes.push_back(k->name);
    else if (std::holds_alternative<OverridesStmt>(st.node)) e.overrides = true;
  }
}

namespace {

// An unreadable or oversized entry reads as empty text, which then fails to parse and is reported
// by the scan like any broken entry.
std::string read_text(const std::filesystem::path& p) {
  try {
    return schema::read_input_file(p, schema::limits::kMaxSourceBytes);
  } catch (const schema::InputFileError&) {
    return {};
  }
}

// A location in the manifest for diagnostics about it.
SourceLocation manifest_location(const std::shared_ptr<const SourceFile>& file, const toml::source_region& r) {
  SourceLocation at;
  at.file = file;
  at.line = static_cast<int>(r.begin.line);
  at.column = static_cast<int>(r.begin.column);
  return at;
}

LibraryManifest read_manifest(const std::filesystem::path& dir, Diagnostics& diags) {
  LibraryManifest m;
  const auto path = dir / "library.toml";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return m;
  m.file = path;
  auto file = std::make_shared<const SourceFile>("library/library.toml", read_text(path));
  toml::table doc;
  try {
    doc = toml::parse(file->text, path.string());
  } catch (const toml::parse_error& err) {
    diags.error("E0601", manifest_location(file, err.source()), std::string("library.toml: ") + std::string(err.description()),
                "fix the TOML syntax (https://toml.io)");
    return m;
  }
  auto text_of = [&](const toml::table& t, const char* key, bool required, const std::string& where) {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required)
        diags.error("E0601", manifest_location(file, t.source()), where + " has no `" + key + "`",
                    std::string("add ") + key + " = \"...\"");
      return std::string();
    }
    if (auto s = n->value<std::string>()) return *s;
    diags.error("E0601", manifest_location(file, n->source()), where + ": `" + key + "` must be a string",
                std::string("write ") + key + " = \"...\"");
    return std::string();
  };
  m.name = text_of(doc, "name", true, "library.toml");
  m.id = text_of(doc, "id", false, "library.toml");
  if (m.id.find_first_of(": \t") != std::string::npos)
    diags.error("E0601", manifest_location(file, doc.get("id")->source()), "library.toml: `id` must be one word without ':'",
                "write id = \"lab\": entries of this root are then named lab:NAME");
  m.version = text_of(doc, "version", true, "library.toml");
  m.reference = text_of(doc, "reference", false, "library.toml");
  if (const auto* fams = doc.get_as<toml::table>("families")) {
    // toml++ keeps keys sorted; the file's order is the display order.
    std::vector<std::pair<std::string, const toml::table*>> ordered;
    for (const auto& [k, v] : *fams) {
      if (const auto* t = v.as_table()) ordered.emplace_back(std::string(k.str()), t);
      else
        diags.error("E0601", manifest_location(file, v.source()), "library.toml: families." + std::string(k.str()) + " must be a table",
                    "write [families." + std::string(k.str()) + "] with title and describes");
    }
    std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
      const auto& ra = a.second->source().begin;
      const auto& rb = b.second->source().begin;
      return ra.line != rb.line ? ra.line < rb.line : ra.column < rb.column;
    });
    for (const auto& [id, t] : ordered) {
      LibraryFamily f{id, text_of(*t, "title", true, "families." + id), text_of(*t, "describes", false, "families." + id)};
      if (const toml::node* n = t->get("stimulus-set")) {
        if (auto b = n->value<bool>()) f.stimulus_set = *b;
        else
          diags.error("E0601", manifest_location(file, n->source()), "families." + id + ": `stimulus-set` must be true or false",
                      "write stimulus-set = true for a published stimulus set whose entries share force levels by design");
      }
      m.families.push_back(std::move(f));
    }
  }
  return m;
}

}  // namespace

Library::Library(std::filesystem::path dir) : Library(std::vector<std::filesystem::path>{std::move(dir)}) {}

Library::Library(std::vector<std::filesystem::path> roots) {
  read_roots(std::move(roots));
  for (std::size_t i = 0; i < roots_.size(); ++i) scan(i);
  index_names();
}

Library::Library(std::filesystem::path dir, const std::vector<std::string>& only_files) {
  read_roots({std::move(dir)});
  scan(0, &only_files);
  index_names();
}

Library::Library(std::vector<std::filesystem::path> roots, const std::vector<std::vector<std::string>>& only_files) {
  read_roots(std::move(roots));
  if (only_files.size() != roots_.size()) throw std::invalid_argument("Library: one list of files per root");
  for (std::size_t i = 0; i < roots_.size(); ++i) scan(i, &only_files[i]);
  index_names();
}

void Library::read_roots(std::vector<std::filesystem::path> roots) {
  if (roots.empty()) roots.push_back(default_library_dir());
  for (auto& dir : roots) {
    LibraryRoot r;
    r.dir = std::move(dir);
    r.manifest = read_manifest(r.dir, scan_diags_);
    r.id = !r.manifest.id.empty() ? r.manifest.id : std::filesystem::path(r.dir).lexically_normal().filename().string();
    if (r.id.empty()) r.id = std::filesystem::absolute(r.dir).lexically_normal().parent_path().filename().string();
    roots_.push_back(std::move(r));
  }
  manifest_ = roots_.front().manifest;
  for (std::size_t i = 1; i < roots_.size(); ++i) {
    const auto& m = roots_[i].manifest;
    if (manifest_.reference.empty()) manifest_.reference = m.reference;
    for (const auto& f : m.families)
      if (!manifest_.family(f.id)) manifest_.families.push_back(f);
  }
}

void Library::index_names() {
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const auto& a, const auto& b) { return a.name != b.name ? a.name < b.name : a.root < b.root; });
  // Two files with one name in a root: the first (in path order) wins here; `library check`
  // reports the clash. Across roots, the front one wins.
  by_root_.resize(roots_.size());
  for (std::size_t i = 0; i < entries_.size(); ++i) by_root_[entries_[i].root].emplace(entries_[i].name, i);
  for (std::size_t i = 0; i < entries_.size(); ++i)
    for (const auto& a : entries_[i].aliases) by_root_[entries_[i].root].emplace(a, i);
  // Each name or alias means what the layered rule says: the first root that knows it.
  const auto knows_in = [this](std::size_t r, const std::string& n) { return knows(r, n); };
  for (const auto& names : by_root_)
    for (const auto& entry : names)
      if (!by_name_.count(entry.first))
        if (const auto hit = layers::resolve(roots_.size(), entry.first, knows_in))
          by_name_.emplace(entry.first, by_root_[hit->first].at(entry.first));
}

void Library::scan(std::size_t root, const std::vector<std::string>* only_files) {
  const auto& dir = roots_[root].dir;
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  if (only_files) {
    for (const auto& rel : *only_files)
      if (std::filesystem::path p = dir / rel; p.extension() == ".hmat" && std::filesystem::is_regular_file(p, ec))
        files.push_back(std::move(p));
  } else {
    for (auto it = std::filesystem::recursive_directory_iterator(dir, ec); !ec && it != std::filesystem::recursive_directory_iterator();
         it.increment(ec)) {
      if (it->is_regular_file() && it->path().extension() == ".hmat") files.push_back(it->path());
    }
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  for (const auto& p : files) {
    LibraryEntry e;
    e.name = p.stem().string();
    e.file = p;
    e.root = root;
    e.relative_path = std::filesystem::relative(p, dir).generic_string();
    // An entry is named by its file's stem and reached by `like NAME` in material text, which is
    // UTF-8 (E0104): a path that is not UTF-8 names an entry nothing can reach, and every JSON and
    // page the library is written into stopped at it (F30). It is reported and not read.
    if (std::size_t bad = 0; !schema::is_valid_utf8(e.relative_path, bad)) {
      SourceLocation at;
      at.file = std::make_shared<const SourceFile>(schema::replace_invalid_utf8(source_name(e)), "");
      scan_diags_.error("E0614", at,
                        "the file's path is not UTF-8 (byte " + std::to_string(bad + 1) +
                            "), so no `like` can name the entry; it is not read",
                        "rename the file (and its folder) in UTF-8, as its `material \"...\"` name is written");
      continue;
    }
    auto file = std::make_shared<const SourceFile>(source_name(e), read_text(p));
    Diagnostics d;
    auto toks = lex(file, d);
    e.syntax = parse(toks, file, d);
    e.parsed_ok = !d.has_errors();
    scan_diags_.append(d);
    read_entry_metadata(e);
    entries_.push_back(std::move(e));
  }
}

std::string Library::qualified_name(const LibraryEntry& e) const {
  return layered() ? roots_[e.root].id + ":" + e.name : e.name;
}

std::string Library::source_name(const LibraryEntry& e) const {
  return layered() ? "library/" + roots_[e.root].id + "/" + e.relative_path : "library/" + e.relative_path;
}

std::optional<std::pair<std::filesystem::path, std::string>> Library::source_file(const std::string& name) const {
  if (name.rfind("library/", 0) != 0) return std::nullopt;
  std::string rest = name.substr(8);
  if (!layered()) return std::make_pair(roots_.front().dir, rest);
  const auto slash = rest.find('/');
  if (slash == std::string::npos) return std::nullopt;
  for (const auto& r : roots_)
    if (r.id == rest.substr(0, slash)) return std::make_pair(r.dir, rest.substr(slash + 1));
  return std::nullopt;
}

std::filesystem::path Library::thesis_directory() const {
  std::error_code ec;
  for (const auto& r : roots_)
    if (std::filesystem::is_regular_file(r.dir / "thesis" / "version1.toml", ec)) return r.dir;
  return roots_.front().dir;
}

std::optional<std::string> Library::knows(std::size_t root, const std::string& name_or_alias) const {
  auto it = by_root_[root].find(name_or_alias);
  if (it == by_root_[root].end()) return std::nullopt;
  return entries_[it->second].name;
}

const LibraryEntry* Library::shadowed_by(const LibraryEntry& e) const {
  std::vector<std::string> names{e.name};
  names.insert(names.end(), e.aliases.begin(), e.aliases.end());
  const auto knows_in = [this](std::size_t r, const std::string& n) { return knows(r, n); };
  const auto hit = layers::hides(e.root, roots_.size(), names, knows_in);
  return hit ? &entries_[by_root_[hit->first].at(hit->second)] : nullptr;
}

std::vector<std::string> Library::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.name);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

const LibraryEntry* Library::entry(const std::string& name_or_alias) const {
  if (const auto colon = name_or_alias.find(':'); colon != std::string::npos) {
    const auto id = name_or_alias.substr(0, colon);
    for (std::size_t r = 0; r < roots_.size(); ++r)
      if (roots_[r].id == id) {
        auto it = by_root_[r].find(name_or_alias.substr(colon + 1));
        return it == by_root_[r].end() ? nullptr : &entries_[it->second];
      }
    return nullptr;
  }
  auto it = by_name_.find(name_or_alias);
  return it == by_name_.end() ? nullptr : &entries_[it->second];
}

std::vector<std::filesystem::path> split_library_path(const std::string& text) {
  std::vector<std::filesystem::path> out;
  std::size_t a = 0;
  while (a <= text.size()) {
    auto b = text.find(':', a);
    if (b == std::string::npos) b = text.size();
    if (b > a) out.emplace_back(text.substr(a, b - a));
    a = b + 1;
  }
  return out;
}

std::vector<std::filesystem::path> default_library_path() {
  if (const char* env = std::getenv("SANDPAPER_LIBRARY_PATH"); env && *env) {
    auto roots = split_library_path(env);
    if (!roots.empty()) return roots;
  }
  return {default_library_dir()};
}

std::optional<std::filesystem::path> Library::find(const std::string& name) const {
  if (const auto* e = entry(name)) return e->file;
  return std::nullopt;
}

std::optional<std::string> Library::canonical_name(const std::string& name) const {
  if (const auto* e = entry(name)) return e->name;
  return std::nullopt;
}

}  // namespace sandpaper::compiler
