// The SQLite index: what it stores, search and near over it, and that a failed rebuild leaves the
// previous index byte-identical.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <fstream>
#include <map>
#include <set>
#include <numbers>
#include <streambuf>
#include <tuple>
#include <sstream>
#include <stdexcept>

#include "curation_test_support.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/near.hpp"
#include "sandpaper/curation/percepts.hpp"
#include "sandpaper/curation/search.hpp"
#include "test_support.hpp"

namespace sandpaper::test {
namespace {

using namespace sandpaper::curation;

IndexBuildResult build(const std::filesystem::path& lib, const std::filesystem::path& index) {
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  return build_index({lib, {}, index, "sim"}, quiet);
}

std::vector<std::string> names(const std::vector<SearchHit>& hits) {
  std::vector<std::string> out;
  for (const auto& h : hits) out.push_back(h.entry.name);
  return out;
}

TEST(LibraryIndex, DebiansSqliteHasFts5) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(":memory:", &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, "CREATE VIRTUAL TABLE t USING fts5(x); INSERT INTO t VALUES ('ribbed cloth');", nullptr, nullptr, &err);
  EXPECT_EQ(rc, SQLITE_OK) << (err ? err : "");
  sqlite3_free(err);
  sqlite3_close(db);
}

struct Built {
  std::filesystem::path lib, index;
};

Built built(const std::string& tag) {
  Built b{mini_library_copy(tag), {}};
  b.index = b.lib.parent_path() / "idx" / "library.sqlite";
  const auto r = build(b.lib, b.index);
  EXPECT_TRUE(r.ok) << r.error << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.entries, 5u);
  return b;
}

TEST(LibraryIndex, StoresMetadataCoordinatesAndProvenanceWithSources) {
  const auto b = built("index-store");
  const Index idx(b.index);
  EXPECT_EQ(idx.meta("library_version"), "0.1.0");
  EXPECT_EQ(idx.meta("device"), "sim");
  const auto e = idx.entry("ribbed-cloth");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->family, "textiles");
  EXPECT_EQ(e->family_title, "Textiles");
  EXPECT_EQ(e->file, "textiles/ribbed-cloth.hmat");
  EXPECT_EQ(e->aliases, std::vector<std::string>{"rib-cloth"});
  EXPECT_NEAR(e->roughness, 0.45, 1e-6);
  // Figure 19's ratio scale, restated: F = 382 gf * r^(1 / 0.759593).
  EXPECT_NEAR(e->max_lateral_force_N, expected_force_for_roughness(0.45), 0.01 * expected_force_for_roughness(0.45));
  EXPECT_EQ(e->texture_kind, "grating");
  EXPECT_NEAR(e->period_m, 0.0032, 1e-12);
  EXPECT_EQ(e->period_class, "transitional");
  EXPECT_NE(e->physical.find("grating period 3.2 mm, hill 60 %"), std::string::npos) << e->physical;
  EXPECT_EQ(idx.entry("old-grit")->deprecated_by, "coarse-grit");
  EXPECT_EQ(idx.resolve("grit-80"), "coarse-grit");

  bool period_sourced = false;
  for (const auto& p : idx.provenance("ribbed-cloth"))
    if (p.parameter == "texture.period") {
      EXPECT_EQ(p.si_unit, "m");
      EXPECT_EQ(p.layer, "physical");
      ASSERT_FALSE(p.notes.empty());
      EXPECT_EQ(p.notes[0].first, "derived");
      EXPECT_EQ(p.notes[0].second, "8 ribs per inch: 25.4 mm / 8");
      period_sourced = true;
    }
  EXPECT_TRUE(period_sourced);
  // Inherited through `like`: fine-rib's hill comes from ribbed-cloth's grating, with its source.
  bool hill_inherited = false;
  for (const auto& p : idx.provenance("fine-rib"))
    if (p.parameter == "texture.hill") {
      ASSERT_FALSE(p.notes.empty()) << p.source;
      EXPECT_EQ(p.notes[0].second, "8 ribs per inch: 25.4 mm / 8");
      hill_inherited = true;
    }
  EXPECT_TRUE(hill_inherited);
  const auto st = idx.statements("ribbed-cloth");
  ASSERT_EQ(st.size(), 6u);  // describes, family, alias, licence, grating, roughness (sources attach)
  EXPECT_EQ(st[4].keyword, "grating");
  ASSERT_EQ(st[4].sources.size(), 1u);
  EXPECT_EQ(st[4].sources[0].first, "derived");
}

TEST(LibrarySearch, ByNameAliasWordsPrefixRangeAndFamily) {
  const auto b = built("index-search");
  const Index idx(b.index);
  auto q = [&](std::vector<std::string> words, std::optional<RoughnessRange> r = {}, std::string family = {}) {
    SearchQuery s;
    s.words = std::move(words);
    s.roughness = r;
    s.family = std::move(family);
    return search(idx, s);
  };
  // A name first, even though other entries mention it (fine-rib's description names the ribbed cloth).
  auto by_name = q({"ribbed-cloth"});
  ASSERT_FALSE(by_name.empty());
  EXPECT_EQ(by_name[0].entry.name, "ribbed-cloth");
  EXPECT_EQ(by_name[0].why, "name");
  auto by_alias = q({"grit-80"});
  ASSERT_FALSE(by_alias.empty());
  EXPECT_EQ(by_alias[0].entry.name, "coarse-grit");
  EXPECT_EQ(by_alias[0].matched_alias, "grit-80");
  EXPECT_EQ(names(q({"sharp", "grains"})), std::vector<std::string>{"coarse-grit"});
  auto prefix = names(q({"sandp"}));  // the last word is a prefix: "sandpaper"
  std::sort(prefix.begin(), prefix.end());
  EXPECT_EQ(prefix, (std::vector<std::string>{"coarse-grit", "old-grit"}));
  EXPECT_EQ(names(q({}, parse_roughness_range("0.4..0.6"))), (std::vector<std::string>{"ribbed-cloth", "reference-grating"}));
  EXPECT_EQ(names(q({}, parse_roughness_range("..0.3"))), std::vector<std::string>{"fine-rib"});
  auto fam = names(q({}, {}, "abrasives"));
  std::sort(fam.begin(), fam.end());
  EXPECT_EQ(fam, (std::vector<std::string>{"coarse-grit", "old-grit"}));
  EXPECT_EQ(names(q({"ribbed"}, {}, "abrasives")), std::vector<std::string>{});
  EXPECT_TRUE(q({"velvet"}).empty());
  try {
    q({}, {}, "abrasive");
    ADD_FAILURE() << "an unknown family should throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'abrasives'?"), std::string::npos) << e.what();
  }
}

