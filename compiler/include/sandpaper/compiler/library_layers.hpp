#pragma once
// The one rule of a layered library (docs/LIBRARY.md, "Layered libraries"), written once for every
// model of it: the compiler's Library (files read), the curation's LayeredIndex (SQLite indexes) and
// through them `library check`, search, near and the catalog. Roots are asked front first:
// - a name or alias means the entry of the first root that knows it;
// - an entry is hidden when a root in front of its own knows its name;
// - an entry hides the first entry behind it that its name or one of its aliases names.
// `Knows` is any callable (std::size_t root, const std::string& name_or_alias) ->
// std::optional<std::string>: the name of the entry that root gives it (names before aliases within a root).
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sandpaper::compiler::layers {

// The root and entry name `name_or_alias` means, asking roots 0 .. roots-1 in order; nullopt if none knows it.
template <class Knows>
std::optional<std::pair<std::size_t, std::string>> resolve(std::size_t roots, const std::string& name_or_alias,
                                                           const Knows& knows) {
  for (std::size_t r = 0; r < roots; ++r)
    if (auto name = knows(r, name_or_alias)) return std::make_pair(r, std::move(*name));
  return std::nullopt;
}

// Whether an entry named `name` in `root` is hidden by a root in front of it.
template <class Knows>
bool hidden(std::size_t root, const std::string& name, const Knows& knows) {
  return resolve(root, name, knows).has_value();
}

// The entry that an entry of `root` with these `names` (its name, then its aliases) hides: the
// first root behind it that knows one of them, and the name it knows it by; nullopt if none.
template <class Knows>
std::optional<std::pair<std::size_t, std::string>> hides(std::size_t root, std::size_t roots,
                                                         const std::vector<std::string>& names, const Knows& knows) {
  for (std::size_t r = root + 1; r < roots; ++r)
    for (const auto& n : names)
      if (auto hit = knows(r, n)) return std::make_pair(r, std::move(*hit));
  return std::nullopt;
}

}  // namespace sandpaper::compiler::layers
