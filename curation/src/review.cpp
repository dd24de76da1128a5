// `library review` (review.hpp): git says what changed; `library check` of the library now and at
// the base says what is wrong; the entries the change touches decide what fails.
#include "sandpaper/curation/review.hpp"

#include <unistd.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "sandpaper/compiler/library.hpp"
#include "sandpaper/curation/licences.hpp"
#include "subprocess.hpp"

namespace sandpaper::curation {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split_nul(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < s.size()) {
    auto end = s.find('\0', start);
    if (end == std::string::npos) end = s.size();
    if (end > start) out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// A diagnostic's file relative to `root`, or "" if it lies elsewhere.
std::string relative_to(const compiler::Diagnostic& d, const fs::path& root) {
  if (!d.location.file) return "";
  std::error_code ec;
  const auto file = fs::weakly_canonical(fs::absolute(d.location.file->name), ec);
  const auto base = fs::weakly_canonical(root, ec);
  const auto rel = file.lexically_relative(base);
  if (rel.empty() || *rel.begin() == "..") return "";
  return rel.generic_string();
}

void copy_into(compiler::Diagnostics& to, const compiler::Diagnostic& d) {
  compiler::Diagnostics one;
  auto& x = d.severity == compiler::Severity::Error     ? one.error(schema::Code::of(d.code), d.location, d.message, d.suggestion)
            : d.severity == compiler::Severity::Warning ? one.warning(schema::Code::of(d.code), d.location, d.message, d.suggestion)
                                                        : one.accepted(schema::Code::of(d.code), d.location, d.message, d.suggestion);
  x.notes = d.notes;
  to.append(one);
}

// The library folder's file of each entry that uses `image` (relative to the library).
std::string image_of(const compiler::LibraryEntry& e, const compiler::HeightmapStmt& h) {
  return (fs::path(e.relative_path).parent_path() / h.path).lexically_normal().generic_string();
}

// Removes a folder tree when the review ends.
struct TempDir {
  fs::path path;
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

}  // namespace

ReviewResult review_library(const ReviewOptions& options, Progress& progress) {
  ReviewResult r;
  const fs::path lib_dir = fs::absolute(options.library_dir.empty() ? compiler::default_library_dir() : options.library_dir).lexically_normal();
  std::string err;
  const auto top = run_capture({"git", "-C", lib_dir.string(), "rev-parse", "--show-toplevel"}, &err);
  const auto prefix = run_capture({"git", "-C", lib_dir.string(), "rev-parse", "--show-prefix"}, &err);
  if (!top || !prefix) {
    r.error = lib_dir.string() + " is not in a git work tree (library review compares with a commit): " + trim(err);
    return r;
  }
  const std::string root = trim(*top), pre = trim(*prefix);
  if (!run_capture({"git", "-C", root, "rev-parse", "--verify", "--quiet", options.base + "^{commit}"}, &err)) {
    r.error = "no commit '" + options.base + "' in " + root + ": give --base a branch, tag or commit (for a pull request, its target branch)";
    return r;
  }
  // What changed: against the base, in the work tree (committed or not), and files git does not track yet.
  const std::string scope = pre.empty() ? "." : pre;
  const auto diff = run_capture({"git", "-C", root, "diff", "--name-only", "-z", "--no-renames", options.base, "--", scope}, &err);
  const auto fresh = run_capture({"git", "-C", root, "ls-files", "-z", "--others", "--exclude-standard", "--", scope}, &err);
  if (!diff || !fresh) {
    r.error = "git could not list the changes: " + trim(err);
    return r;
  }
  std::set<std::string> changed;
  for (const auto& f : split_nul(*diff + std::string(1, '\0') + *fresh)) {
    if (f.compare(0, pre.size(), pre) != 0) continue;
    const auto rel = f.substr(pre.size());
    if (rel.empty() || rel[0] == '.' || rel.find("/.") != std::string::npos) continue;  // .index/ and other hidden files
    changed.insert(rel);
  }
  r.changed_files.assign(changed.begin(), changed.end());

  // The library at the base, from git's own copy of it.
  TempDir tmp;
  {
    auto t = fs::temp_directory_path() / ("sandpaper-review-" + std::to_string(getpid()));
    fs::create_directories(t);
    tmp.path = t;
  }
  const auto tar = tmp.path / "base.tar";
  if (!run_capture({"git", "-C", root, "archive", "--format=tar", "-o", tar.string(), options.base, "--", scope}, &err) ||
      !run_capture({"tar", "-xf", tar.string(), "-C", tmp.path.string()}, &err)) {
    r.error = "git could not give the library at " + options.base + ": " + trim(err);
    return r;
  }
  const fs::path base_dir = tmp.path / pre;
  std::error_code ec;
  const bool had_base = fs::is_regular_file(base_dir / "library.toml", ec);

  // The entries the change touches.
  const compiler::Library lib(lib_dir);
  std::set<std::string> touched;
  std::set<std::string> removed;
  const bool everything = changed.count("library.toml") > 0;
  for (const auto& f : changed)
    if (fs::path(f).extension() == ".hmat") {
      bool here = false;
      for (const auto& e : lib.entries())
        if (e.relative_path == f) touched.insert(e.name), here = true;
      if (!here) removed.insert(fs::path(f).stem().string());
    }
  for (const auto& e : lib.entries()) {
    if (everything) touched.insert(e.name);
    for (const auto& st : e.syntax.statements)
      if (const auto* h = std::get_if<compiler::HeightmapStmt>(&st.node)) {
        const auto img = image_of(e, *h);
        if (changed.count(img) || changed.count(img + ".license")) touched.insert(e.name);
      }
  }
  // And everything built on them (or on a removed entry), through `like`, by name or alias.
  for (bool grew = true; grew;) {
    grew = false;
    std::set<std::string> names(touched.begin(), touched.end());
    names.insert(removed.begin(), removed.end());
    for (const auto& e : lib.entries())
      if (const auto* t = lib.entry(e.name); t && names.count(t->name))
        for (const auto& a : t->aliases) names.insert(a);
    for (const auto& e : lib.entries())
      if (!touched.count(e.name))
        for (const auto& l : e.likes)
          if (names.count(l)) {
            touched.insert(e.name), grew = true;
            break;
          }
  }
  r.entries.assign(touched.begin(), touched.end());
  std::set<std::string> touched_files;
  for (const auto& e : lib.entries())
    if (touched.count(e.name)) touched_files.insert(e.relative_path);
  for (const auto& f : changed) touched_files.insert(f);  // library.toml, a sidecar: their own diagnostics

  // Check now and at the base, on the same devices.
  CheckOptions now_options{lib_dir, options.calibration_dir, options.devices, {}, {}};
  // The base's entry files are the established ones: a name clash is the newcomer's.
  now_options.established.emplace();
  if (had_base)
    for (const auto& f : fs::recursive_directory_iterator(base_dir, ec))
      if (f.path().extension() == ".hmat") now_options.established->insert(f.path().lexically_relative(base_dir).generic_string());
  const CheckResult now = check_library(now_options, progress);
  r.devices = now.devices.size();
  std::set<std::tuple<std::string, std::string, std::string>> before;
  if (had_base) {
    std::ostringstream sink;
    Progress quiet("checking", 0, true, sink, false);
    const CheckResult then = check_library({base_dir, options.calibration_dir, options.devices, {}, {}}, quiet);
    for (const auto& d : then.diagnostics.all())
      if (d.severity == compiler::Severity::Warning) before.emplace(relative_to(d, base_dir), d.code, d.message);
  }
  for (const auto& d : now.diagnostics.all()) {
    const auto rel = relative_to(d, lib_dir);
    if (!touched_files.count(rel)) continue;
    if (d.severity == compiler::Severity::Warning && before.count({rel, d.code, d.message})) {
      ++r.old_warnings;
      continue;
    }
    copy_into(r.failing, d);
  }
  for (const auto& d : now.accepted.all())
    if (touched_files.count(relative_to(d, lib_dir))) copy_into(r.accepted, d);

  // What no check can judge.
  for (const auto& f : changed) {
    const auto ext = fs::path(f).extension().string();
    if (ext == ".hmat" || f == "library.toml" || ext == ".md") continue;
    const bool exists = fs::is_regular_file(lib_dir / f, ec);
    if (ext == ".license") {
      if (exists) r.by_hand.push_back("image licence " + f + ": is the licence right for the image, and the credit who made it and where it is from?");
      continue;
    }
    if (!exists) continue;
    std::vector<std::string> users;
    for (const auto& e : lib.entries())
      for (const auto& st : e.syntax.statements)
        if (const auto* h = std::get_if<compiler::HeightmapStmt>(&st.node); h && image_of(e, *h) == f) users.push_back(e.name);
    std::string who;
    for (const auto& u : users) who += (who.empty() ? "" : ", ") + u;
    const auto side = read_image_licence(lib_dir / f);
    r.by_hand.push_back("image " + f + (who.empty() ? " (no entry uses it)" : " (used by " + who + ")") +
                        ": look at it: does it show what those entries say, at the size they give it? Licence " +
                        (side && !side->licence.empty() ? side->licence : std::string("not stated")) + ", credit " +
                        (side && !side->credit.empty() ? "\"" + side->credit + "\"" : std::string("not stated")));
  }
  for (const auto& e : lib.entries()) {
    if (!changed.count(e.relative_path)) continue;
    for (const auto& st : e.syntax.statements)
      for (const auto& s : st.sources)
        if (s.kind == compiler::SourceKind::Measurement)
          r.by_hand.push_back("measurement in " + e.relative_path + ":" + std::to_string(s.location.line) + " (" + st.keyword +
                              "): \"" + s.text + "\": who measured it, how, and can the numbers be checked?");
  }
  for (const auto& n : removed)
    r.by_hand.push_back("entry " + n + " is removed: files that say `like " + n +
                        "` stop compiling; deprecate it first (`deprecated replaced-by NAME`) and raise library.toml's major version");
  return r;
}

}  // namespace sandpaper::curation