TEST(LibrarySearch, ABoundEqualToTheWrittenRoughnessFindsIt) {
  const auto b = built("index-bounds");
  const Index idx(b.index);
  auto only = [&](const std::string& range) {
    SearchQuery s;
    s.roughness = parse_roughness_range(range);
    return names(search(idx, s));
  };
  // Each entry's file says `roughness X`; the index holds what the map's round trip gives back,
  // which may differ from X in the last bits. A bound written as X takes it in, at either end.
  EXPECT_EQ(only("0.2..0.2"), std::vector<std::string>{"fine-rib"});
  EXPECT_EQ(only("0.45..0.45"), std::vector<std::string>{"ribbed-cloth"});
  EXPECT_EQ(only("0.8..0.8"), (std::vector<std::string>{"coarse-grit", "old-grit"}));  // old-grit is like coarse-grit
  EXPECT_EQ(only("..0.2"), std::vector<std::string>{"fine-rib"});
  EXPECT_TRUE(only("0.2001..0.44").empty());
}

TEST(LibrarySearch, RoughnessRangesAndTheirErrors) {
  auto r = parse_roughness_range("0.4..0.6");
  EXPECT_EQ(r.min, 0.4);
  EXPECT_EQ(r.max, 0.6);
  EXPECT_FALSE(parse_roughness_range("0.4..").max);
  EXPECT_FALSE(parse_roughness_range("..0.6").min);
  for (const char* bad : {"0.4", "..", "a..b", "0.6..0.4", "0.1..0.2..0.3", "-1..2"}) {
    try {
      parse_roughness_range(bad);
      ADD_FAILURE() << bad << " should be refused";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("A..B"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(fts_query({"wide", "wal"}), "\"wide\" \"wal\"*");
  EXPECT_EQ(fts_query({"say\"x"}), "\"say\"\"x\"*");
}

TEST(LibraryIndex, AFailedRebuildLeavesThePreviousIndexByteIdentical) {
  const auto b = built("index-atomic");
  const auto before = read(b.index);
  ASSERT_FALSE(before.empty());
  // An entry that does not compile (roughness above 1 without `extrapolate`: E0303).
  write(b.lib / "textiles/too-rough.hmat", R"(material "too-rough" {
  describes "rougher than the scale"
  family textiles
  licence "CC0-1.0"
  grating period 2 mm
  source by-ear "x"
  roughness 5
  source by-ear "x"
}
)");
  const auto r = build(b.lib, b.index);
  EXPECT_FALSE(r.ok);
  ASSERT_TRUE(r.diagnostics.has_errors());
  EXPECT_EQ(r.diagnostics.all()[0].code, "E0303");
  EXPECT_NE(r.diagnostics.all()[0].location.str().find("textiles/too-rough.hmat:7:"), std::string::npos);
  EXPECT_EQ(read(b.index), before);
  for (const auto& f : std::filesystem::directory_iterator(b.index.parent_path()))
    EXPECT_EQ(f.path().filename(), "library.sqlite") << "left behind: " << f.path();
  const Index idx(b.index);
  SearchQuery q;
  q.words = {"grit-80"};
  EXPECT_EQ(names(search(idx, q)), std::vector<std::string>{"coarse-grit"});
  EXPECT_FALSE(idx.entry("too-rough"));
  // An unwritable place: an I/O failure, reported, nothing written.
  const auto blocked = b.lib.parent_path() / "file-not-dir";
  write(blocked, "x");
  std::filesystem::remove(b.lib / "textiles/too-rough.hmat");
  const auto io = build(b.lib, blocked / "library.sqlite");
  EXPECT_FALSE(io.ok);
  EXPECT_FALSE(io.error.empty());
}

// The JSON columns and the Weber fraction of an index edited or damaged since it was built: a reader
// reports the index as damaged, naming what and the way to mend it, not the JSON library's or
// std::stod's exception (F43); a full rebuild mends it. The index is written only by Sandpaper, but
// it is a file on disk all the same.
TEST(LibraryIndex, ADamagedColumnIsReportedWithWhatIsDamagedAndTheWayToMendIt) {
  const auto b = built("index-damaged-json");
  auto damage = [&](const std::string& sql) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(b.index.c_str(), &db), SQLITE_OK);
    char* err = nullptr;
    EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err), SQLITE_OK) << (err ? err : "");
    sqlite3_free(err);
    sqlite3_close(db);
  };
  auto error_of = [](const std::function<void()>& read) -> std::string {
    try {
      read();
    } catch (const IndexError& e) {
      return e.what();
    } catch (const std::exception& e) {
      return std::string("not an IndexError: ") + e.what();
    }
    return "no error";
  };
  for (const char* bad : {"not json", "", "{}", "[1]", "[[1, 2]]", "[[\"a\"]]", "[[\"a\", \"b\"]]", "[[\"a\", 1, 2]]"}) {
    damage(std::string("UPDATE entries SET term_params = '") + bad + "' WHERE name = 'ribbed-cloth'");
    const Index idx(b.index);
    const std::string what = error_of([&] { (void)idx.entry("ribbed-cloth"); });
    EXPECT_NE(what.find(b.index.string() + " is damaged: entry 'ribbed-cloth': its term_params is not a JSON list of "
                                            "[name, number] pairs; rebuild it with `sandpaper library index --full`"),
              std::string::npos)
        << bad << ": " << what;
    EXPECT_EQ(error_of([&] { (void)idx.entries(); }), what) << bad;
    EXPECT_EQ(error_of([&] { (void)idx.entry("coarse-grit"); }), "no error") << "an undamaged entry still reads";
  }
  damage("UPDATE entries SET term_params = '[[\"grating.period_m\", 0.0032]]' WHERE name = 'ribbed-cloth'");
  EXPECT_EQ(error_of([&] { (void)Index(b.index).entry("ribbed-cloth"); }), "no error");

  for (const char* bad : {"[[\"derived\", 8]]", "[\"derived\"]", "null"}) {
    damage(std::string("UPDATE provenance SET notes = '") + bad + "' WHERE name = 'ribbed-cloth'");
    const std::string what = error_of([&] { (void)Index(b.index).provenance("ribbed-cloth"); });
    EXPECT_NE(what.find(" is damaged: entry 'ribbed-cloth': the notes of its "), std::string::npos) << bad << ": " << what;
    EXPECT_NE(what.find("is not a JSON list of [name, text] pairs"), std::string::npos) << what;
  }

  // The Weber fraction `near` measures distances in, kept as text in `meta`.
  EXPECT_EQ(error_of([&] { (void)nearest(Index(b.index), "ribbed-cloth", 3); }), "no error");
  for (const char* bad : {"x", "", "0", "-0.1", "2", "nan", "0.125x"}) {
    damage(std::string("UPDATE meta SET value = '") + bad + "' WHERE key = 'weber_fraction'");
    const std::string what = error_of([&] { (void)nearest(Index(b.index), "ribbed-cloth", 3); });
    EXPECT_NE(what.find(" is damaged: its weber_fraction is '" + std::string(bad) +
                        "', not a number in (0, 1]; rebuild it with `sandpaper library index --full`"),
              std::string::npos)
        << bad << ": " << what;
  }

  // Before, 0 and nan reached the search for neighbours, whose box never grew: it never ended.
  const Index undamaged_entries(b.index);
  const auto from = undamaged_entries.entry("ribbed-cloth");
  ASSERT_TRUE(from);
  for (const double w : {0.0, -1.0, std::nan(""), 2.0})
    EXPECT_THROW((void)nearest_to(undamaged_entries, *from, 3, w), std::invalid_argument) << w;

  damage("UPDATE entries SET term_params = 'not json' WHERE name = 'ribbed-cloth'");
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  IndexOptions full{b.lib, {}, b.index, "sim"};
  full.full = true;
  const auto r = build_index(full, quiet);
  ASSERT_TRUE(r.ok) << r.error;
  const Index mended(b.index);
  EXPECT_EQ(error_of([&] { (void)mended.entries(); }), "no error");
  EXPECT_NEAR(mended.weber_fraction(), 0.125, 1e-9);
  bool period_sourced = false;
  for (const auto& p : mended.provenance("ribbed-cloth"))
    period_sourced = period_sourced || (p.parameter == "texture.period" && !p.notes.empty() && p.notes[0].first == "derived");
  EXPECT_TRUE(period_sourced);
}

