// The buffers OpenImageIO's decoders fill (compiler/image_io/decoder_buffer.hpp): every byte of the
// asked size is usable, and guarded (in builds with AddressSanitizer, whose checks do not reach the
// decoders, and wherever SANDPAPER_GUARD_DECODER_BUFFERS=1, as ctest sets for these tests), the first
// byte past the end faults at once (docs/RELIABILITY.md, F41).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "decoder_buffer.hpp"

namespace {

using sandpaper::compiler::image_io::DecoderBuffer;
using sandpaper::compiler::image_io::kBuiltWithAddressSanitizer;

TEST(DecoderBuffer, EveryByteOfTheAskedSizeIsUsableAndFloatsStayAligned) {
  for (std::size_t bytes : {std::size_t{1}, std::size_t{7}, std::size_t{4096}, std::size_t{4100}, std::size_t{1} << 20}) {
    DecoderBuffer b(bytes);
    ASSERT_EQ(b.size(), bytes);
    std::memset(b.data(), 0xA5, bytes);
    EXPECT_EQ(b.data()[0], 0xA5);
    EXPECT_EQ(b.data()[bytes - 1], 0xA5);
  }
  DecoderBuffer floats(3 * 5 * sizeof(float));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(floats.data()) % alignof(float), 0u);
}

// Without AddressSanitizer the fault kills the process with SIGSEGV; with it, ASan reports the SEGV
// and exits with 1.
bool died_of_the_fault(int status) {
  if (kBuiltWithAddressSanitizer) return WIFEXITED(status) && WEXITSTATUS(status) != 0;
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGSEGV;
}
const char* const kFaultReport = kBuiltWithAddressSanitizer ? "SEGV" : "";

// A volatile store, as the decoders' unchecked code would make it.
void write_at(DecoderBuffer& b, std::ptrdiff_t at) { static_cast<volatile unsigned char*>(b.data())[at] = 1; }

TEST(DecoderBuffer, GuardedTheFirstBytePastTheEndFaults) {
  if (!DecoderBuffer::guarded()) GTEST_SKIP() << "unguarded: set SANDPAPER_GUARD_DECODER_BUFFERS=1 (ctest does)";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  for (std::size_t bytes : {std::size_t{100}, std::size_t{4096}, std::size_t{12288 + 3}}) {
    DecoderBuffer b(bytes);
    write_at(b, static_cast<std::ptrdiff_t>(bytes) - 1);  // the last byte is fine
    EXPECT_EXIT(write_at(b, static_cast<std::ptrdiff_t>(bytes)), died_of_the_fault, kFaultReport);
  }
  DecoderBuffer empty(0);
  EXPECT_EXIT(write_at(empty, 0), died_of_the_fault, kFaultReport);
}

}  // namespace
