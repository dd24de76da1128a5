#include "sandpaper/schema/workspace_io.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <zlib.h>

#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::schema {
namespace {

constexpr char kMagic[8] = {'S', 'N', 'D', 'W', 'K', 'S', 'P', 'C'};
constexpr std::size_t kHeaderSize = 32;
// A workspace of 1,000 image patches stays far below this; a header claiming more is corrupt.
constexpr std::uint64_t kMaxPayload = 1ull << 33;

void put_bytes(std::vector<unsigned char>& out, const void* p, std::size_t n) {
  const auto* b = static_cast<const unsigned char*>(p);
  out.insert(out.end(), b, b + n);
}
template <class T>
void put(std::vector<unsigned char>& out, T v) {
  put_bytes(out, &v, sizeof v);
}
void put_str(std::vector<unsigned char>& out, const std::string& s) {
  put(out, static_cast<std::uint32_t>(s.size()));
  put_bytes(out, s.data(), s.size());
}

bool plausible_length(double m) {
  return std::isfinite(m) && m >= limits::kMinPlausibleLength_m && m <= limits::kMaxPlausibleLength_m;
}

class Cursor {
 public:
  Cursor(const unsigned char* p, std::size_t n) : p_(p), end_(p + n) {}
  template <class T>
  T pod() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  std::string str() {
    const auto n = pod<std::uint32_t>();
    need(n);
    std::string s(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    // Names go on to JSON and terminals; the compiler writes only UTF-8 .
    if (std::size_t bad = 0; !is_valid_utf8(s, bad))
      throw PatchFormatError("workspace program holds a string that is not UTF-8 (byte " + std::to_string(bad) + " of it)");
    return s;
  }
  // The next n bytes, in place (valid while the payload is).
  std::string_view view(std::uint64_t n) {
    need(n);
    const std::string_view v(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    return v;
  }
  bool done() const { return p_ == end_; }

 private:
  void need(std::uint64_t n) const {
    if (static_cast<std::uint64_t>(end_ - p_) < n) throw PatchFormatError("workspace program truncated");
  }
  void take(void* into, std::size_t n) {
    need(n);
    std::memcpy(into, p_, n);
    p_ += n;
  }
  const unsigned char* p_;
  const unsigned char* end_;
};

std::uint32_t crc_of(const unsigned char* p, std::size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  while (n > 0) {
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace

void write_workspace_program_file(const std::filesystem::path& path, const WorkspaceProgram& ws,
                                  const PatchWriteOptions& options) {
  std::vector<unsigned char> payload;
  put_str(payload, ws.name);
  put(payload, ws.size_m[0]);
  put(payload, ws.size_m[1]);
  put(payload, static_cast<std::uint32_t>(ws.patches.size()));
  std::shared_ptr<const PatchProgram> last_program;
  std::vector<unsigned char> program;
  for (const auto& p : ws.patches) {
    put_str(payload, p.source);
    put(payload, p.centre_m[0]);
    put(payload, p.centre_m[1]);
    put(payload, p.size_m[0]);
    put(payload, p.size_m[1]);
    // A shared program is serialized once (the file still holds it per patch).
    if (p.program != last_program) {
      program = serialize(*p.program, options);
      last_program = p.program;
    }
    put(payload, static_cast<std::uint64_t>(program.size()));
    put_bytes(payload, program.data(), program.size());
  }
  std::vector<unsigned char> header(kHeaderSize, 0);
  const std::uint32_t version = kWorkspaceFormatVersion;
  const std::uint64_t size = payload.size();
  const std::uint32_t crc = crc_of(payload.data(), payload.size());
  std::memcpy(header.data(), kMagic, sizeof kMagic);
  std::memcpy(header.data() + 8, &version, sizeof version);
  std::memcpy(header.data() + 16, &size, sizeof size);
  std::memcpy(header.data() + 24, &crc, sizeof crc);
  write_file_atomically(path, std::vector<std::string_view>{
                                  std::string_view(reinterpret_cast<const char*>(header.data()), header.size()),
                                  std::string_view(reinterpret_cast<const char*>(payload.data()), payload.size())});
}

WorkspaceProgram read_workspace_program_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (const auto status = std::filesystem::status(path, ec); !ec && std::filesystem::exists(status) &&
                                                             !std::filesystem::is_regular_file(status))
    throw PatchFormatError(path.string() + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open workspace program '" + path.string() + "'");
  try {
    unsigned char head[kHeaderSize] = {};
    in.read(reinterpret_cast<char*>(head), kHeaderSize);
    if (in.gcount() != static_cast<std::streamsize>(kHeaderSize) || std::memcmp(head, kMagic, sizeof kMagic) != 0)
      throw PatchFormatError("not a Sandpaper workspace program (no SNDWKSPC header)");
    std::uint32_t version = 0, crc = 0;
    std::uint64_t size = 0;
    std::memcpy(&version, head + 8, sizeof version);
    std::memcpy(&size, head + 16, sizeof size);
    std::memcpy(&crc, head + 24, sizeof crc);
    if (version != kWorkspaceFormatVersion)
      throw PatchFormatError("workspace format version " + std::to_string(version) + ", this build reads version " +
                             std::to_string(kWorkspaceFormatVersion) + ": recompile the workspace");
    const auto file_size = std::filesystem::file_size(path, ec);
    if (ec || size > kMaxPayload || size != file_size - kHeaderSize)
      throw PatchFormatError("workspace program size does not match its header (truncated or padded file)");
    std::vector<unsigned char> payload(size);
    in.read(reinterpret_cast<char*>(payload.data()), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size) throw PatchFormatError("workspace program truncated");
    if (crc_of(payload.data(), payload.size()) != crc)
      throw PatchFormatError("workspace program checksum mismatch (corrupted file)");
    Cursor c(payload.data(), payload.size());
    WorkspaceProgram ws;
    ws.name = c.str();
    ws.size_m[0] = c.pod<double>();
    ws.size_m[1] = c.pod<double>();
    const auto n = c.pod<std::uint32_t>();
    // Keyed by views into `payload`, which outlives the map: a program is copied only to be read.
    std::unordered_map<std::string_view, std::shared_ptr<const PatchProgram>> distinct;
    for (std::uint32_t i = 0; i < n; ++i) {
      PlacedPatch p;
      p.source = c.str();
      p.centre_m[0] = c.pod<double>();
      p.centre_m[1] = c.pod<double>();
      p.size_m[0] = c.pod<double>();
      p.size_m[1] = c.pod<double>();
      const auto length = c.pod<std::uint64_t>();
      // Patches with byte-identical programs share one (as the compiler made them).
      const auto bytes = c.view(length);
      auto& shared = distinct[bytes];
      if (!shared) shared = std::make_shared<const PatchProgram>(deserialize(std::vector<unsigned char>(bytes.begin(), bytes.end())));
      p.program = shared;
      if (!plausible_length(p.size_m[0]) || !plausible_length(p.size_m[1]) || !std::isfinite(p.centre_m[0]) ||
          !std::isfinite(p.centre_m[1]))
        throw PatchFormatError("workspace program with a patch whose size or centre is not a plausible length");
      ws.patches.push_back(std::move(p));
    }
    // The compiler's range for any quantity (1e-12 to 1e12 in SI): a denormal workspace size made the
    // runtime's patch grid overflow.
    if (!plausible_length(ws.size_m[0]) || !plausible_length(ws.size_m[1]))
      throw PatchFormatError("workspace program whose size is not between 1e-12 m and 1e12 m");
    if (!c.done()) throw PatchFormatError("workspace program has trailing bytes");
    return ws;
  } catch (const PatchFormatError& e) {
    throw PatchFormatError(path.string() + ": " + e.what());
  }
}

bool looks_like_workspace_program_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  char m[8] = {};
  in.read(m, 8);
  return in.gcount() == 8 && std::memcmp(m, kMagic, 8) == 0;
}

}  // namespace sandpaper::schema