TEST(LibraryIndex, KnowsWhenItIsStale) {
  const auto b = built("index-stale");
  EXPECT_EQ(index_state(b.index, b.lib, calibration::default_calibration_dir()), IndexState::Fresh);
  edit(b.lib / "textiles/fine-rib.hmat", "roughness 0.2", "roughness 0.25");
  EXPECT_EQ(index_state(b.index, b.lib, calibration::default_calibration_dir()), IndexState::Stale);
  EXPECT_EQ(index_state(b.index.parent_path() / "none.sqlite", b.lib, calibration::default_calibration_dir()), IndexState::Missing);
  // Files under hidden folders (the index's own .index/) do not count.
  write(b.lib / ".index/scratch", "x");
  const auto fp = library_fingerprint(b.lib, calibration::default_calibration_dir());
  write(b.lib / ".index/scratch", "y");
  EXPECT_EQ(library_fingerprint(b.lib, calibration::default_calibration_dir()), fp);
}

// Every row about each entry, as text, by entry name (all tables but meta, families and the stamps).
std::map<std::string, std::string> rows_by_entry(const std::filesystem::path& index) {
  std::map<std::string, std::string> out;
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(index.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  const char* queries[] = {
      "SELECT name, * FROM entries ORDER BY name",
      "SELECT name, alias FROM aliases ORDER BY name, alias",
      "SELECT name, percept, value FROM percepts ORDER BY name, rowid",
      "SELECT name, * FROM statements ORDER BY name, ordinal",
      "SELECT name, * FROM sources ORDER BY name, ordinal, rowid",
      "SELECT name, * FROM provenance ORDER BY name, ordinal",
      "SELECT name, hash FROM inputs ORDER BY name",
      "SELECT name, kind, target FROM depends ORDER BY name, kind, target",
      "SELECT name, aliases, describes, family FROM search ORDER BY name",
      "SELECT e.name, c.log_force_min, c.log_force_max, c.log_period_min, c.log_period_max, k.kind_terms FROM coordinates c "
      "JOIN classes k ON k.id = c.class_min "
      "JOIN entries e ON e.rowid = c.id ORDER BY e.name",
      // The two row ids must agree, or search and near would name the wrong entry.
      "SELECT e.name, e.name = s.name FROM entries e JOIN search s ON s.rowid = e.rowid ORDER BY e.name"};
  for (const char* q : queries) {
    sqlite3_stmt* st = nullptr;
    EXPECT_EQ(sqlite3_prepare_v2(db, q, -1, &st, nullptr), SQLITE_OK) << q;
    while (sqlite3_step(st) == SQLITE_ROW) {
      std::string row = std::string(q).substr(0, 40) + ":";
      for (int c = 1; c < sqlite3_column_count(st); ++c) {
        const auto* t = sqlite3_column_text(st, c);
        row += std::string("|") + (t ? reinterpret_cast<const char*>(t) : "NULL");
      }
      out[reinterpret_cast<const char*>(sqlite3_column_text(st, 0))] += row + "\n";
    }
    sqlite3_finalize(st);
  }
  sqlite3_close(db);
  return out;
}

// The rows a build from nothing (`--full`) writes for `lib`, into a fresh file beside it.
std::map<std::string, std::string> rows_of_a_full_build(const std::filesystem::path& lib) {
  const auto full = lib.parent_path() / "full" / "library.sqlite";
  std::filesystem::remove(full);
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  IndexOptions o{lib, {}, full, "sim"};
  o.full = true;
  EXPECT_TRUE(build_index(o, quiet).ok);
  return rows_by_entry(full);
}

TEST(LibraryIndex, ARebuildCompilesOnlyWhatChangedAndWhatIsBuiltOnIt) {
  const auto b = built("index-incremental");
  const auto before = rows_by_entry(b.index);
  ASSERT_EQ(before.size(), 5u);
  // Nothing changed: nothing compiled, every row as it was.
  auto r = build(b.lib, b.index);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.compiled, 0u);
  EXPECT_EQ(r.reused, 5u);
  EXPECT_EQ(rows_by_entry(b.index), before);
  // One entry changed: it, and old-grit, which is built on it (`like coarse-grit`), are compiled.
  edit(b.lib / "abrasives/coarse-grit.hmat", "roughness 0.8", "roughness 0.85");
  r = build(b.lib, b.index);
  ASSERT_TRUE(r.ok) << r.error << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.compiled, 2u);
  EXPECT_EQ(r.reused, 3u);
  EXPECT_TRUE(r.in_place);
  const auto after = rows_by_entry(b.index);
  for (const auto& [name, rows] : before)
    if (name == "coarse-grit" || name == "old-grit") EXPECT_NE(after.at(name), rows) << name;
    else EXPECT_EQ(after.at(name), rows) << name << " changed, though nothing it is built from did";
  // And the result is what a full build gives.
  EXPECT_EQ(rows_of_a_full_build(b.lib), after);
  // A removed entry's rows go; nothing else is compiled.
  std::filesystem::remove(b.lib / "textiles/fine-rib.hmat");
  r = build(b.lib, b.index);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.compiled, 0u);
  EXPECT_EQ(rows_by_entry(b.index).count("fine-rib"), 0u);
}

