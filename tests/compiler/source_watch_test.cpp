// `run --watch` notices saves by their text (source_watch.hpp). The file system's stamps are set by
// hand here to what a coarse clock gives a truncate-then-write save: the same stamp on both.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

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
  EXPECT_FALSE(watch.changed_text()) << "the text it started with is not a change";

  write(f, "roughness 0.8; grating period 3 mm\n");
  EXPECT_EQ(watch.changed_text(), "roughness 0.8; grating period 3 mm\n");
  EXPECT_FALSE(watch.changed_text()) << "a save is reported once";

  // The editor truncates; the watch looks in between; the write lands within the same clock tick.
  const auto tick = fs::last_write_time(f);
  write(f, "");
  fs::last_write_time(f, tick);
  EXPECT_EQ(watch.changed_text(), "");
  write(f, "roughness 0.3; grating period 3 mm\n");
  fs::last_write_time(f, tick);
  EXPECT_EQ(watch.changed_text(), "roughness 0.3; grating period 3 mm\n") << "the full file under the truncation's stamp";

  // The same size and the same stamp: seen while the stamp is racy, by reading the text.
  write(f, "roughness 0.4; grating period 3 mm\n");
  fs::last_write_time(f, tick);
  EXPECT_EQ(watch.changed_text(), "roughness 0.4; grating period 3 mm\n");
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
  EXPECT_FALSE(watch.changed_text());
  // A real save moves the stamp.
  write(f, "roughness 0.7\n");
  EXPECT_EQ(watch.changed_text(), "roughness 0.7\n");
  fs::remove(f);
  EXPECT_FALSE(watch.changed_text()) << "removed mid-save: no change until it is back";
  write(f, "roughness 0.9\n");
  EXPECT_EQ(watch.changed_text(), "roughness 0.9\n");
}

}  // namespace
}  // namespace sandpaper
