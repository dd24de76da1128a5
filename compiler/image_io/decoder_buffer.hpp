#pragma once
// A buffer that OpenImageIO's decoders write into (a strip as stored, a picture's floats, a resized
// picture). Those decoders are not instrumented by AddressSanitizer, so a write past such a buffer
// goes unreported and lands in whatever lies next; in the fuzzing build that corrupted ASan's own
// allocator headers without a report naming the input (docs/RELIABILITY.md, F41). Guarded, the
// buffer sits in its own mapping, its end flush against an inaccessible page and a second such page
// before it: a decoder writing past either end stops the program at once with SIGSEGV. Guarded in
// builds with AddressSanitizer (the `fuzz` and `asan` presets) and wherever the environment sets
// SANDPAPER_GUARD_DECODER_BUFFERS=1 (the test suite does); otherwise a plain heap buffer. Sizes in
// bytes; throws std::bad_alloc when the mapping fails, as the heap would.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace sandpaper::compiler::image_io {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kBuiltWithAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kBuiltWithAddressSanitizer = true;
#else
inline constexpr bool kBuiltWithAddressSanitizer = false;
#endif
#else
inline constexpr bool kBuiltWithAddressSanitizer = false;
#endif

class DecoderBuffer {
 public:
  // Read once per process, the first time a buffer is made.
  static bool guarded() {
    static const bool on = kBuiltWithAddressSanitizer || [] {
      const char* v = std::getenv("SANDPAPER_GUARD_DECODER_BUFFERS");
      return v != nullptr && v[0] == '1' && v[1] == '\0';
    }();
    return on;
  }

  explicit DecoderBuffer(std::size_t bytes) : bytes_(bytes) {
    if (!guarded()) {
      heap_.resize(bytes);
      data_ = heap_.data();
      return;
    }
    const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t body = (bytes + page - 1) / page * page;
    map_bytes_ = body + 2 * page;
    void* map = mmap(nullptr, map_bytes_, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (map == MAP_FAILED) throw std::bad_alloc();
    map_ = static_cast<unsigned char*>(map);
    if (body > 0 && mprotect(map_ + page, body, PROT_READ | PROT_WRITE) != 0) {
      munmap(map_, map_bytes_);
      throw std::bad_alloc();
    }
    // Flush against the page after: the first byte past the end faults. A whole number of
    // elements long, the buffer keeps its elements aligned to that page's start.
    data_ = map_ + page + body - bytes;
  }
  DecoderBuffer(const DecoderBuffer&) = delete;
  DecoderBuffer& operator=(const DecoderBuffer&) = delete;
  ~DecoderBuffer() {
    if (map_ != nullptr) munmap(map_, map_bytes_);
  }

  unsigned char* data() { return data_; }
  std::size_t size() const { return bytes_; }

 private:
  std::size_t bytes_;
  unsigned char* data_ = nullptr;
  std::vector<unsigned char> heap_;
  unsigned char* map_ = nullptr;
  std::size_t map_bytes_ = 0;
};

}  // namespace sandpaper::compiler::image_io
