// Movies and shuffles (thesis Appendix B): reproducible seeded shuffles, the file formats, limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <random>

#include "sandpaper/compiler/movie.hpp"
#include "sandpaper/compiler/shuffle.hpp"
#include "test_support.hpp"
#include "workspace_test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;
using compiler::Diagnostics;

std::vector<std::string> codes(const Diagnostics& d) {
  std::vector<std::string> out;
  for (const auto& x : d.all()) out.push_back(x.code);
  return out;
}

// A folder holding a movie of `n` frames whose workspace files exist (empty files do: the movie
// reader checks names, not contents).
fs::path movie_with_frames(const std::string& tag, std::size_t n) {
  const fs::path dir = test::temp_dir(tag);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < n; ++i) {
    names.push_back("frame-" + std::to_string(i + 1) + ".hws");
    std::ofstream(dir / names.back()) << "";
  }
  std::ofstream movie(dir / "session.movie");
  for (const auto& name : names) movie << name << "\n";  // not format_movie, which refuses over 100 frames
  return dir / "session.movie";
}

// The C++ standard fixes mt19937_64: its 10000th output from the default seed is 9981545732273789042
// ([rand.predef]). The shuffle's reproducibility rests on that.
TEST(Shuffle, TheGeneratorIsTheStandardOne) {
  std::mt19937_64 rng;
  rng.discard(9999);
  EXPECT_EQ(rng(), 9981545732273789042ull);
}

TEST(Shuffle, UniformBelowStaysInRangeAndRejectsTheBiasedTail) {
  std::mt19937_64 rng(7);
  for (std::uint64_t bound : {1ull, 2ull, 3ull, 7ull, 1000ull, (1ull << 63) + 1}) {
    for (int k = 0; k < 200; ++k) EXPECT_LT(compiler::uniform_below(rng, bound), bound);
  }
  EXPECT_THROW(compiler::uniform_below(rng, 0), std::invalid_argument);
  // For bound 2^63 + 1 the draws below 2^64 mod bound = 2^63 - 1 are rejected: roughly half of them.
  // Restated here: the first draws of seed 11 and which of them the rule keeps.
  std::mt19937_64 a(11), b(11);
  const std::uint64_t bound = (1ull << 63) + 1, threshold = (1ull << 63) - 1;
  for (int k = 0; k < 20; ++k) {
    std::uint64_t r = b();
    while (r < threshold) r = b();
    EXPECT_EQ(compiler::uniform_below(a, bound), r % bound);
  }
}

// The algorithm restated from its description: positions n-1 down to 1 swap with a draw in [0, i].
std::vector<std::size_t> restated_fisher_yates(std::size_t n, std::uint64_t seed) {
  std::vector<std::size_t> v(n);
  std::iota(v.begin(), v.end(), std::size_t{0});
  std::mt19937_64 rng(seed);
  for (std::size_t i = n; i-- > 1;) {
    const std::uint64_t bound = i + 1;
    const std::uint64_t threshold = (std::numeric_limits<std::uint64_t>::max() - bound + 1) % bound;
    std::uint64_t r = rng();
    while (r < threshold) r = rng();
    std::swap(v[i], v[static_cast<std::size_t>(r % bound)]);
  }
  return v;
}

TEST(Shuffle, SameSeedSameOrder) {
  for (std::uint64_t seed : {0ull, 1ull, 42ull, 1995ull, 0xFFFFFFFFFFFFFFFFull}) {
    const auto p = compiler::seeded_permutation(37, seed);
    EXPECT_EQ(p, compiler::seeded_permutation(37, seed));
    EXPECT_EQ(p, restated_fisher_yates(37, seed));
    auto sorted = p;
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::size_t> identity(37);
    std::iota(identity.begin(), identity.end(), std::size_t{0});
    EXPECT_EQ(sorted, identity);
  }
  EXPECT_NE(compiler::seeded_permutation(37, 1), compiler::seeded_permutation(37, 2));
  EXPECT_TRUE(compiler::seeded_permutation(0, 5).empty());
  EXPECT_EQ(compiler::seeded_permutation(1, 5), std::vector<std::size_t>{0});
}

// Each of the 6 orders of 3 frames should come up about equally often over many seeds
// (deterministic: the seeds are fixed, so this cannot flake).
TEST(Shuffle, AllOrdersAreAboutEquallyLikely) {
  std::map<std::vector<std::size_t>, int> seen;
  const int seeds = 60000;
  for (int s = 0; s < seeds; ++s) ++seen[compiler::seeded_permutation(3, static_cast<std::uint64_t>(s))];
  ASSERT_EQ(seen.size(), 6u);
  for (const auto& [order, count] : seen) EXPECT_NEAR(count, seeds / 6.0, 0.05 * seeds / 6.0);
}

