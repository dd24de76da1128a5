#include "curation_test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace sandpaper::test {

std::filesystem::path mini_library_copy(const std::string& tag) {
  const std::filesystem::path dir = temp_dir(tag) + "/lib";
  std::filesystem::copy(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "tests/curation/data/mini", dir,
                        std::filesystem::copy_options::recursive);
  return dir;
}

std::filesystem::path calibration_copy(const std::string& tag) {
  const std::filesystem::path dir = temp_dir(tag) + "/calibration";
  std::filesystem::copy(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "calibration", dir,
                        std::filesystem::copy_options::recursive);
  return dir;
}

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

void edit(const std::filesystem::path& file, const std::string& from, const std::string& to) {
  auto text = read(file);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "'" << from << "' not in " << file;
  text.replace(at, from.size(), to);
  write(file, text);
}

std::vector<const compiler::Diagnostic*> with_code(const compiler::Diagnostics& d, const std::string& code) {
  std::vector<const compiler::Diagnostic*> out;
  for (const auto& x : d.all())
    if (x.code == code) out.push_back(&x);
  return out;
}

}  // namespace sandpaper::test