// A few changed entries are updated in the index itself, reading only their files and what they
// are built on; every step must give the rows a full build gives.
TEST(LibraryIndex, AFewChangedEntriesAreUpdatedInPlaceAsAFullBuildWould) {
  const auto b = built("index-in-place");
  const auto photos = std::filesystem::path(SANDPAPER_SOURCE_DIR) / "library/images";
  std::filesystem::create_directories(b.lib / "images");
  std::filesystem::copy_file(photos / "gravel.png", b.lib / "images/stones.png");
  auto step = [&](const char* what, std::size_t compiled, bool in_place = true) {
    const auto before = rows_by_entry(b.index);
    const auto r = build(b.lib, b.index);
    EXPECT_TRUE(r.ok) << what << ": " << r.error << compiler::format_diagnostics(r.diagnostics);
    EXPECT_EQ(r.in_place, in_place) << what;
    EXPECT_EQ(r.compiled, compiled) << what;
    const auto after = rows_by_entry(b.index);
    EXPECT_EQ(r.entries, after.size()) << what;
    EXPECT_EQ(rows_of_a_full_build(b.lib), after) << what;
    return std::make_pair(before, after);
  };
  // New entries: one built on an alias, one bare roughness (built on the reference), one photograph.
  write(b.lib / "textiles/soft-rib.hmat",
        "material \"soft-rib\" {\n  describes \"a softer rib\"\n  family textiles\n  licence \"CC0-1.0\"\n  like rib-cloth\n"
        "  roughness 0.3\n  source by-ear \"soft\"\n}\n");
  write(b.lib / "textiles/bare.hmat",
        "material \"bare\" {\n  describes \"a roughness alone\"\n  family textiles\n  licence \"CC0-1.0\"\n  roughness 0.3\n"
        "  source by-ear \"between\"\n}\n");
  write(b.lib / "abrasives/stones.hmat",
        "material \"stones\" {\n  describes \"small stones\"\n  family abrasives\n  licence \"CC0-1.0\"\n"
        "  heightmap \"../images/stones.png\" size 20 mm\n  source by-ear \"about 1 mm stones\"\n  roughness 0.4\n"
        "  source by-ear \"rough\"\n}\n");
  step("three new entries", 3);
  // An entry others are built on, through its name and its alias: it and both of them.
  std::map<std::string, std::string> before, after;
  edit(b.lib / "textiles/ribbed-cloth.hmat", "roughness 0.45", "roughness 0.5");
  std::tie(before, after) = step("ribbed-cloth edited", 3);
  for (const auto& [name, rows] : before)
    if (name != "ribbed-cloth" && name != "fine-rib" && name != "soft-rib") {
      EXPECT_EQ(after.at(name), rows) << name;
    }
  // The reference entry: it, and the bare roughness that starts from it.
  edit(b.lib / "reference/reference-grating.hmat", "roughness 0.5", "roughness 0.55");
  step("reference edited", 2);
  // An image: the entry whose heightmap reads it.
  std::filesystem::copy_file(photos / "brick.png", b.lib / "images/stones.png", std::filesystem::copy_options::overwrite_existing);
  step("image replaced", 1);
  // A second file with a taken name: which one counts is decided over the whole library.
  write(b.lib / "textiles/coarse-grit.hmat", read(b.lib / "abrasives/coarse-grit.hmat"));
  step("a name taken twice", 0, false);
  std::filesystem::remove(b.lib / "textiles/coarse-grit.hmat");
  // A removed entry's rows go, in place.
  std::filesystem::remove(b.lib / "textiles/soft-rib.hmat");
  std::tie(before, after) = step("soft-rib removed", 0);
  EXPECT_EQ(after.count("soft-rib"), 0u);
  // Nothing changed: nothing is written at all. The files written above are within the 2 s racy
  // window of the last build, and a build that starts after it has passed rewrites their stamps as
  // settled (on a loaded machine the next build may start that late). So age every file and
  // folder past the window, and let one build record them, before checking that a build writes nothing.
  for (const auto& e : std::filesystem::recursive_directory_iterator(b.lib)) {
    if (e.path().filename().string().rfind('.', 0) == 0) continue;
    std::filesystem::last_write_time(e.path(), std::filesystem::file_time_type::clock::now() - std::chrono::seconds(10));
  }
  std::filesystem::last_write_time(b.lib, std::filesystem::file_time_type::clock::now() - std::chrono::seconds(10));
  ASSERT_TRUE(build(b.lib, b.index).ok);
  const auto bytes = read(b.index);
  const auto r = build(b.lib, b.index);
  EXPECT_TRUE(r.ok && !r.in_place && r.compiled == 0 && r.reused == r.entries) << r.error;
  EXPECT_EQ(read(b.index), bytes);
}

TEST(LibraryIndex, CalibrationAndManifestChangesRecompileEverything) {
  const auto b = built("index-calibration");
  const auto cal = calibration_copy("index-calibration");
  IndexOptions o{b.lib, cal, b.index, "sim"};
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  // A copy of the same calibration: the same content, so the same inputs (content-addressed).
  auto r = build_index(o, quiet);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.compiled, 0u);
  write(cal / "knowledge/unrelated-note.md", "a file the calibration folder gained");
  r = build_index(o, quiet);
  EXPECT_EQ(r.compiled, 5u);
  edit(b.lib / "library.toml", "version = \"0.1.0\"", "version = \"0.2.0\"");
  r = build_index(o, quiet);
  EXPECT_EQ(r.compiled, 5u);
  EXPECT_EQ(Index(b.index).entry("fine-rib")->library_version, "0.2.0");
}

// A Progress stream that ends the process, as kill -9 would, after `lines` lines.
class DieAfter : public std::streambuf {
 public:
  explicit DieAfter(int lines) : left_(lines) {}
  int overflow(int ch) override {
    if (ch == '\n' && --left_ == 0) ::_exit(9);
    return ch;
  }

 private:
  int left_;
};

