// layered_inputs and layered_files_reached (layers.hpp): what a layered library's catalog compares
// and reads, taken off each root's index so that nothing grows with the library but reading the
// hashes.
#include <algorithm>
#include <deque>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "sandpaper/curation/layers.hpp"
#include "sqlite_util.hpp"
#include "affected.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

namespace {

std::string file_hash(const Index& idx, const std::string& path) {
  sql::Stmt s(idx.handle(), "SELECT hash FROM files WHERE path = ?");
  s.bind(1, path);
  return s.step() ? s.text(0) : std::string("absent");
}

// An entry's hash over the path: what its own root's index hashed, and for an entry that reaches
// the roots in front of its own (`affected`), what each name it builds on resolves to over the path,
// hashed the same way, recursively; its replacement link; the path's reference and the thesis'
// readings where a root in front supplies them.
class PathHasher {
 public:
  PathHasher(const LayeredIndex& idx, std::string global, const std::vector<std::set<std::string>>& affected, std::size_t thesis,
             std::string thesis_hash)
      // What every entry shares goes in as its hash: at 100,000 entries, hashing it whole for each took 0.1 s.
      : idx_(idx), global_(stamps::fnv_hex(global)), affected_(affected), thesis_(thesis), thesis_hash_(std::move(thesis_hash)) {
    reference_ = idx.size() ? idx.index(0).meta("library_reference") : std::string();
    for (std::size_t i = 0; i < idx.size(); ++i) {
      own_hash_.push_back(std::make_unique<sql::Stmt>(idx.index(i).handle(), "SELECT hash FROM inputs WHERE name = ?"));
      builds_on_.push_back(std::make_unique<sql::Stmt>(idx.index(i).handle(), "SELECT target FROM depends WHERE name = ? AND kind = 'entry' ORDER BY target"));
      replaced_by_.push_back(std::make_unique<sql::Stmt>(idx.index(i).handle(), "SELECT deprecated_by FROM entries WHERE name = ?"));
    }
  }
  // `own`: the entry's hash in its root's index, if the caller has it (else it is looked up).
  std::string of(std::size_t layer, const std::string& name, const std::string* own = nullptr) {
    const bool affected = affected_[layer].count(name) > 0;
    // Most entries: nothing to remember, nothing else to read.
    if (own && !affected) return stamps::fnv_hex(global_ + "\nentry " + idx_.id(layer) + ":" + name + " " + *own);
    const auto key = std::make_pair(layer, name);
    if (const auto it = done_.find(key); it != done_.end()) return it->second;
    std::string looked_up = "absent";
    if (!own) {
      auto& h = *own_hash_[layer];
      h.bind(1, name);
      if (h.step()) looked_up = h.text(0);
      h.reset();
    }
    std::string in = global_ + "\nentry " + idx_.id(layer) + ":" + name + " " + (own ? *own : looked_up);
    if (affected) {
      if (!visiting_.insert(key).second) return "cycle";  // the build reports a `like` cycle; any stable text will do
      std::vector<std::string> targets;
      auto& b = *builds_on_[layer];
      b.bind(1, name);
      while (b.step()) targets.push_back(b.text(0));
      b.reset();
      for (const auto& t : targets) in += "\nlike " + t + " " + resolved(t);
      auto& d = *replaced_by_[layer];
      d.bind(1, name);
      if (d.step() && !d.text(0).empty()) {
        const auto at = idx_.resolve(d.text(0));
        in += "\nreplaced-by " + (at ? idx_.id(at->first) + ":" + at->second : std::string("none"));
      }
      d.reset();
      if (const auto own_ref = idx_.index(layer).meta("library_reference"); own_ref != reference_)
        in += "\nreference " + reference_ + " " + resolved(reference_);
      if (thesis_ < layer) in += "\nthesis " + thesis_hash_;
      visiting_.erase(key);
    }
    return done_[key] = stamps::fnv_hex(in);
  }

 private:
  std::string resolved(const std::string& name) {
    const auto at = idx_.resolve(name);
    return at ? of(at->first, at->second) : std::string("none");  // a thesis stimulus, or the compiler's error
  }
  const LayeredIndex& idx_;
  std::string global_, reference_;
  const std::vector<std::set<std::string>>& affected_;
  std::size_t thesis_;
  std::string thesis_hash_;
  std::vector<std::unique_ptr<sql::Stmt>> own_hash_, builds_on_, replaced_by_;
  std::map<std::pair<std::size_t, std::string>, std::string> done_;
  std::set<std::pair<std::size_t, std::string>> visiting_;
};

}  // namespace

