#include "sandpaper/curation/layers.hpp"

#include <algorithm>
#include <set>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library_layers.hpp"

namespace sandpaper::curation {

std::string root_id(const Index& index, const std::filesystem::path& root_dir) {
  // Indexes built before schema 5's `library_id` row: the folder's name, as the compiler falls back to.
  auto id = index.meta("library_id");
  if (id.empty()) id = std::filesystem::absolute(root_dir).lexically_normal().filename().string();
  return id;
}

LayeredIndex::LayeredIndex(const std::vector<std::filesystem::path>& roots, const std::vector<std::filesystem::path>& index_paths)
    : roots_(roots) {
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const auto& r = roots[i];
    Layer l;
    try {
      l.index = std::make_unique<Index>(i < index_paths.size() ? index_paths[i] : layer_index_path(r));
    } catch (const IndexError& e) {
      throw IndexError("the index of library root " + r.string() + ": " + e.what());
    }
    l.id = root_id(*l.index, r);
    layers_.push_back(std::move(l));
  }
}

std::optional<std::pair<std::size_t, std::string>> LayeredIndex::resolve(const std::string& name) const {
  if (const auto colon = name.find(':'); colon != std::string::npos) {
    const auto id = name.substr(0, colon);
    for (std::size_t i = 0; i < layers_.size(); ++i)
      if (layers_[i].id == id) {
        if (auto n = layers_[i].index->resolve(name.substr(colon + 1))) return std::make_pair(i, *n);
        return std::nullopt;
      }
    return std::nullopt;
  }
  const auto knows = [this](std::size_t r, const std::string& n) { return layers_[r].index->resolve(n); };
  return compiler::layers::resolve(layers_.size(), name, knows);
}

bool LayeredIndex::hidden(std::size_t layer, const std::string& name) const {
  const auto knows = [this](std::size_t r, const std::string& n) { return layers_[r].index->resolve(n); };
  return compiler::layers::hidden(std::min(layer, layers_.size()), name, knows);
}

std::optional<IndexedEntry> LayeredIndex::entry(std::size_t layer, const std::string& name) const {
  auto e = index_of(layer, name).entry(name);
  if (e) e->root = layers_[layer].id;
  return e;
}

std::vector<SearchHit> LayeredIndex::search(const SearchQuery& q) const {
  if (!q.family.empty()) {
    std::vector<std::string> all;
    for (const auto& l : layers_)
      for (auto& f : l.index->families()) all.push_back(std::move(f));
    if (std::find(all.begin(), all.end(), q.family) == all.end()) (void)curation::search(*layers_.front().index, q);  // throws, with "did you mean"
  }
  std::vector<std::pair<std::size_t, SearchHit>> hits;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    const auto& idx = *layers_[i].index;
    const auto fams = q.family.empty() ? std::vector<std::string>{} : idx.families();
    if (!q.family.empty() && std::find(fams.begin(), fams.end(), q.family) == fams.end()) continue;
    // Hidden entries take places in a root's own ranking: ask for more until `limit` are left.
    for (auto lq = q;; lq.limit *= 2) {
      std::vector<SearchHit> kept;
      const auto got = curation::search(idx, lq);
      // A hidden entry is still what its alias names if no root in front has that alias.
      for (const auto& h : got)
        if (!through_path(i, h.entry.name) &&
            (h.why == "alias" ? resolve(h.matched_alias) == std::make_pair(i, h.entry.name) : !hidden(i, h.entry.name)))
          kept.push_back(h);
      if (kept.size() >= q.limit || got.size() < lq.limit) {
        for (auto& h : kept) {
          h.entry.root = layers_[i].id;
          hits.emplace_back(i, std::move(h));
        }
        break;
      }
    }
  }
  // The entries compiled over the path (see_through_path): none is hidden, but an alias may be.
  if (path_) {
    const auto fams = q.family.empty() ? std::vector<std::string>{} : path_->families();
    if (q.family.empty() || std::find(fams.begin(), fams.end(), q.family) != fams.end())
      for (auto& h : curation::search(*path_, q)) {
        const std::size_t i = path_layer_.at(h.entry.name);
        if (h.why == "alias" && resolve(h.matched_alias) != std::make_pair(i, h.entry.name)) continue;
        h.entry.root = layers_[i].id;
        hits.emplace_back(i, std::move(h));
      }
  }
  std::stable_sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) {
    if (search_before(a.second, b.second)) return true;
    if (search_before(b.second, a.second)) return false;
    // Equal ranks in name order, as within one root; the same name, front root first.
    if (a.second.entry.name != b.second.entry.name) return a.second.entry.name < b.second.entry.name;
    return a.first < b.first;
  });
  std::vector<SearchHit> out;
  for (auto& [layer, h] : hits)
    if (out.size() < q.limit) out.push_back(std::move(h));
  return out;
}

std::string LayeredIndex::hides(std::size_t layer, const std::string& name) const {
  if (layer + 1 >= layers_.size()) return "";
  std::vector<std::string> names{name};
  if (const auto e = layers_[layer].index->entry(name)) names.insert(names.end(), e->aliases.begin(), e->aliases.end());
  const auto knows = [this](std::size_t r, const std::string& n) { return layers_[r].index->resolve(n); };
  const auto hit = compiler::layers::hides(layer, layers_.size(), names, knows);
  return hit ? layers_[hit->first].id + ":" + hit->second : "";
}

std::vector<Neighbour> LayeredIndex::nearest(std::size_t layer, const std::string& name, std::size_t limit,
                                             const std::string& family) const {
  const auto from = entry(layer, name);
  if (!from) return {};
  const WeberFractions weber = index_of(layer, name).weber_fractions();
  std::vector<Neighbour> found;
  for (std::size_t i = 0; i < layers_.size(); ++i)
    for (std::size_t lim = limit;; lim *= 2) {
      std::vector<Neighbour> kept;
      const auto got = nearest_to(*layers_[i].index, *from, lim, weber, family);
      for (const auto& n : got)
        if (!hidden(i, n.entry.name) && !through_path(i, n.entry.name) && n.entry.name != from->name) kept.push_back(n);
      if (kept.size() >= limit || got.size() < lim) {
        for (auto& n : kept) {
          n.entry.root = layers_[i].id;
          found.push_back(std::move(n));
        }
        break;
      }
    }
  if (path_)
    for (auto& n : nearest_to(*path_, *from, limit + 1, weber, family)) {
      if (n.entry.name == from->name) continue;
      n.entry.root = layers_[path_layer_.at(n.entry.name)].id;
      found.push_back(std::move(n));
    }
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.entry.name < b.entry.name;
  });
  if (found.size() > limit) found.resize(limit);
  return found;
}

std::vector<std::string> LayeredIndex::names_and_aliases() const {
  std::vector<std::string> out;
  for (const auto& l : layers_)
    for (const auto& n : l.index->names_and_aliases()) {
      out.push_back(n);
      out.push_back(l.id + ":" + n);
    }
  return out;
}

}  // namespace sandpaper::curation
