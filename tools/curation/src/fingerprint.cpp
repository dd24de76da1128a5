#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <vector>

#include "sandpaper/curation/index.hpp"

namespace sandpaper::curation {

std::filesystem::path default_index_path(const std::filesystem::path& library_dir) {
  if (const char* env = std::getenv("SANDPAPER_LIBRARY_INDEX"); env && *env) return env;
  return library_dir / ".index" / "library.sqlite";
}

namespace {

struct Fnv1a64 {
  std::uint64_t h = 1469598103934665603ULL;
  void add(const char* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(p[i]);
      h *= 1099511628211ULL;
    }
  }
  void add(const std::string& s) { add(s.data(), s.size() + 1); }  // with the terminator, so "ab"+"c" != "a"+"bc"
};

// Every regular file under `dir`, hidden files and folders left out, by relative path.
void add_folder(Fnv1a64& h, const std::filesystem::path& dir, const std::string& tag) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec); !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    const auto name = it->path().filename().string();
    if (!name.empty() && name[0] == '.') {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file()) files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    h.add(tag + "/" + f.lexically_relative(dir).generic_string());
    std::ifstream in(f, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    h.add(std::to_string(bytes.size()));
    h.add(bytes.data(), bytes.size());
  }
}

}  // namespace

std::string library_fingerprint(const std::filesystem::path& library_dir, const std::filesystem::path& calibration_dir) {
  Fnv1a64 h;
  h.add("sandpaper-library-index/" + std::to_string(kIndexSchemaVersion));
  add_folder(h, library_dir, "library");
  add_folder(h, calibration_dir, "calibration");
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h.h));
  return buf;
}

}  // namespace sandpaper::curation