TEST(LibraryIndex, AKilledBuildIsResumedAndLeavesTheIndexAsItWas) {
  const auto b = built("index-resume");
  const std::string index_before = read(b.index);
  for (const char* f : {"textiles/ribbed-cloth.hmat", "textiles/fine-rib.hmat", "abrasives/coarse-grit.hmat",
                        "abrasives/old-grit.hmat", "reference/reference-grating.hmat"})
    write(b.lib / f, read(b.lib / f) + "# edited\n");
  IndexOptions o{b.lib, {}, b.index, "sim"};
  o.batch = 1;  // commit after each entry, so that the kill finds some entries done
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    DieAfter die(3);
    std::ostream out(&die);
    Progress progress("indexing", 5, false, out, false, 1);  // a line per entry: dies after the third
    (void)build_index(o, progress);
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 9) << "the build was not interrupted";
  EXPECT_EQ(read(b.index), index_before) << "an interrupted build touched the index";
  std::size_t temporaries = 0;
  for (const auto& f : std::filesystem::directory_iterator(b.index.parent_path()))
    temporaries += f.path().filename().string().find(".tmp-") != std::string::npos;
  EXPECT_GE(temporaries, 1u);
  const auto r = build(b.lib, b.index);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.resumed);
  EXPECT_EQ(r.reused, 3u);
  EXPECT_EQ(r.compiled, 2u);
  for (const auto& f : std::filesystem::directory_iterator(b.index.parent_path()))
    EXPECT_EQ(f.path().filename(), "library.sqlite") << "left behind: " << f.path();
  EXPECT_EQ(rows_by_entry(b.index), rows_of_a_full_build(b.lib));
}

// An in-place update killed inside its transaction: readers see the old index (SQLite's journal
// is rolled back by the next opener), and the next build does the update.
TEST(LibraryIndex, AnInPlaceUpdateKilledBeforeItsCommitLeavesTheOldIndex) {
  const auto b = built("index-in-place-kill");
  const auto before = rows_by_entry(b.index);
  const double roughness_before = Index(b.index).entry("ribbed-cloth")->roughness;
  edit(b.lib / "textiles/ribbed-cloth.hmat", "roughness 0.45", "roughness 0.5");  // and fine-rib, built on it
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    DieAfter die(1);
    std::ostream out(&die);
    Progress progress("indexing", 2, false, out, false, 1);  // a line per entry written: dies after the first
    (void)build_index({b.lib, {}, b.index, "sim"}, progress);
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 9) << "the update was not interrupted";
  {
    const Index idx(b.index);  // read-only, as queries open it
    EXPECT_EQ(idx.entry("ribbed-cloth")->roughness, roughness_before);
  }
  EXPECT_EQ(rows_by_entry(b.index), before);
  const auto r = build(b.lib, b.index);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.in_place);
  EXPECT_EQ(r.compiled, 2u);
  EXPECT_EQ(rows_by_entry(b.index), rows_of_a_full_build(b.lib));
  EXPECT_NEAR(Index(b.index).entry("ribbed-cloth")->roughness, 0.5, 1e-9);
}

TEST(LibraryIndex, QueriesCheckFolderStampsAndAnInPlaceEditOfAnOldFolderWaitsForIndex) {
  const auto b = built("index-stamps");
  const auto cal = calibration::default_calibration_dir();
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Fresh);
  // Backdate everything by an hour, so no stamp is racy, and rebuild: the stamps are settled.
  const auto hour_ago = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  for (const auto& e : std::filesystem::recursive_directory_iterator(b.lib)) std::filesystem::last_write_time(e.path(), hour_ago);
  std::filesystem::last_write_time(b.lib, hour_ago);
  ASSERT_TRUE(build(b.lib, b.index).ok);
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Fresh);
  // An edit in place of a file in an old folder keeps the folder's time: queries do not see it
  // (they read no file), `library index` does (it stats every file).
  const auto folder_time = std::filesystem::last_write_time(b.lib / "textiles");
  edit(b.lib / "textiles/fine-rib.hmat", "roughness 0.2", "roughness 0.25");
  ASSERT_EQ(std::filesystem::last_write_time(b.lib / "textiles"), folder_time);
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Fresh);
  auto r = build(b.lib, b.index);
  EXPECT_EQ(r.compiled, 1u);
  // A new file changes its folder's time; so does a save by rename, as editors do.
  write(b.lib / "textiles/new.hmat", read(b.lib / "textiles/fine-rib.hmat"));
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Stale);
  std::filesystem::remove(b.lib / "textiles/new.hmat");
  ASSERT_TRUE(build(b.lib, b.index).ok);
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Fresh);
  write(b.lib / "textiles/.fine-rib.swp", read(b.lib / "textiles/fine-rib.hmat"));
  std::filesystem::rename(b.lib / "textiles/.fine-rib.swp", b.lib / "textiles/fine-rib.hmat");
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Stale);
  // The library root's files are always checked: an in-place edit of library.toml is seen.
  ASSERT_TRUE(build(b.lib, b.index).ok);
  edit(b.lib / "library.toml", "version = \"0.1.0\"", "version = \"0.1.1\"");
  EXPECT_EQ(index_state(b.index, b.lib, cal), IndexState::Stale);
}

