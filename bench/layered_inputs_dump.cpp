// Prints what a layered library's catalog compares (curation::layered_inputs), "NAME<TAB>HASH" a
// line, so that bench/catalog_seed.py can seed a layered catalog's record at sizes whose full
// drawing takes hours (docs/performance.md, "A layered library").
//   build/bin/sandpaper_layered_inputs LAB WORLD > hashes.tsv
// The roots' indexes must be up to date (`sandpaper library index --library LAB:WORLD`).
#include <iostream>

#include "sandpaper/curation/layers.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: sandpaper_layered_inputs ROOT ROOT... (front first; at least two)\n";
    return 2;
  }
  const std::vector<std::filesystem::path> roots(argv + 1, argv + argc);
  const sandpaper::curation::LayeredIndex idx(roots);
  const auto in = sandpaper::curation::layered_inputs(idx, roots);
  for (const auto& [name, hash] : in.entries) std::cout << name << '\t' << hash << '\n';
  std::cerr << in.entries.size() << " entries, " << in.affected << " reaching a root in front of their own\n";
  return 0;
}