LayeredInputs layered_inputs(const LayeredIndex& idx, const std::vector<std::filesystem::path>& roots,
                             const std::vector<std::string>* bottom_names) {
  LayeredInputs r;
  const std::size_t n = idx.size();
  const std::size_t thesis = thesis_root(roots);
  // What every page shares: the roots, in order (entries are shown as ID:NAME, their files as
  // library/ID/...), every root's library.toml (the front one names the whole, families are the
  // union, the reference is the first declared) and which root the thesis' readings come from.
  std::string global = "sandpaper-layered-catalog/1";
  for (std::size_t i = 0; i < n; ++i) {
    global += "\nroot " + idx.id(i) + " " + std::filesystem::absolute(roots.at(i)).lexically_normal().string() + " " +
              file_hash(idx.index(i), "library/library.toml");
  }
  global += "\nthesis " + std::to_string(thesis);
  r.global = stamps::fnv_hex(global);
  std::vector<std::string> fingerprints;
  for (std::size_t i = 0; i < n; ++i) fingerprints.push_back(idx.index(i).meta("fingerprint"));
  r.fingerprint = layered_fingerprint(r.global, idx, fingerprints);
  const std::string reference = n ? idx.index(0).meta("library_reference") : std::string();

  const auto affected = path_affected(idx, roots);

  PathHasher hasher(idx, global, affected, thesis, thesis < n ? file_hash(idx.index(thesis), "library/thesis/version1.toml") : "none");
  // What the path shows: an entry not hidden by a name or alias of a root in front.
  std::unordered_set<std::string> in_front;
  for (std::size_t layer = 0; layer < n; ++layer) {
    const bool some = bottom_names && layer + 1 == n && n > 0;
    if (some) {
      // Only these of the bottom root (and its affected entries), and how many it shows in all: the
      // entries it has less those a root in front hides.
      std::set<std::string> names(bottom_names->begin(), bottom_names->end());
      names.insert(affected[layer].begin(), affected[layer].end());
      const auto& bottom = idx.index(layer);
      std::size_t hidden = 0;
      for (const auto& name : in_front) hidden += bottom.input_hash(name).has_value();
      r.shown = r.entries.size() + bottom.size() - hidden;
      for (const auto& name : names) {
        auto hash = bottom.input_hash(name);
        if (!hash) {
          r.gone = true;
          continue;
        }
        if (in_front.count(name)) continue;
        r.affected += affected[layer].count(name);
        r.entries.emplace_back(name, hasher.of(layer, name, &*hash));
      }
      break;
    }
    for (auto& [name, hash] : idx.index(layer).input_hashes()) {
      if (in_front.count(name)) continue;
      r.affected += affected[layer].count(name);
      hash = hasher.of(layer, name, &hash);
      r.entries.emplace_back(std::move(name), std::move(hash));
    }
    if (layer + 1 < n)
      for (auto& name : idx.index(layer).names_and_aliases()) in_front.insert(std::move(name));
  }
  if (!bottom_names) r.shown = r.entries.size();
  std::sort(r.entries.begin(), r.entries.end());
  return r;
}

std::string layered_fingerprint(const std::string& global, const LayeredIndex& idx, const std::vector<std::string>& fingerprints) {
  std::string out = "global " + global + "\n";
  for (std::size_t i = 0; i < idx.size(); ++i) out += idx.id(i) + " " + (i < fingerprints.size() ? fingerprints[i] : "") + "\n";
  return out;
}

std::vector<std::vector<std::string>> layered_files_reached(const LayeredIndex& idx, const std::vector<std::string>& names) {
  std::vector<std::set<std::string>> files(idx.size());
  std::vector<std::unique_ptr<sql::Stmt>> builds_on, file_of;
  for (std::size_t i = 0; i < idx.size(); ++i) {
    builds_on.push_back(std::make_unique<sql::Stmt>(idx.index(i).handle(), "SELECT target FROM depends WHERE name = ? AND kind = 'entry'"));
    file_of.push_back(std::make_unique<sql::Stmt>(idx.index(i).handle(), "SELECT file, deprecated_by FROM entries WHERE name = ?"));
  }
  // Down the chains, every name resolved as the compiler resolves it over the path; the entries the
  // drawn ones link to as their replacement are read too, without what they are built on.
  std::deque<std::string> down(names.begin(), names.end());
  if (idx.size())
    if (const auto ref = idx.index(0).meta("library_reference"); !ref.empty()) down.push_back(ref);
  std::vector<std::string> links;
  const std::set<std::string> drawn(names.begin(), names.end());
  std::set<std::pair<std::size_t, std::string>> seen;
  const auto add = [&](const std::string& name, bool follow) {
    const auto at = idx.resolve(name);
    if (!at || (follow && !seen.insert(*at).second)) return;  // a thesis stimulus, or no such entry
    auto& f = *file_of[at->first];
    f.bind(1, at->second);
    if (f.step()) {
      files[at->first].insert(f.text(0));
      if (follow && drawn.count(name) && !f.text(1).empty()) links.push_back(f.text(1));
    }
    f.reset();
    if (!follow) return;
    auto& b = *builds_on[at->first];
    b.bind(1, at->second);
    while (b.step()) down.push_back(b.text(0));
    b.reset();
  };
  while (!down.empty()) {
    const auto name = std::move(down.front());
    down.pop_front();
    add(name, true);
  }
  for (const auto& l : links) add(l, false);
  std::vector<std::vector<std::string>> out;
  for (auto& f : files) out.emplace_back(f.begin(), f.end());
  return out;
}

}  // namespace sandpaper::curation