// Told which files changed (`library index --changed`), the update stats those alone: an edit it
// was not told of waits for a build that walks; what it writes (rows, stamps, folders, fingerprint)
// is what a walking build writes, so that build then finds nothing to do.
TEST(LibraryIndex, AnUpdateToldWhichFilesChangedLooksAtThemAloneAndAgreesWithAWalk) {
  const auto b = built("index-listed");
  const auto cal = calibration::default_calibration_dir();
  // Every stamp an hour old and each one different, so that none is racy (stamps.hpp) however
  // slowly this runs, and every step's files and folders get a stamp of their own.
  auto stamp = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  auto settle = [&](std::initializer_list<std::filesystem::path> paths) {
    for (const auto& p : paths) std::filesystem::last_write_time(p, stamp += std::chrono::seconds(1));
  };
  write(b.lib / ".index/scratch", "x");
  for (const auto& e : std::filesystem::recursive_directory_iterator(b.lib)) settle({e.path()});
  settle({b.lib});
  ASSERT_TRUE(build(b.lib, b.index).ok);
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  auto listed = [&](std::vector<std::filesystem::path> files) {
    IndexOptions o{b.lib, {}, b.index, "sim"};
    o.changed = std::move(files);
    return build_index(o, quiet);
  };
  // What a walking build says afterwards: nothing changed, and the index's bytes stay.
  auto walk_finds_nothing = [&](const char* what) {
    EXPECT_EQ(Index(b.index).meta("fingerprint"), library_fingerprint(b.lib, cal)) << what;
    const auto bytes = read(b.index);
    const auto r = build(b.lib, b.index);
    EXPECT_TRUE(r.ok && !r.in_place && r.compiled == 0) << what << ": a walk found " << r.compiled << " to compile";
    EXPECT_EQ(read(b.index), bytes) << what;
  };
  const double coarse_before = Index(b.index).entry("coarse-grit")->roughness;
  edit(b.lib / "textiles/ribbed-cloth.hmat", "roughness 0.45", "roughness 0.5");  // fine-rib is built on it
  edit(b.lib / "abrasives/coarse-grit.hmat", "roughness 0.8", "roughness 0.85");  // not listed
  settle({b.lib / "textiles/ribbed-cloth.hmat", b.lib / "abrasives/coarse-grit.hmat"});
  auto r = listed({b.lib / "textiles/ribbed-cloth.hmat"});
  ASSERT_TRUE(r.ok) << r.error << compiler::format_diagnostics(r.diagnostics);
  EXPECT_TRUE(r.in_place);
  EXPECT_EQ(r.compiled, 2u);
  EXPECT_EQ(r.files_hashed, 1u);
  EXPECT_NEAR(Index(b.index).entry("ribbed-cloth")->roughness, 0.5, 1e-9);
  EXPECT_EQ(Index(b.index).entry("coarse-grit")->roughness, coarse_before) << "read a file it was not told of";
  // The walk finds the edit the list left out, and it and old-grit (built on it) are compiled.
  r = build(b.lib, b.index);
  EXPECT_TRUE(r.ok && r.in_place);
  EXPECT_EQ(r.compiled, 2u);
  EXPECT_EQ(rows_by_entry(b.index), rows_of_a_full_build(b.lib));
  walk_finds_nothing("after the walk");

  edit(b.lib / "textiles/fine-rib.hmat", "roughness 0.2", "roughness 0.25");
  settle({b.lib / "textiles/fine-rib.hmat"});
  r = listed({b.lib / "textiles/fine-rib.hmat"});
  EXPECT_TRUE(r.ok && r.in_place && r.compiled == 1) << r.error;
  EXPECT_EQ(rows_by_entry(b.index), rows_of_a_full_build(b.lib));
  walk_finds_nothing("an edit");
  // A new file in a new folder (its folder and the root's stamps change), given relative to the
  // working directory and twice.
  write(b.lib / "leather/suede.hmat",
        "material \"suede\" {\n  describes \"soft suede\"\n  family textiles\n  licence \"CC0-1.0\"\n  like rib-cloth\n"
        "  roughness 0.2\n  source by-ear \"soft\"\n}\n");
  settle({b.lib / "leather/suede.hmat", b.lib / "leather", b.lib});
  const auto suede = std::filesystem::relative(b.lib / "leather/suede.hmat");
  r = listed({suede, b.lib / "leather/suede.hmat"});
  EXPECT_TRUE(r.ok && r.in_place && r.compiled == 1) << r.error;
  ASSERT_TRUE(Index(b.index).entry("suede"));
  walk_finds_nothing("a new file");
  // A removed file: its rows go.
  std::filesystem::remove(b.lib / "leather/suede.hmat");
  settle({b.lib / "leather"});
  r = listed({b.lib / "leather/suede.hmat"});
  EXPECT_TRUE(r.ok && r.in_place && r.compiled == 0) << r.error;
  EXPECT_FALSE(Index(b.index).entry("suede"));
  walk_finds_nothing("a removed file");
  // Hidden files are not the library's; a listed file that did not change writes nothing.
  write(b.lib / ".index/scratch", "y");
  const auto bytes = read(b.index);
  r = listed({b.lib / ".index/scratch", b.lib / "textiles/fine-rib.hmat"});
  EXPECT_TRUE(r.ok && !r.in_place && r.compiled == 0) << r.error;
  EXPECT_EQ(read(b.index), bytes);
  // A second file with a taken name: decided over the whole library, by the walking build.
  write(b.lib / "textiles/coarse-grit.hmat", read(b.lib / "abrasives/coarse-grit.hmat"));
  r = listed({b.lib / "textiles/coarse-grit.hmat"});
  EXPECT_TRUE(r.ok && !r.in_place) << r.error;
  std::filesystem::remove(b.lib / "textiles/coarse-grit.hmat");
  // A file of neither folder is refused, and the index is left as it was.
  const auto before = read(b.index);
  r = listed({b.lib.parent_path() / "elsewhere.hmat"});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("neither the library folder"), std::string::npos) << r.error;
  EXPECT_EQ(read(b.index), before);
}

// Search on the shipped library as a curator types it (docs/LIBRARY.md, "search").
TEST(LibrarySearch, WordsMatchDescriptionsAndFamiliesNotCitationsAndStimuliComeAfterMaterials) {
  const auto dir = std::filesystem::path(temp_dir("search-shipped"));
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  ASSERT_TRUE(build_index({std::filesystem::path(SANDPAPER_SOURCE_DIR) / "library", {}, dir / "i.sqlite", "sim"}, quiet).ok);
  const Index idx(dir / "i.sqlite");
  const auto all = idx.entries();
  std::vector<double> rs;
  for (const auto& e : all)
    if (e.max_lateral_force_N > 0) rs.push_back(e.roughness);
  std::sort(rs.begin(), rs.end());
  const double median = rs[rs.size() / 2];
  const auto query = [&](std::vector<std::string> words, std::string family = "") {
    SearchQuery q;
    q.words = std::move(words);
    q.family = std::move(family);
    q.limit = 500;
    return search(idx, q);
  };
  // "textiles": the textiles, by their family's id, whatever their own words say.
  const auto cloth = query({"textiles"});
  std::set<std::string> textiles;
  for (const auto& e : all)
    if (e.family == "textiles") textiles.insert(e.name);
  std::set<std::string> got;
  for (const auto& h : cloth) got.insert(h.entry.name);
  EXPECT_EQ(got, textiles);
  // "rough textiles": the textiles at or above the library's median roughness, roughest first.
  const auto rough = query({"rough", "textiles"});
  std::vector<std::string> want;
  for (const auto& e : all)
    if (e.family == "textiles" && e.max_lateral_force_N > 0 && e.roughness >= median) want.push_back(e.name);
  std::sort(want.begin(), want.end(), [&](const auto& a, const auto& b) { return idx.entry(a)->roughness > idx.entry(b)->roughness; });
  EXPECT_EQ(names(rough), want);
  EXPECT_GT(want.size(), 2u);
  EXPECT_LT(want.size(), textiles.size());
  // "smooth": the smoother half, smoothest first; the thesis' stimuli after the materials, smoothest first too.
  const auto smooth = query({"smooth"});
  ASSERT_FALSE(smooth.empty());
  for (std::size_t i = 0; i < smooth.size(); ++i) {
    EXPECT_LE(smooth[i].entry.roughness, median) << smooth[i].entry.name;
    if (i && smooth[i - 1].stimulus == smooth[i].stimulus) {
      EXPECT_LE(smooth[i - 1].entry.roughness, smooth[i].entry.roughness);
    }
    if (i) {
      EXPECT_LE(smooth[i - 1].stimulus, smooth[i].stimulus) << smooth[i - 1].entry.name << " before " << smooth[i].entry.name;
    }
  }
  // A citation is not a description: wool-gabardine's source notes name denim-twill; `denim` finds denim.
  EXPECT_EQ(names(query({"denim"})), std::vector<std::string>{"denim-twill"});
  // "grating": the reference grating (a material) before the thesis' Table 8 gratings, which
  // `--family thesis-gratings` still finds.
  const auto gratings = query({"grating"});
  ASSERT_GT(gratings.size(), 2u);
  EXPECT_EQ(gratings.front().entry.name, "reference-grating");
  bool stimuli = false;
  for (const auto& h : gratings) {
    const bool stimulus = h.entry.family.rfind("thesis-", 0) == 0;
    EXPECT_FALSE(stimuli && !stimulus) << h.entry.name << " after a thesis stimulus";
    stimuli = stimuli || stimulus;
  }
  EXPECT_TRUE(stimuli);
  EXPECT_FALSE(query({"grating"}, "thesis-gratings").empty());
  std::filesystem::remove_all(dir);
}

