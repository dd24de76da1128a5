#include "sandpaper/compiler/library.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {

const LibraryFamily* LibraryManifest::family(const std::string& id) const {
  for (const auto& f : families)
    if (f.id == id) return &f;
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

Library::Library(std::filesystem::path dir) : dir_(std::move(dir)) {
  manifest_ = read_manifest(dir_, scan_diags_);
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  for (auto it = std::filesystem::recursive_directory_iterator(dir_, ec); !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_regular_file() && it->path().extension() == ".hmat") files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& p : files) {
    LibraryEntry e;
    e.name = p.stem().string();
    e.file = p;
    e.relative_path = std::filesystem::relative(p, dir_).generic_string();
    auto file = std::make_shared<const SourceFile>("library/" + e.relative_path, read_text(p));
    Diagnostics d;
    auto toks = lex(file, d);
    e.syntax = parse(toks, file, d);
    e.parsed_ok = !d.has_errors();
    scan_diags_.append(d);
    read_entry_metadata(e);
    entries_.push_back(std::move(e));
  }
  std::sort(entries_.begin(), entries_.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  // Two files with one name: the first (in path order) wins here; `library check` reports the clash.
  for (std::size_t i = 0; i < entries_.size(); ++i) by_name_.emplace(entries_[i].name, i);
  for (std::size_t i = 0; i < entries_.size(); ++i)
    for (const auto& a : entries_[i].aliases) by_name_.emplace(a, i);
}

std::vector<std::string> Library::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.name);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

const LibraryEntry* Library::entry(const std::string& name_or_alias) const {
  auto it = by_name_.find(name_or_alias);
  return it == by_name_.end() ? nullptr : &entries_[it->second];
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
