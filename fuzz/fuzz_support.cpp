#include "fuzz_support.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <zlib.h>

namespace sandpaper::fuzz {

std::filesystem::path source_dir() { return SANDPAPER_SOURCE_DIR; }

void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

bool known_defect_tolerated(std::string_view name) {
  static const std::string list = [] {
    const char* env = std::getenv("SANDPAPER_FUZZ_KNOWN");
    return env ? "," + std::string(env) + "," : std::string();
  }();
  return list.find("," + std::string(name) + ",") != std::string::npos;
}

namespace {
// Removes the scratch folder when the process ends normally (libFuzzer's -runs, the replay driver).
void remove_scratch() {
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir(), ec);
}
}  // namespace

const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("sandpaper-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit(remove_scratch);
    return d;
  }();
  return dir;
}

void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  // A harness that cannot write its scratch file would test nothing: stop, not a finding.
  if (!out) {
    std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
    std::exit(2);
  }
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  std::string bytes(static_cast<std::size_t>(in.tellg()), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

void dump_json(const nlohmann::json& j) {
  try {
    const std::string text = j.dump();
    check(!text.empty(), "empty JSON text");
  } catch (const nlohmann::json::type_error& e) {
    if (e.id == 316 && known_defect_tolerated("json-utf8")) return;
    throw;
  }
}

std::vector<unsigned char> with_valid_header(const std::uint8_t* data, std::size_t size, std::string_view magic,
                                             std::uint32_t version) {
  constexpr std::size_t kHeaderSize = 32;
  std::vector<unsigned char> out(kHeaderSize, 0);
  const bool has_header = size >= kHeaderSize && std::memcmp(data, magic.data(), magic.size()) == 0;
  const std::uint8_t* payload = has_header ? data + kHeaderSize : data;
  const std::size_t payload_size = has_header ? size - kHeaderSize : size;
  if (has_header) std::memcpy(out.data(), data, kHeaderSize);  // keeps flags and padding as mutated
  std::memcpy(out.data(), magic.data(), magic.size());
  std::memcpy(out.data() + 8, &version, sizeof version);
  const std::uint64_t n = payload_size;
  std::memcpy(out.data() + 16, &n, sizeof n);
  const std::uint32_t crc =
      static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), payload, static_cast<uInt>(payload_size)));
  std::memcpy(out.data() + 24, &crc, sizeof crc);
  out.insert(out.end(), payload, payload + payload_size);
  return out;
}

}  // namespace sandpaper::fuzz
