#include "sandpaper/compiler/library.hpp"

#include <algorithm>
#include <cstdlib>

namespace sandpaper::compiler {

std::vector<std::string> Library::names() const {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir_, ec))
    if (e.is_regular_file() && e.path().extension() == ".hmat") out.push_back(e.path().stem().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::optional<std::filesystem::path> Library::find(const std::string& name) const {
  // Names are plain words; anything path-like would let `like ../x` escape the library.
  if (name.empty() || name.find('/') != std::string::npos || name.find("..") != std::string::npos) return std::nullopt;
  auto p = dir_ / (name + ".hmat");
  std::error_code ec;
  if (std::filesystem::is_regular_file(p, ec)) return p;
  return std::nullopt;
}

}  // namespace sandpaper::compiler
