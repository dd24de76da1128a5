#include "entry_inputs.hpp"

#include <set>
#include <variant>

#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/inputs.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

namespace {

class Hasher {
 public:
  Hasher(const compiler::Library& lib, const std::function<std::string(const std::string&)>& file_hash, const std::string& global)
      : lib_(lib), file_hash_(file_hash), global_(global) {}

  const EntryInputs& of(const compiler::LibraryEntry& e) {
    if (auto it = done_.find(&e); it != done_.end()) return it->second;
    EntryInputs out;
    // An entry of a root below, in a layered path: its files are in the lower roots' fingerprints, in
    // `global`. Its chain may still come back to a name this root defines (a world entry `like
    // corduroy` under a lab's corduroy), so what its names resolve to is hashed too.
    if (e.root != 0) {
      if (!visiting_.insert(&e).second) {
        cycle_.hash = "cycle:" + e.name;
        return cycle_;
      }
      std::string in = "below " + lib_.qualified_name(e);
      for (const auto& name : e.likes)
        if (const auto* t = lib_.entry(name)) in += "\nlike " + name + " " + of(*t).hash;
      const auto& ref = lib_.manifest().reference;
      if (e.likes.empty() && !textured(e) && !ref.empty())
        if (const auto* r = lib_.entry(ref); r && r != &e) in += "\nreference " + of(*r).hash;
      visiting_.erase(&e);
      out.hash = stamps::fnv_hex(in);
      return done_[&e] = std::move(out);
    }
    // A `like` cycle: the entry does not compile, and the build reports it; any stable text will do.
    if (!visiting_.insert(&e).second) {
      cycle_.hash = "cycle:" + e.name;
      return cycle_;
    }
    std::string in = global_ + "\nentry " + e.relative_path + " " + file("library/" + e.relative_path, out);
    const bool texture = textured(e);
    for (const auto& st : e.syntax.statements) {
      if (const auto* h = std::get_if<compiler::HeightmapStmt>(&st.node)) {
        const std::filesystem::path p(h->path);
        const auto rel = p.is_absolute()
                             ? p.string()
                             : (std::filesystem::path(e.relative_path).parent_path() / p).lexically_normal().generic_string();
        in += "\nimage " + h->path + " " + file("library/" + rel, out);
        // Its licence and credit, which the catalog's page shows (licences.hpp).
        in += "\nimage-licence " + file("library/" + rel + ".license", out);
      }
    }
    for (const auto& name : e.likes) {
      out.entries.push_back(name);
      if (const auto* t = lib_.entry(name)) in += "\nlike " + name + " " + of(*t).hash;
      // Not an entry: a thesis stimulus, generated from its name and library/thesis/version1.toml.
      else in += "\nlike " + name + " thesis " + file("library/thesis/version1.toml", out);
    }
    const auto& ref = lib_.manifest().reference;
    if (e.likes.empty() && !texture && !ref.empty()) {
      out.entries.push_back(ref);
      if (const auto* r = lib_.entry(ref); r && r->name != e.name) in += "\nreference " + of(*r).hash;
    }
    visiting_.erase(&e);
    out.hash = stamps::fnv_hex(in);
    return done_[&e] = std::move(out);
  }

 private:
  // Whether the entry states a texture of its own (else a bare perceptual description starts from the reference).
  static bool textured(const compiler::LibraryEntry& e) {
    for (const auto& st : e.syntax.statements)
      if (std::holds_alternative<compiler::HeightmapStmt>(st.node) || std::holds_alternative<compiler::GratingStmt>(st.node) ||
          std::holds_alternative<compiler::PatternStmt>(st.node))
        return true;
    return false;
  }
  std::string file(const std::string& path, EntryInputs& out) const {
    out.files.push_back(path);
    return file_hash_(path);
  }
  const compiler::Library& lib_;
  const std::function<std::string(const std::string&)>& file_hash_;
  const std::string& global_;
  std::map<const compiler::LibraryEntry*, EntryInputs> done_;
  std::set<const compiler::LibraryEntry*> visiting_;
  EntryInputs cycle_;
};

}  // namespace

std::map<std::string, EntryInputs> entry_inputs(const compiler::Library& lib,
                                                const std::function<std::string(const std::string&)>& file_hash,
                                                const std::string& global) {
  Hasher h(lib, file_hash, global);
  std::map<std::string, EntryInputs> out;
  for (const auto& e : lib.entries())
    if (e.root == 0 && lib.entry(e.name) == &e) out[e.name] = h.of(e);
  return out;
}

std::map<std::string, std::string> entry_input_hashes(const compiler::Library& lib,
                                                      const std::map<std::string, std::string>& file_hashes,
                                                      const std::string& global) {
  const std::function<std::string(const std::string&)> lookup = [&](const std::string& path) {
    const auto it = file_hashes.find(path);
    return it == file_hashes.end() ? std::string("absent") : it->second;
  };
  std::map<std::string, std::string> out;
  for (auto& [name, in] : entry_inputs(lib, lookup, global)) out[name] = std::move(in.hash);
  return out;
}

std::string global_inputs(const std::map<std::string, std::string>& file_hashes, const std::string& device) {
  std::string global = "sandpaper-library-index/" + std::to_string(kIndexSchemaVersion);
  for (const auto& [path, hash] : file_hashes)
    if (path.rfind("calibration/", 0) == 0 || path == "library/library.toml") global += "\n" + path + " " + hash;
  return global + std::string("\ncompiler ") + SANDPAPER_VERSION + "\ndevice " + device;
}

std::map<std::string, std::string> entry_input_hashes(const compiler::Compiler& compiler, const std::filesystem::path& calibration_dir) {
  const auto& lib = compiler.library();
  if (lib.layered()) return {};
  stamps::Tree tree;
  stamps::walk(lib.directory(), "library", {}, stamps::now_ns(), false, tree);
  stamps::walk(calibration_dir.empty() ? calibration::default_calibration_dir() : calibration_dir, "calibration", {},
               stamps::now_ns(), true, tree);
  std::map<std::string, std::string> files;
  for (const auto& f : tree.files) files[f.path] = f.hash;
  return entry_input_hashes(lib, files, global_inputs(files, compiler.device().name));
}

}  // namespace sandpaper::curation
