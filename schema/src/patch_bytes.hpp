#pragma once
// The patch file's bytes (patch_io.cpp): a writer that keeps large arrays where they lie, readers
// from memory or from the open file (summed with CRC-32 as read), and CRC-32 over a buffer.
// Internal to the schema library.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <zlib.h>

// Header-only use of Imath's binary16 conversions (no lookup table, so nothing to link): the
// patch reader stays free of image libraries.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <Imath/half.h>

#include "sandpaper/schema/no_coverage.hpp"
#include "sandpaper/schema/patch_io.hpp"

namespace sandpaper::schema::patch_bytes {

// binary16 to float32, apart so that the fuzzing build leaves the per-sample loop uninstrumented
// (no_coverage.hpp).
SANDPAPER_NO_COVERAGE inline void widen_halves(const std::uint16_t* h, std::size_t n, float* out) {
  for (std::size_t i = 0; i < n; ++i) out[i] = imath_half_to_float(h[i]);
}

// The payload as a list of segments: small fields in buffers of their own, large float arrays
// referenced where they lie in the program, so that writing a 4096 x 4096 height field copies no
// grid (docs/performance.md, "Image compile that scales").
class Writer {
 public:
  template <class T>
  void pod(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* b = reinterpret_cast<const unsigned char*>(&v);
    own().insert(own().end(), b, b + sizeof(T));
  }
  // Strings as JSON output writes them (schema/json_text.hpp): each byte that does not begin a whole
  // UTF-8 character as U+FFFD. They are display text (a Latin-1 file name in a location, a picture's
  // channel name), and the reader refuses any other: a program written is one it can read
  // (docs/RELIABILITY.md, F42).
  void str(const std::string& s) {
    if (std::size_t bad = 0; !is_valid_utf8(s, bad)) return text(replace_invalid_utf8(s));
    text(s);
  }
  void text(const std::string& s) {  // `s` known to be UTF-8
    pod<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    own().insert(own().end(), s.begin(), s.end());
  }
  void floats(const std::vector<float>& v) {
    pod<std::uint64_t>(v.size());
    const auto* b = reinterpret_cast<const unsigned char*>(v.data());
    if (v.size() < kReferencedFloats) {
      own().insert(own().end(), b, b + v.size() * sizeof(float));
    } else {
      segments_.push_back({{}, std::string_view(reinterpret_cast<const char*>(b), v.size() * sizeof(float))});
    }
  }
  // uint16 values, kept by the writer (the halves of a compact grid exist only here).
  void halves(std::vector<std::uint16_t> v) {
    pod<std::uint64_t>(v.size());
    Segment seg;
    seg.owned.resize(v.size() * sizeof(std::uint16_t));
    if (!v.empty()) std::memcpy(seg.owned.data(), v.data(), seg.owned.size());
    segments_.push_back(std::move(seg));
    segments_.emplace_back();  // what follows goes to a fresh buffer
  }
  // The segments in order; valid while this Writer and the program it wrote live.
  std::vector<std::string_view> parts() const {
    std::vector<std::string_view> out;
    for (const auto& s : segments_)
      out.push_back(s.external.data() ? s.external : std::string_view(reinterpret_cast<const char*>(s.owned.data()), s.owned.size()));
    return out;
  }
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& part : parts()) n += part.size();
    return n;
  }

 private:
  static constexpr std::size_t kReferencedFloats = 4096;
  struct Segment {
    std::vector<unsigned char> owned;
    std::string_view external;
  };
  std::vector<unsigned char>& own() {
    if (segments_.empty() || segments_.back().external.data()) segments_.emplace_back();
    return segments_.back().owned;
  }
  std::vector<Segment> segments_;
};

// Where the reader's bytes come from: memory (deserialize) or the file itself, read in place into
// the program's arrays (read_patch_file), so that loading a height field holds no second copy.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual void read(void* into, std::size_t n) = 0;  // throws PatchFormatError when fewer are left
  virtual std::size_t remaining() const = 0;
};

class MemorySource final : public ByteSource {
 public:
  MemorySource(const unsigned char* p, std::size_t n) : p_(p), end_(p + n) {}
  void read(void* into, std::size_t n) override {
    if (static_cast<std::size_t>(end_ - p_) < n) throw PatchFormatError("patch program truncated");
    if (n > 0) std::memcpy(into, p_, n);
    p_ += n;
  }
  std::size_t remaining() const override { return static_cast<std::size_t>(end_ - p_); }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
};

// The payload of an open file, `size` bytes long (checked against the file's size before), summed
// with CRC-32 as it is read.
class FileSource final : public ByteSource {
 public:
  FileSource(std::FILE* f, std::size_t size) : f_(f), left_(size), crc_(crc32(0L, Z_NULL, 0)) {}
  void read(void* into, std::size_t n) override {
    if (left_ < n) throw PatchFormatError("patch program truncated");
    if (n > 0 && std::fread(into, 1, n, f_) != n) throw PatchFormatError("patch program truncated");
    auto* p = static_cast<const unsigned char*>(into);
    for (std::size_t done = 0; done < n;) {
      const auto chunk = static_cast<uInt>(std::min<std::size_t>(n - done, 1u << 30));
      crc_ = crc32(crc_, p + done, chunk);
      done += chunk;
    }
    left_ -= n;
  }
  std::size_t remaining() const override { return left_; }
  std::uint32_t crc() const { return static_cast<std::uint32_t>(crc_); }

 private:
  std::FILE* f_;
  std::size_t left_;
  uLong crc_;
};

class Reader {
 public:
  explicit Reader(ByteSource& source) : source_(source) {}
  template <class T>
  T pod() {
    T v;
    source_.read(&v, sizeof(T));
    return v;
  }
  std::string str() {
    auto n = pod<std::uint32_t>();
    if (n > source_.remaining()) throw PatchFormatError("patch program truncated");
    std::string s(n, '\0');
    source_.read(s.data(), n);
    // Strings go on to JSON and terminals; the compiler writes only UTF-8.
    if (std::size_t bad = 0; !is_valid_utf8(s, bad))
      throw PatchFormatError("patch program holds a string that is not UTF-8 (byte " + std::to_string(bad) + " of it)");
    return s;
  }
  std::vector<float> floats() {
    auto n = pod<std::uint64_t>();
    // Checked before allocating: a corrupt count must not ask for more memory than the file holds.
    if (n > source_.remaining() / sizeof(float))
      throw PatchFormatError("patch program truncated: float array longer than the file");
    std::vector<float> v(n);
    source_.read(v.data(), n * sizeof(float));
    return v;
  }
  // binary16 values, widened to float32.
  std::vector<float> halves() {
    auto n = pod<std::uint64_t>();
    if (n > source_.remaining() / sizeof(std::uint16_t))
      throw PatchFormatError("patch program truncated: half-float array longer than the file");
    std::vector<std::uint16_t> h(n);
    source_.read(h.data(), n * sizeof(std::uint16_t));
    std::vector<float> v(n);
    widen_halves(h.data(), n, v.data());
    return v;
  }
  bool done() const { return source_.remaining() == 0; }

 private:
  ByteSource& source_;
};

inline std::uint32_t crc_of(const unsigned char* p, std::size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths; feed in chunks so payloads over 4 GiB would still be summed right.
  while (n > 0) {
    auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace sandpaper::schema::patch_bytes