// For every entry and limits 1, `middle` and all: near's R*Tree search gives exactly what comparing
// with every entry gives, each dimension in its percept's JNDs as the index was built
// (weber_fractions.hpp). Returns how many searches were compared.
std::size_t expect_search_equals_full_scan(const Index& idx, std::size_t middle) {
  const auto all = idx.entries();
  const WeberFractions weber = idx.weber_fractions();
  std::size_t compared = 0;
  for (const auto& from : all)
    for (const std::size_t limit : {std::size_t{1}, middle, all.size()}) {
      std::vector<Neighbour> scan;
      for (const auto& e : all)
        if (e.name != from.name) scan.push_back(distance_between(from, e, weber));
      std::sort(scan.begin(), scan.end(), [](const auto& a, const auto& b) {
        return a.distance != b.distance ? a.distance < b.distance : a.entry.name < b.entry.name;
      });
      if (scan.size() > limit) scan.resize(limit);
      const auto got = nearest(idx, from.name, limit);
      EXPECT_EQ(got.size(), scan.size()) << from.name << " limit " << limit;
      for (std::size_t i = 0; i < std::min(got.size(), scan.size()); ++i) {
        EXPECT_EQ(got[i].entry.name, scan[i].entry.name) << from.name << " #" << i << " limit " << limit;
        EXPECT_DOUBLE_EQ(got[i].distance, scan[i].distance);
      }
      ++compared;
    }
  return compared;
}

// near's R*Tree search gives exactly what comparing with every entry gives, on the shipped library.
TEST(LibraryNear, TheRTreeSearchEqualsAFullScanOnTheShippedLibrary) {
  const auto dir = std::filesystem::path(temp_dir("near-rtree"));
  const auto index = dir / "library.sqlite";
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  const auto lib = std::filesystem::path(SANDPAPER_SOURCE_DIR) / "library";
  ASSERT_TRUE(build_index({lib, {}, index, "sim"}, quiet).ok);
  const Index idx(index);
  EXPECT_GT(expect_search_equals_full_scan(idx, 7), 300u);
}

// Springs are apart in softness JNDs, dampers in viscosity JNDs, friction in slipperiness JNDs
// (each map's [jnd]: 23 %, 34 %, 11 %), not all in force JNDs; the untextured search by the `laws`
// R*Tree finds the same as comparing with every entry.
TEST(LibraryNear, ForceLawsAreApartInTheirOwnPerceptsJnds) {
  const auto dir = std::filesystem::path(temp_dir("near-laws"));
  const auto lib = dir / "library";
  std::filesystem::create_directories(lib / "laws");
  std::ofstream(lib / "library.toml") << "name = \"laws\"\nversion = \"1.0.0\"\n"
                                          "[families.laws]\ntitle = \"Laws\"\ndescribes = \"force laws\"\n";
  const auto entry = [&](const std::string& name, const std::string& body) {
    std::ofstream(lib / "laws" / (name + ".hmat")) << "material \"" << name << "\" {\n  family laws\n  licence \"CC0-1.0\"\n  "
                                                   << body << "\n}\n";
  };
  for (int k : {20, 40, 80, 160}) entry("spring" + std::to_string(k), "spring " + std::to_string(k) + " N/m");
  for (int b : {1, 2, 4}) entry("damper" + std::to_string(b), "damper " + std::to_string(b) + " N*s/m");
  entry("slide04", "physics Friction static 0.4 kinetic 0.4 press 1 N");
  entry("slide08", "physics Friction static 0.8 kinetic 0.8 press 1 N");
  const auto index = dir / "library.sqlite";
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  ASSERT_TRUE(build_index({lib, std::filesystem::path(SANDPAPER_SOURCE_DIR) / "calibration", index, "sim"}, quiet).ok) << sink.str();
  const Index idx(index);
  const auto w = idx.weber_fractions();
  EXPECT_DOUBLE_EQ(w.stiffness, 0.23);
  EXPECT_DOUBLE_EQ(w.damping, 0.34);
  EXPECT_DOUBLE_EQ(w.friction, 0.11);
  EXPECT_DOUBLE_EQ(w.force, 0.125);
  const auto springs = nearest(idx, "spring40", 3);
  ASSERT_EQ(springs.size(), 3u);
  EXPECT_EQ(springs[0].entry.name, "spring20");  // a doubling either way: ties by name
  EXPECT_NEAR(springs[0].distance, std::log(2.0) / std::log(1.23), 1e-9);  // 3.35 softness JNDs, not 5.9 force JNDs
  EXPECT_NEAR(springs[2].distance, std::log(4.0) / std::log(1.23), 1e-9);
  EXPECT_NE(springs[0].why.find("at 23 %"), std::string::npos) << springs[0].why;
  EXPECT_NEAR(nearest(idx, "damper1", 1)[0].distance, std::log(2.0) / std::log(1.34), 1e-9);
  // Friction: the static and the kinetic coefficient each a doubling, 2 x 6.6 slipperiness JNDs in
  // quadrature (9.4): farther than the 8 that other terms count, so slide08 comes after them.
  double slide08 = -1;
  for (const auto& n : nearest(idx, "slide04", 10))
    if (n.entry.name == "slide08") slide08 = n.distance;
  EXPECT_NEAR(slide08, std::hypot(1.0, 1.0) * std::log(2.0) / std::log(1.11), 1e-9);
  expect_search_equals_full_scan(idx, 3);
  std::filesystem::remove_all(dir);
}