TEST(GoldenShuffle, FixedSeedAndDate) {
  const fs::path movie_path = movie_with_frames("golden-shuffle", 12);
  Diagnostics d;
  auto movie = compiler::read_movie(movie_path, d);
  ASSERT_TRUE(movie) << compiler::format_diagnostics(d);
  const auto s = compiler::shuffle_movie(*movie, 1995, "session.movie", "1995-06-01", "14:30:00");
  testws::check_golden("tests/golden/movie/session-seed-1995.shuffle", compiler::format_shuffle(s));
}

TEST(Movie, ShuffleFileRoundTrip) {
  const fs::path movie_path = movie_with_frames("round-trip", 25);
  Diagnostics d;
  auto movie = compiler::read_movie(movie_path, d);
  ASSERT_TRUE(movie);
  ASSERT_EQ(movie->frames.size(), 25u);
  const auto s = compiler::shuffle_movie(*movie, 99, "session.movie", "2024-02-29", "23:59:59");
  const fs::path out = compiler::default_shuffle_path(movie_path, s.date, s.time);
  EXPECT_EQ(out.filename(), "session-20240229-235959.shuffle");
  std::ofstream(out, std::ios::binary) << compiler::format_shuffle(s);
  EXPECT_TRUE(compiler::looks_like_shuffle(out));
  EXPECT_FALSE(compiler::looks_like_shuffle(movie_path));
  auto back = compiler::read_shuffle(out, d);
  ASSERT_TRUE(back) << compiler::format_diagnostics(d);
  EXPECT_EQ(back->movie, "session.movie");
  EXPECT_EQ(back->date, "2024-02-29");
  EXPECT_EQ(back->time, "23:59:59");
  ASSERT_EQ(back->frames.size(), 25u);
  for (std::size_t k = 0; k < 25; ++k) {
    EXPECT_EQ(back->frames[k].original_index, s.frames[k].original_index);
    EXPECT_EQ(back->frames[k].name, s.frames[k].name);
    // The name at position k is the movie's frame at its original (1-based) index.
    EXPECT_EQ(back->frames[k].name, movie->frames[back->frames[k].original_index - 1]);
  }
  compiler::check_shuffle_against_movie(*back, *movie, {}, d);
  EXPECT_FALSE(d.has_errors()) << compiler::format_diagnostics(d);
}

TEST(Movie, WriteAndReadBack) {
  const fs::path dir = test::temp_dir("movie-write");
  std::vector<std::string> names{"a.hws", "b c.hws", "sub/d.hws"};
  fs::create_directories(dir / "sub");
  for (const auto& n : names) std::ofstream(dir / n) << "";
  compiler::write_movie(dir / "m.movie", names);
  Diagnostics d;
  auto m = compiler::read_movie(dir / "m.movie", d);
  ASSERT_TRUE(m) << compiler::format_diagnostics(d);
  EXPECT_EQ(m->frames, names);
}

TEST(Movie, MacintoshLineEndsAndBlankLines) {
  const fs::path dir = test::temp_dir("movie-cr");
  for (const char* n : {"a.hws", "b.hws", "c.hws"}) std::ofstream(dir / n) << "";
  std::ofstream(dir / "m.movie", std::ios::binary) << "a.hws\r  b.hws  \r\n\r\nc.hws";
  Diagnostics d;
  auto m = compiler::read_movie(dir / "m.movie", d);
  ASSERT_TRUE(m) << compiler::format_diagnostics(d);
  EXPECT_EQ(m->frames, (std::vector<std::string>{"a.hws", "b.hws", "c.hws"}));
  ASSERT_EQ(m->frame_locations.size(), 3u);
  EXPECT_EQ(m->frame_locations[1].line, 2);
  EXPECT_EQ(m->frame_locations[1].column, 3);
  EXPECT_EQ(m->frame_locations[2].line, 4);
}

TEST(Movie, AtMostAHundredFrames) {
  Diagnostics ok;
  EXPECT_TRUE(compiler::read_movie(movie_with_frames("movie-100", 100), ok));
  Diagnostics d;
  EXPECT_FALSE(compiler::read_movie(movie_with_frames("movie-101", 101), d));
  EXPECT_EQ(codes(d), std::vector<std::string>{"E0511"});
  EXPECT_EQ(d.all().front().location.line, 101);
  EXPECT_THROW(compiler::format_movie(std::vector<std::string>(101, "x.hws")), std::invalid_argument);
  EXPECT_THROW(compiler::format_movie({"a\nb.hws"}), std::invalid_argument);
}

