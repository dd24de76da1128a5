// `run --watch` notices saves by their text (source_watch.hpp). The file system's stamps are set by
// hand here to what a coarse clock gives a truncate-then-write save: the same stamp on both.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>

#include <gtest/gtest.h>

#include "sandpaper/compiler/source_watch.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& f, const std::string& text) { std::ofstream(f, std::ios::binary | std::ios::trunc) << text; }

TEST(SourceWatch, ASaveThatKeepsTheStampOfTheTruncatedFileIsStillSeen) {
  const fs::path f = fs::path(test::temp_dir("source-watch")) / "m.hmat";
  write(f, "roughness 0.5\n");
  compiler::SourceWatch watch(f);
  EXPECT_FALSE(watch.changed()) << "the text it started with is not a change";

  write(f, "roughness 0.8; grating period 3 mm\n");
  EXPECT_TRUE(watch.changed());
  EXPECT_FALSE(watch.changed()) << "a save is reported once";

  // The editor truncates; the watch looks in between; the write lands within the same clock tick.
  const auto tick = fs::last_write_time(f);
  write(f, "");
  fs::last_write_time(f, tick);
  EXPECT_TRUE(watch.changed());
  write(f, "roughness 0.3; grating period 3 mm\n");
  fs::last_write_time(f, tick);
  EXPECT_TRUE(watch.changed()) << "the full file under the truncation's stamp";

  // The same size and the same stamp: seen while the stamp is racy, by reading the text.
  write(f, "roughness 0.4; grating period 3 mm\n");
  fs::last_write_time(f, tick);
  EXPECT_TRUE(watch.changed());
}

TEST(SourceWatch, AnOldStampIsNotReadAgainAndAMissingFileIsNoChange) {
  const fs::path f = fs::path(test::temp_dir("source-watch")) / "m.hmat";
  write(f, "roughness 0.5\n");
  const auto old = fs::last_write_time(f) - std::chrono::hours(1);
  fs::last_write_time(f, old);
  compiler::SourceWatch watch(f);
  // Another text of the same size under the same old stamp is not looked for: the stamp and size are
  // all a look costs once the stamp is no longer racy (as make and git).
  write(f, "roughness 0.6\n");
  fs::last_write_time(f, old);
  EXPECT_FALSE(watch.changed());
  // A real save moves the stamp.
  write(f, "roughness 0.7\n");
  EXPECT_TRUE(watch.changed());
  fs::remove(f);
  EXPECT_FALSE(watch.changed()) << "removed mid-save: no change until it is back";
  write(f, "roughness 0.9\n");
  EXPECT_TRUE(watch.changed());
}

// What the watch reads is bounded as the compiler's reader is (schema/input_limits.hpp): a FIFO put
// where the material was is reported as a change without being opened (opening it would block the
// watch until a writer came), and a file past the limit is compared by its stamp and size alone.
TEST(SourceWatch, AFifoOrAFileOverTheLimitIsAChangeSeenWithoutReadingIt) {
  const fs::path dir = test::temp_dir("source-watch");
  const fs::path f = dir / "m.hmat";
  write(f, "roughness 0.5\n");
  compiler::SourceWatch watch(f, 64);

  const fs::path fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::rename(fifo, f);
  EXPECT_TRUE(watch.changed()) << "a FIFO where the material was: the compile says why it cannot be read";
  EXPECT_FALSE(watch.changed()) << "and it is reported once";
  fs::remove(f);
  write(f, "roughness 0.5\n");
  EXPECT_TRUE(watch.changed()) << "a regular file again";

  const std::string big(100, 'x');
  write(f, big);
  EXPECT_TRUE(watch.changed()) << "past the limit: a change by its size";
  const auto tick = fs::last_write_time(f);
  write(f, std::string(100, 'y'));
  fs::last_write_time(f, tick);
  EXPECT_FALSE(watch.changed()) << "past the limit the text is not read, so the same stamp and size are no change";
  write(f, std::string(101, 'y'));
  fs::last_write_time(f, tick);
  EXPECT_TRUE(watch.changed()) << "another size under the same stamp";
  write(f, "roughness 0.5\n");
  EXPECT_TRUE(watch.changed()) << "back under the limit";
  EXPECT_FALSE(watch.changed());
}

}  // namespace
}  // namespace sandpaper