// Two gratings of one force (1.5 N) a period doubling apart: 0 force JNDs, so the why says the force
// is the same, not "0 JND stronger", and the distance is the period's alone (4 JND a doubling).
TEST(LibraryNear, EqualForcesAreTheSameForceNotZeroJndStronger) {
  IndexedEntry a, b;
  a.name = "a", b.name = "b";
  a.texture_kind = b.texture_kind = "grating";
  a.max_lateral_force_N = b.max_lateral_force_N = 1.5;
  a.period_m = 0.002, b.period_m = 0.004;
  const auto n = distance_between(a, b, WeberFractions(0.125));
  EXPECT_EQ(n.force_steps, 0.0);
  EXPECT_DOUBLE_EQ(n.distance, kJndPerPeriodDoubling);
  EXPECT_EQ(n.why.find("0 JND"), std::string::npos) << n.why;
  EXPECT_NE(n.why.find("same force (1.5 N)"), std::string::npos) << n.why;
  // One JND apart (1.5 N x 1.125) still reads as a difference.
  b.max_lateral_force_N = 1.5 * 1.125;
  EXPECT_NE(distance_between(a, b, WeberFractions(0.125)).why.find("1 JND stronger (1.69 vs 1.5 N)"), std::string::npos)
      << distance_between(a, b, WeberFractions(0.125)).why;
}

TEST(LibraryNear, NearestByForceJndsPeriodAndKind) {
  const auto b = built("index-near");
  const Index idx(b.index);
  const auto ns = nearest(idx, "ribbed-cloth", 10);
  ASSERT_EQ(ns.size(), 4u);
  // reference-grating: roughness 0.5 vs 0.45 and 2.5 vs 3.2 mm is closer than fine-rib (0.2, 1.2 mm).
  EXPECT_EQ(ns[0].entry.name, "reference-grating");
  EXPECT_EQ(ns.back().entry.name, "fine-rib");
  for (std::size_t i = 1; i < ns.size(); ++i) EXPECT_LE(ns[i - 1].distance, ns[i].distance);
  const auto from = *idx.entry("ribbed-cloth");
  const auto to = *idx.entry("reference-grating");
  const double steps = std::log(to.max_lateral_force_N / from.max_lateral_force_N) / std::log(1.125);
  EXPECT_NEAR(ns[0].force_steps, steps, 1e-9);
  EXPECT_NEAR(ns[0].period_doublings, std::log2(2.5 / 3.2), 1e-9);
  EXPECT_NEAR(ns[0].distance, std::hypot(steps, kJndPerPeriodDoubling * std::log2(2.5 / 3.2)), 1e-9);
  EXPECT_NE(ns[0].why.find("same kind (grating)"), std::string::npos) << ns[0].why;
  // Symmetric in size.
  EXPECT_NEAR(distance_between(to, from, 0.125).distance, ns[0].distance, 1e-9);
  // --family: only that family's entries, nearest first, though reference-grating is nearer.
  const auto textiles = nearest(idx, "ribbed-cloth", 10, "textiles");
  ASSERT_EQ(textiles.size(), 1u);
  EXPECT_EQ(textiles[0].entry.name, "fine-rib");
  const auto abrasives = nearest(idx, "ribbed-cloth", 1, "abrasives");
  ASSERT_EQ(abrasives.size(), 1u);
  EXPECT_EQ(abrasives[0].entry.family, "abrasives");
  EXPECT_TRUE(nearest(idx, "ribbed-cloth", 10, "no-such-family").empty());
}

TEST(LibraryNear, SpatialScaleOfAHeightFieldIsTheSinusoidsPeriodAndScalesWithTheImage) {
  // A sampled sinusoid's heights, h = A sin(2 pi x / P) (any amplitude and offset): the scale is its period.
  for (const double period : {1e-3, 4e-3}) {
    compiler::RecoveredHeightField t;
    t.nx = 256, t.ny = 8;
    t.spacing_m[0] = period / 32, t.spacing_m[1] = 1e-3;
    for (int y = 0; y < t.ny; ++y)
      for (int x = 0; x < t.nx; ++x) t.h_m.push_back(2e-3 + 0.7e-3 * std::sin(2 * std::numbers::pi * x * t.spacing_m[0] / period));
    // Eight whole periods: the sample autocorrelation's first zero lies within a few % of P / 4.
    EXPECT_NEAR(spatial_scale_m(t), period, 0.03 * period);
  }
  // The same photograph laid over 40 mm and over 80 mm: the same kind and force, a scale twice as
  // large, one doubling apart in `near`, and it says so.
  const auto root = std::filesystem::path(temp_dir("near-scale"));
  std::filesystem::create_directories(root / "lib" / "images");
  std::filesystem::copy_file(SANDPAPER_SOURCE_DIR "/library/images/gravel.png", root / "lib" / "images" / "gravel.png");
  for (const auto& [name, mm] : {std::pair<std::string, int>{"small", 40}, {"large", 80}}) {
    std::ofstream f(root / "lib" / (name + ".hmat"));
    // The smoothing scaled with the image: the large one is the small one magnified, nothing else.
    f << "material \"" << name << "\" {\n  heightmap \"images/gravel.png\" size " << mm << " mm smoothing "
      << mm / 100.0 << " mm\n  roughness 0.5\n}\n";
  }
  const auto r = build(root / "lib", root / "idx.sqlite");
  ASSERT_TRUE(r.ok) << r.error << compiler::format_diagnostics(r.diagnostics);
  const Index idx(root / "idx.sqlite");
  const auto small = *idx.entry("small"), large = *idx.entry("large");
  EXPECT_EQ(small.texture_kind, "image");
  ASSERT_GT(small.period_m, 0);
  EXPECT_NEAR(large.period_m / small.period_m, 2.0, 0.05);
  const auto n = distance_between(small, large, 0.125);
  EXPECT_NEAR(n.period_doublings, 1.0, 0.04);
  EXPECT_NE(n.why.find("spatial scale"), std::string::npos) << n.why;
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace sandpaper::test
