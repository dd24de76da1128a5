#pragma once
// The world haptics library: representative descriptions (`like corduroy`) are material files
// in library/, one per entry, named <entry>.hmat.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sandpaper::compiler {

class Library {
 public:
  explicit Library(std::filesystem::path dir) : dir_(std::move(dir)) {}
  // Entry names, sorted.
  std::vector<std::string> names() const;
  // The entry's file, or nullopt if there is no such entry.
  std::optional<std::filesystem::path> find(const std::string& name) const;
  const std::filesystem::path& directory() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

// $SANDPAPER_LIBRARY if set, else the source tree's library/.
std::filesystem::path default_library_dir();

}  // namespace sandpaper::compiler