TEST(Movie, NamesMustExist) {
  const fs::path dir = test::temp_dir("movie-missing");
  std::ofstream(dir / "a.hws") << "";
  std::ofstream(dir / "m.movie") << "a.hws\nmissing.hws\n";
  Diagnostics d;
  EXPECT_FALSE(compiler::read_movie(dir / "m.movie", d));
  EXPECT_EQ(codes(d), std::vector<std::string>{"E0512"});
  EXPECT_EQ(d.all().front().location.line, 2);
  Diagnostics e;
  std::ofstream(dir / "empty.movie") << "\n\n";
  EXPECT_FALSE(compiler::read_movie(dir / "empty.movie", e));
  EXPECT_EQ(codes(e), std::vector<std::string>{"E0513"});
  Diagnostics f;
  EXPECT_FALSE(compiler::read_movie(dir / "nope.movie", f));
  EXPECT_EQ(codes(f), std::vector<std::string>{"E0510"});
}

std::vector<std::string> shuffle_codes(const std::string& text) {
  Diagnostics d;
  auto f = std::make_shared<const compiler::SourceFile>("<shuffle>", text);
  auto s = compiler::parse_shuffle(f, d);
  EXPECT_EQ(s.has_value(), !d.has_errors());
  return codes(d);
}

TEST(Movie, ShuffleFileErrors) {
  const std::string head = "Movie: m.movie\nDate: 1995-06-01\nTime: 14:30:00\n\n";
  EXPECT_TRUE(shuffle_codes(head + "2 b.hws\n1 a.hws\n").empty());
  // The thesis wrote "Movie:<filename>" without a space; both read.
  EXPECT_TRUE(shuffle_codes("Movie:m.movie\nDate: d\nTime: t\n\n1 a.hws\n").empty());
  EXPECT_EQ(shuffle_codes("Date: 1995-06-01\nMovie: m\nTime: t\n\n1 a.hws\n"), std::vector<std::string>{"E0521"});
  EXPECT_EQ(shuffle_codes("Movie: m\nDate: d\nTime: t\n1 a.hws\n"), std::vector<std::string>{"E0521"});
  EXPECT_EQ(shuffle_codes(head + "a.hws\n1\n"), (std::vector<std::string>{"E0522", "E0522"}));
  EXPECT_EQ(shuffle_codes(head + "1 a.hws\n1 b.hws\n"), std::vector<std::string>{"E0523"});
  EXPECT_EQ(shuffle_codes(head + "0 a.hws\n3 b.hws\n"), (std::vector<std::string>{"E0523", "E0523"}));
}

TEST(Movie, ShuffleMustFitItsMovie) {
  compiler::Movie m;
  m.frames = {"a.hws", "b.hws", "c.hws"};
  compiler::Shuffle s{"m.movie", "1995-06-01", "14:30:00", {{2, "b.hws"}, {3, "c.hws"}, {1, "a.hws"}}};
  Diagnostics ok;
  compiler::check_shuffle_against_movie(s, m, {}, ok);
  EXPECT_FALSE(ok.has_errors());
  s.frames[0].name = "x.hws";
  Diagnostics bad;
  compiler::check_shuffle_against_movie(s, m, {}, bad);
  EXPECT_EQ(codes(bad), std::vector<std::string>{"E0524"});
  m.frames.pop_back();
  Diagnostics shorter;
  compiler::check_shuffle_against_movie(s, m, {}, shorter);
  EXPECT_EQ(codes(shorter), std::vector<std::string>{"E0524"});
}

TEST(Movie, DatesAndTimes) {
  EXPECT_TRUE(compiler::is_valid_date("1995-06-01"));
  EXPECT_TRUE(compiler::is_valid_date("2024-02-29"));
  EXPECT_FALSE(compiler::is_valid_date("2023-02-29"));
  EXPECT_FALSE(compiler::is_valid_date("1995-13-01"));
  EXPECT_FALSE(compiler::is_valid_date("95-06-01"));
  EXPECT_TRUE(compiler::is_valid_time("00:00:00"));
  EXPECT_TRUE(compiler::is_valid_time("23:59:59"));
  EXPECT_FALSE(compiler::is_valid_time("24:00:00"));
  EXPECT_FALSE(compiler::is_valid_time("2:30 PM"));
  std::string date, time;
  compiler::local_date_time_now(date, time);
  EXPECT_TRUE(compiler::is_valid_date(date)) << date;
  EXPECT_TRUE(compiler::is_valid_time(time)) << time;
}

}  // namespace
}  // namespace sandpaper
