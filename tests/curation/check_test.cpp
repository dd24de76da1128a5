// `library check` on copies of data/mini/ with one thing broken each: the Done-when of issue 6
// (a missing source, a duplicate alias, a cycle, an entry that does not compile for a shipped
// device), and the other checks. Each asserts the code, where, and that the help says how to fix it.
#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "curation_test_support.hpp"
#include "sandpaper/curation/check.hpp"
#include "sandpaper/curation/index.hpp"

namespace sandpaper::test {
namespace {

using curation::CheckResult;

CheckResult check(const std::filesystem::path& lib, const std::filesystem::path& cal = {}) {
  std::ostringstream sink;
  curation::Progress quiet("checking", 0, true, sink, false);
  return curation::check_library({lib, cal, {}, {}, {}}, quiet);
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The one diagnostic of `code`, with its location ending in `where` ("textiles/x.hmat:6:3").
const compiler::Diagnostic& only(const CheckResult& r, const std::string& code, const std::string& where) {
  auto ds = with_code(r.diagnostics, code);
  EXPECT_EQ(ds.size(), 1u) << compiler::format_diagnostics(r.diagnostics);
  static const compiler::Diagnostic none;
  if (ds.empty()) return none;
  EXPECT_TRUE(ends_with(ds[0]->location.str(), where)) << ds[0]->location.str() << " vs " << where;
  return *ds[0];
}

TEST(LibraryCheck, TheMiniLibraryPassesOnEveryShippedDevice) {
  const auto lib = mini_library_copy("check-clean");
  const auto r = check(lib);
  EXPECT_EQ(r.errors(), 0u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.warnings(), 0u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.entries, 5u);
  EXPECT_EQ(r.devices.size(), 7u);
  // The three gratings' W0350 (on each device where it holds: 2 on sim, 3 on sandpaper-1995's 900 Hz,
  // 2 on each OpenFFBoard file, joystick and wheel, at 1000 Hz, and 2 on each 3-DOF file, sim3d, the
  // Falcon and the Inverse3) are accepted in their files.
  EXPECT_EQ(r.accepted.all().size(), 15u) << compiler::format_diagnostics(r.accepted);
  EXPECT_EQ(r.summary(), "checked 5 entries on 7 devices (uncalibrated, W0331: haply-inverse3, novint-falcon, openffboard-2axis, "
                         "openffboard-wheel): 0 errors, 0 warnings, 15 accepted");
}

// Every warning the compiler gives an entry, on every device, as explain gives it: W0350 (a fine
// grating felt weaker at 100 mm/s) once per device with its own numbers.
TEST(LibraryCheck, ShowsEveryWarningTheCompilerGivesAnEntryOnEveryDevice) {
  const auto lib = mini_library_copy("check-warnings");
  edit(lib / "textiles/fine-rib.hmat",
       "  accept W0350 \"test data: a 1.2 mm grating read at the servo rate loses force at 100 mm/s, as W0350 says; kept to test "
       "what depends on it\"\n",
       "");
  const auto r = check(lib);
  const auto ws = with_code(r.diagnostics, "W0350");
  ASSERT_EQ(ws.size(), 7u) << compiler::format_diagnostics(r.diagnostics);
  std::set<std::string> devices;
  for (const auto* w : ws) {
    EXPECT_TRUE(ends_with(w->location.str(), "textiles/fine-rib.hmat:6:3")) << w->location.str();
    for (const char* d : {"sim", "sandpaper-1995", "openffboard-2axis", "openffboard-wheel", "sim3d", "novint-falcon", "haply-inverse3"})
      if (w->message.find(std::string("servo on ") + d + " reads") != std::string::npos) devices.insert(d);
  }
  EXPECT_EQ(devices.size(), 7u);
  EXPECT_EQ(r.warnings(), 7u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.accepted.all().size(), 8u);
}

// `accept` with nothing to accept warns (W0614) where it stands; accepting an error or an unknown code is E0220.
TEST(LibraryCheck, AnAcceptWithNothingToAcceptWarnsAndOnlyWarningsCanBeAccepted) {
  auto lib = mini_library_copy("check-accept");
  edit(lib / "textiles/ribbed-cloth.hmat", "  licence \"CC0-1.0\"\n", "  licence \"CC0-1.0\"\n  accept W0304 \"no image here\"\n");
  auto r = check(lib);
  const auto& w = only(r, "W0614", "textiles/ribbed-cloth.hmat:6:10");
  EXPECT_NE(w.message.find("'ribbed-cloth' accepts W0304, but neither a device's compile nor `library check` gives it that warning"), std::string::npos) << w.message;
  EXPECT_EQ(r.errors(), 0u) << compiler::format_diagnostics(r.diagnostics);

  edit(lib / "textiles/ribbed-cloth.hmat", "accept W0304", "accept E0304");
  r = check(lib);
  EXPECT_FALSE(with_code(r.diagnostics, "E0220").empty()) << compiler::format_diagnostics(r.diagnostics);
  edit(lib / "textiles/ribbed-cloth.hmat", "accept E0304", "accept W0305x");
  r = check(lib);
  const auto e = with_code(r.diagnostics, "E0220");
  ASSERT_FALSE(e.empty()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NE(e[0]->suggestion.find("did you mean W0305?"), std::string::npos) << e[0]->suggestion;
}

TEST(LibraryCheck, AMissingSourceIsAnErrorAtTheStatement) {
  const auto lib = mini_library_copy("check-source");
  edit(lib / "textiles/ribbed-cloth.hmat", "  source derived \"8 ribs per inch: 25.4 mm / 8\"\n", "");
  const auto r = check(lib);
  const auto& d = only(r, "E0606", "textiles/ribbed-cloth.hmat:6:3");
  EXPECT_EQ(d.severity, compiler::Severity::Error);
  EXPECT_NE(d.message.find("`grating` carries numbers but has no `source`"), std::string::npos) << d.message;
  EXPECT_NE(d.suggestion.find("add a line after it: source KIND"), std::string::npos) << d.suggestion;
  const auto text = compiler::format_diagnostic(d);
  EXPECT_NE(text.find("error[E0606]"), std::string::npos);
  EXPECT_NE(text.find("  grating period 3.2 mm hill 60%\n"), std::string::npos) << text;  // the line, then a caret
  EXPECT_NE(text.find("^~~~~~~"), std::string::npos) << text;
  EXPECT_EQ(r.errors(), 1u) << compiler::format_diagnostics(r.diagnostics);
}

TEST(LibraryCheck, ADuplicateAliasNamesBothPlaces) {
  const auto lib = mini_library_copy("check-alias");
  edit(lib / "abrasives/coarse-grit.hmat", "  alias grit-80\n", "  alias grit-80\n  alias rib-cloth\n");
  const auto r = check(lib);
  // Entries are checked in name order: coarse-grit claims the alias first, ribbed-cloth's is the clash.
  const auto& d = only(r, "E0607", "textiles/ribbed-cloth.hmat:4:9");
  EXPECT_NE(d.message.find("alias 'rib-cloth' is already an alias of 'coarse-grit'"), std::string::npos) << d.message;
  EXPECT_NE(d.suggestion.find("remove this alias, or say one that is free ('rib-cloth-2' is)"), std::string::npos) << d.suggestion;
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_TRUE(ends_with(d.notes[0].location.str(), "abrasives/coarse-grit.hmat:5:9")) << d.notes[0].location.str();
  EXPECT_EQ(r.errors(), 1u) << compiler::format_diagnostics(r.diagnostics);
}

TEST(LibraryCheck, AnAliasThatIsAnotherEntrysNameIsADuplicate) {
  const auto lib = mini_library_copy("check-alias-name");
  edit(lib / "abrasives/coarse-grit.hmat", "  alias grit-80\n", "  alias grit-80\n  alias fine-rib\n");
  const auto r = check(lib);
  const auto& d = only(r, "E0607", "abrasives/coarse-grit.hmat:5:9");
  EXPECT_NE(d.message.find("is already the name of textiles/fine-rib.hmat"), std::string::npos) << d.message;
}

// A new file that takes a name already in the library: the error is the newcomer's (the file the
// library's index does not have), though it comes first in path order, and the help names a free name.
TEST(LibraryCheck, ANameClashIsBlamedOnTheFileTheIndexDoesNotHave) {
  const auto lib = mini_library_copy("check-clash");
  std::ostringstream sink;
  curation::Progress quiet("indexing", 0, true, sink, false);
  ASSERT_TRUE(curation::build_index({lib, {}, {}, "sim"}, quiet).ok);
  std::string text = read(lib / "textiles/fine-rib.hmat");
  write(lib / "abrasives/fine-rib.hmat", text);
  // A `fine-rib-2` already taken as an alias: the suggestion skips it.
  edit(lib / "abrasives/coarse-grit.hmat", "  alias grit-80\n", "  alias grit-80\n  alias fine-rib-2\n");
  auto r = check(lib);
  const auto& d = only(r, "E0607", "abrasives/fine-rib.hmat:1:10");
  EXPECT_NE(d.message.find("name 'fine-rib' is already the name of textiles/fine-rib.hmat (in the library's index)"), std::string::npos)
      << d.message;
  EXPECT_NE(d.suggestion.find("for instance abrasives/fine-rib-3.hmat with material \"fine-rib-3\""), std::string::npos) << d.suggestion;
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_TRUE(ends_with(d.notes[0].location.str(), "textiles/fine-rib.hmat:1:10")) << d.notes[0].location.str();

  // Without an index, the later file in path order is the one blamed.
  std::filesystem::remove_all(lib / ".index");
  r = check(lib);
  (void)only(r, "E0607", "textiles/fine-rib.hmat:1:10");
}

// A file whose material names another entry: the help does not suggest renaming the file to that name.
TEST(LibraryCheck, AMaterialNamedLikeAnotherEntryIsNotToldToTakeItsFileName) {
  const auto lib = mini_library_copy("check-e0602");
  write(lib / "textiles/fine-rib-offcut.hmat", read(lib / "textiles/fine-rib.hmat"));
  const auto r = check(lib);
  const auto& d = only(r, "E0602", "textiles/fine-rib-offcut.hmat:1:10");
  EXPECT_NE(d.suggestion.find("write material \"fine-rib-offcut\""), std::string::npos) << d.suggestion;
  EXPECT_EQ(d.suggestion.find("rename the file to fine-rib.hmat"), std::string::npos) << d.suggestion;
}

TEST(LibraryCheck, ALikeCycleIsReportedOnceWithItsWholePathThroughAliases) {
  const auto lib = mini_library_copy("check-cycle");
  edit(lib / "textiles/ribbed-cloth.hmat", "  licence \"CC0-1.0\"\n", "  licence \"CC0-1.0\"\n  like fine-rib\n");
  const auto r = check(lib);
  const auto& d = only(r, "E0608", "textiles/fine-rib.hmat:6:8");
  EXPECT_NE(d.message.find("`like` cycle: fine-rib -> ribbed-cloth (as 'rib-cloth') -> fine-rib"), std::string::npos) << d.message;
  EXPECT_NE(d.suggestion.find("remove one of the `like` lines"), std::string::npos) << d.suggestion;
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_TRUE(ends_with(d.notes[0].location.str(), "textiles/ribbed-cloth.hmat:6:8")) << d.notes[0].location.str();
  // The cycle is the cause: its members are not also reported as failing to compile.
  EXPECT_TRUE(with_code(r.diagnostics, "E0610").empty()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.errors(), 1u) << compiler::format_diagnostics(r.diagnostics);
}

TEST(LibraryCheck, AnEntryTheWeakestDeviceCannotPlayFailsWithTheCompilersReasonAsANote) {
  const auto lib = mini_library_copy("check-device");
  const auto cal = calibration_copy("check-device");
  // sandpaper-1995 limited to 2 N: coarse-grit's roughness 0.8 needs about 2.8 N (Figure 19's map).
  edit(cal / "devices/sandpaper-1995.toml", "max_continuous = \"10 N\"", "max_continuous = \"2 N\"");
  const auto r = check(lib, cal);
  // coarse-grit, and old-grit that starts from it; the others need under 2 N.
  const auto fails = with_code(r.diagnostics, "E0610");
  ASSERT_EQ(fails.size(), 2u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.errors(), 2u) << compiler::format_diagnostics(r.diagnostics);
  const auto& d = *fails[0];  // entries are checked by name: coarse-grit first
  EXPECT_TRUE(ends_with(d.location.str(), "abrasives/coarse-grit.hmat:1:10")) << d.location.str();
  EXPECT_NE(d.message.find("'coarse-grit' does not compile for device 'sandpaper-1995'"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("calibration/devices/sandpaper-1995.toml"), std::string::npos) << d.message;
  ASSERT_FALSE(d.notes.empty());
  EXPECT_NE(d.notes[0].message.find("error[E0310]"), std::string::npos) << d.notes[0].message;
  EXPECT_TRUE(ends_with(d.notes[0].location.str(), "abrasives/coarse-grit.hmat:9:13")) << d.notes[0].location.str();
  EXPECT_NE(d.suggestion.find("every entry must play on every shipped device"), std::string::npos) << d.suggestion;
  EXPECT_NE(d.suggestion.find("roughness"), std::string::npos) << d.suggestion;  // E0310's own help: the highest it reaches
  EXPECT_NE(fails[1]->message.find("'old-grit' does not compile for device 'sandpaper-1995'"), std::string::npos);
}

TEST(LibraryCheck, MetadataProblemsEachSayWhatToWrite) {
  const auto lib = mini_library_copy("check-meta");
  edit(lib / "textiles/fine-rib.hmat", "  family textiles\n", "  family textile\n");
  edit(lib / "textiles/ribbed-cloth.hmat", "  licence \"CC0-1.0\"\n", "");
  edit(lib / "abrasives/coarse-grit.hmat", "  describes \"coarse sandpaper, sharp grains\"\n", "");
  edit(lib / "abrasives/old-grit.hmat", "material \"old-grit\"", "material \"older-grit\"");
  const auto r = check(lib);
  const auto& fam = only(r, "E0604", "textiles/fine-rib.hmat:3:10");
  EXPECT_NE(fam.suggestion.find("did you mean `textiles`?"), std::string::npos) << fam.suggestion;
  const auto& lic = only(r, "E0605", "textiles/ribbed-cloth.hmat:1:10");
  EXPECT_NE(lic.suggestion.find("add licence \"CC0-1.0\""), std::string::npos) << lic.suggestion;
  const auto& desc = only(r, "E0603", "abrasives/coarse-grit.hmat:1:10");
  EXPECT_NE(desc.suggestion.find("add describes"), std::string::npos);
  const auto& name = only(r, "E0602", "abrasives/old-grit.hmat:1:10");
  EXPECT_NE(name.message.find("material 'older-grit' is in a file named 'old-grit.hmat'"), std::string::npos) << name.message;
}

TEST(LibraryCheck, LicencesMustBeSpdxAndUnknownOnesWarn) {
  const auto lib = mini_library_copy("check-licence");
  edit(lib / "textiles/fine-rib.hmat", "licence \"CC0-1.0\"", "licence \"CC-BY-4\"");
  edit(lib / "textiles/ribbed-cloth.hmat", "licence \"CC0-1.0\"", "licence \"public domain!\"");
  const auto r = check(lib);
  // The warning points at the id, inside the quotes; the error at where the expression stops parsing.
  const auto& w = only(r, "W0603", "textiles/fine-rib.hmat:4:12");
  EXPECT_EQ(w.severity, compiler::Severity::Warning);
  EXPECT_NE(w.suggestion.find("did you mean \"CC-BY-4.0\"?"), std::string::npos) << w.suggestion;
  const auto& e = only(r, "E0605", "textiles/ribbed-cloth.hmat:5:19");
  EXPECT_NE(e.message.find("expected AND, OR or WITH here"), std::string::npos) << e.message;
  EXPECT_TRUE(curation::known_licence("LicenseRef-museum-scan"));
  EXPECT_TRUE(curation::well_formed_licence("MIT OR Apache-2.0"));
  EXPECT_FALSE(curation::well_formed_licence(""));
}

// SPDX 2.3 Annex D: AND, OR, WITH, '+' and parentheses; the operators are case-sensitive.
TEST(LibraryCheck, LicenceExpressionsParseAsSpdxSaysAndAVersionLeftOffIsGuessed) {
  for (const char* ok : {"CC-BY-SA-4.0 AND CC0-1.0", "(MIT OR Apache-2.0) AND CC-BY-4.0", "GPL-2.0+ WITH Classpath-exception-2.0",
                         "DocumentRef-scan:LicenseRef-museum", " CC0-1.0 "}) {
    const auto ex = curation::parse_licence_expression(ok);
    EXPECT_TRUE(ex.ok()) << ok << ": " << ex.error;
  }
  const auto two = curation::parse_licence_expression("CC-BY-SA-4.0 AND CC0-1.0");
  EXPECT_EQ(two.ids, (std::vector<std::string>{"CC-BY-SA-4.0", "CC0-1.0"}));
  for (const char* bad : {"", "MIT and CC0-1.0", "(MIT OR CC0-1.0", "MIT OR", "AND MIT", "MIT )", "MIT, CC0-1.0"})
    EXPECT_FALSE(curation::parse_licence_expression(bad).ok()) << bad;
  EXPECT_EQ(curation::parse_licence_expression("(MIT OR CC0-1.0").error_at, 15u);
  EXPECT_EQ(curation::licence_guess("CC0"), "CC0-1.0");
  EXPECT_EQ(curation::licence_guess("CC-BY-SA"), "CC-BY-SA-4.0");

  const auto lib = mini_library_copy("check-licence-expr");
  edit(lib / "textiles/fine-rib.hmat", "licence \"CC0-1.0\"", "licence \"CC-BY-SA-4.0 AND CC0-1.0\"");
  edit(lib / "textiles/ribbed-cloth.hmat", "licence \"CC0-1.0\"", "licence \"CC0\"");
  const auto r = check(lib);
  const auto& w = only(r, "W0603", "textiles/ribbed-cloth.hmat:5:12");
  EXPECT_NE(w.suggestion.find("did you mean \"CC0-1.0\"?"), std::string::npos) << w.suggestion;
  EXPECT_EQ(r.errors(), 0u) << compiler::format_diagnostics(r.diagnostics);
}

// Every image an entry uses carries its own licence and credit in a REUSE sidecar (E0615), whose
// licence is checked as an entry's is.
TEST(LibraryCheck, AnImageWithoutItsLicenceAndCreditIsAnError) {
  const auto lib = mini_library_copy("check-image-licence");
  std::filesystem::create_directories(lib / "images");
  std::filesystem::copy_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "library/images/gravel.png", lib / "images/gravel.png");
  write(lib / "abrasives/gravel-grit.hmat",
        "material \"gravel-grit\" {\n  describes \"grit\"\n  family abrasives\n  licence \"CC0-1.0\"\n"
        "  heightmap \"../images/gravel.png\" size 6 mm\n  source by-ear \"x\"\n  roughness 0.6\n  source by-ear \"x\"\n"
        "  accept W0304 \"a photograph\"\n}\n");
  auto r = check(lib);
  const auto& none = only(r, "E0615", "abrasives/gravel-grit.hmat:5:13");
  EXPECT_NE(none.message.find("has no licence: there is no"), std::string::npos) << none.message;
  EXPECT_NE(none.suggestion.find("SPDX-License-Identifier: CC0-1.0"), std::string::npos) << none.suggestion;

  write(lib / "images/gravel.png.license", "SPDX-License-Identifier: CC0\n");
  r = check(lib);
  const auto& credit = only(r, "E0615", "images/gravel.png.license:1:1");
  EXPECT_NE(credit.message.find("no SPDX-FileCopyrightText"), std::string::npos) << credit.message;
  // The image's path in quotes, then words: not '../images/gravel.png''s.
  EXPECT_NE(credit.message.find("the licence file of image '../images/gravel.png' has no SPDX-FileCopyrightText"), std::string::npos)
      << credit.message;
  EXPECT_EQ(credit.message.find("''s"), std::string::npos) << credit.message;
  const auto& guess = only(r, "W0603", "images/gravel.png.license:1:26");
  EXPECT_NE(guess.suggestion.find("did you mean \"CC0-1.0\"?"), std::string::npos) << guess.suggestion;

  write(lib / "images/gravel.png.license", "SPDX-FileCopyrightText: scikit-image sample data\nSPDX-License-Identifier: CC0-1.0\n");
  r = check(lib);
  EXPECT_TRUE(with_code(r.diagnostics, "E0615").empty()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_TRUE(with_code(r.diagnostics, "W0603").empty()) << compiler::format_diagnostics(r.diagnostics);
}

// An image named inside the library that is a link leading out (E0612) needs its licence file beside
// the link all the same: both are said in one round, so a curator does not fix one to meet the other.
TEST(LibraryCheck, AnImageLinkLeadingOutIsToldItsMissingLicenceInTheSameRound) {
  const auto lib = mini_library_copy("check-image-link");
  const auto outside = lib.parent_path() / (lib.filename().string() + "-outside");
  std::filesystem::create_directories(outside);
  std::filesystem::create_directories(lib / "images");
  std::filesystem::copy_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "library/images/gravel.png", outside / "gravel.png",
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::create_symlink(outside / "gravel.png", lib / "images/gravel.png");
  write(lib / "abrasives/gravel-grit.hmat",
        "material \"gravel-grit\" {\n  describes \"grit\"\n  family abrasives\n  licence \"CC0-1.0\"\n"
        "  heightmap \"../images/gravel.png\" size 6 mm\n  source by-ear \"x\"\n  roughness 0.6\n  source by-ear \"x\"\n"
        "  accept W0304 \"a photograph\"\n}\n");
  auto r = check(lib);
  const auto& link = only(r, "E0612", "abrasives/gravel-grit.hmat:5:13");
  EXPECT_NE(link.message.find("symbolic link"), std::string::npos) << link.message;
  const auto& none = only(r, "E0615", "abrasives/gravel-grit.hmat:5:13");
  EXPECT_NE(none.message.find("image '../images/gravel.png' has no licence"), std::string::npos) << none.message;
  // With the licence file beside the link, only the link is left to fix.
  write(lib / "images/gravel.png.license", "SPDX-FileCopyrightText: scikit-image sample data\nSPDX-License-Identifier: CC0-1.0\n");
  r = check(lib);
  EXPECT_TRUE(with_code(r.diagnostics, "E0615").empty()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(with_code(r.diagnostics, "E0612").size(), 1u) << compiler::format_diagnostics(r.diagnostics);
  std::filesystem::remove_all(outside);
}

// check_library counts the entries it goes through, so a caller's counter that did not know the
// total (review's) reads 5/5 on the five-entry mini library, not 5/0.
TEST(LibraryCheck, TheProgressCounterCountsToTheNumberOfEntries) {
  const auto lib = mini_library_copy("check-progress");
  std::ostringstream out;
  curation::Progress counter("checking", 0, false, out, false, 1);
  (void)curation::check_library({lib, {}, {}, {}, {}}, counter);
  EXPECT_NE(out.str().find("checking 5/5\n"), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find("/0\n"), std::string::npos) << out.str();
}

TEST(LibraryCheck, DeprecationMustPointAtALiveEntry) {
  const auto lib = mini_library_copy("check-deprecated");
  edit(lib / "abrasives/old-grit.hmat", "replaced-by coarse-grit", "replaced-by coarse-grid");
  const auto r = check(lib);
  const auto& d = only(r, "E0609", "abrasives/old-grit.hmat:5:26");
  EXPECT_NE(d.suggestion.find("did you mean `coarse-grit`?"), std::string::npos) << d.suggestion;

  const auto lib2 = mini_library_copy("check-deprecated-chain");
  edit(lib2 / "abrasives/coarse-grit.hmat", "  licence \"CC-BY-4.0\"\n", "  licence \"CC-BY-4.0\"\n  deprecated replaced-by fine-rib\n");
  const auto r2 = check(lib2);
  const auto& chain = only(r2, "E0609", "abrasives/old-grit.hmat:5:26");
  EXPECT_NE(chain.message.find("is itself deprecated"), std::string::npos) << chain.message;
  EXPECT_NE(chain.suggestion.find("deprecated replaced-by fine-rib"), std::string::npos) << chain.suggestion;
}

TEST(LibraryCheck, EntriesOfOneFamilyWithinAForceJndAndOnePeriodClassWarn) {
  const auto lib = mini_library_copy("check-jnd");
  const std::string twin = R"(material "ribbed-twin" {
  describes "another ribbed cloth"
  family textiles
  licence "CC0-1.0"
  grating period 3 mm hill 60%
  source by-ear "a little finer"
  roughness ROUGH
  source by-ear "as rough as the ribbed cloth"
}
)";
  auto with = [&](const std::string& r) {
    auto t = twin;
    t.replace(t.find("ROUGH"), 5, r);
    return t;
  };
  write(lib / "textiles/ribbed-twin.hmat", with("0.46"));
  auto r = check(lib);
  const auto& w = only(r, "W0601", "textiles/ribbed-twin.hmat:1:10");
  EXPECT_NE(w.message.find("'ribbed-twin' may feel the same as 'ribbed-cloth' (family textiles)"), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("period class 'transitional'"), std::string::npos) << w.message;  // 3.0 and 3.2 mm: 1.73-3.54 mm
  EXPECT_EQ(r.errors(), 0u);
  // Three force JNDs apart (roughness 0.6 vs 0.45: force x1.46): no warning.
  write(lib / "textiles/ribbed-twin.hmat", with("0.6"));
  EXPECT_TRUE(with_code(check(lib).diagnostics, "W0601").empty());
}

TEST(LibraryCheck, ADenseFamilyWarnsOncePerEntryNamingItsNearestLookAlike) {
  // Five more ribbed cloths within one force JND of ribbed-cloth and of each other: 15 pairs, but
  // one warning an entry (the later of each pair in name order), its nearest partner first.
  const auto lib = mini_library_copy("check-jnd-dense");
  const char* roughness[] = {"0.44", "0.45", "0.451", "0.452", "0.453"};
  for (int k = 0; k < 5; ++k)
    write(lib / ("textiles/ribbed-twin" + std::to_string(k) + ".hmat"),
          "material \"ribbed-twin" + std::to_string(k) + "\" {\n  describes \"another ribbed cloth\"\n  family textiles\n"
          "  licence \"CC0-1.0\"\n  grating period 3 mm hill 60%\n  source by-ear \"a little finer\"\n  roughness " +
              std::string(roughness[k]) + "\n  source by-ear \"as rough as the ribbed cloth\"\n}\n");
  const auto r = check(lib);
  const auto w = with_code(r.diagnostics, "W0601");
  ASSERT_EQ(w.size(), 5u);  // ribbed-twin0..4 each after ribbed-cloth, or after the twins before them
  std::size_t with_more = 0;
  for (const auto* d : w) {
    EXPECT_LE(d->notes.size(), 4u);
    with_more += d->message.find(" more entr") != std::string::npos ? 1u : 0u;
  }
  EXPECT_GE(with_more, 4u);  // every twin has a look-alike besides its nearest
  const auto last = std::find_if(w.begin(), w.end(), [](const auto* d) {
    return d->location.file && d->location.file->name.find("ribbed-twin4.hmat") != std::string::npos;
  });
  ASSERT_NE(last, w.end());
  EXPECT_NE((*last)->message.find("'ribbed-twin4' may feel the same as 'ribbed-twin3'"), std::string::npos) << (*last)->message;
  EXPECT_NE((*last)->message.find("4 more entries of the family, earlier in name order, are also within one force JND"),
            std::string::npos)
      << (*last)->message;
  EXPECT_EQ((*last)->notes.size(), 4u);  // the nearest and three more
}

TEST(LibraryCheck, SyntaxErrorsAreReportedWithTheCompilersCodes) {
  const auto lib = mini_library_copy("check-syntax");
  edit(lib / "textiles/fine-rib.hmat", "grating period 1.2 mm", "grating period 1.2");
  const auto r = check(lib);
  EXPECT_EQ(with_code(r.diagnostics, "E0203").size(), 1u) << compiler::format_diagnostics(r.diagnostics);
}

// A lab's library on top of the mini library ("world"): the lab's root is checked against the world's.
TEST(LibraryCheck, ALayeredPathChecksEachRootAgainstTheRootsBelowIt) {
  const auto world = mini_library_copy("check-layers");
  edit(world / "library.toml", "name = \"curation test library\"", "id = \"world\"\nname = \"curation test library\"");
  const auto lab = world.parent_path() / "lab";
  write(lab / "library.toml", "id = \"lab\"\nname = \"lab\"\nversion = \"0.1.0\"\n");
  const std::string entry_head = "  family textiles\n  licence \"CC0-1.0\"\n";
  // Hides world:ribbed-cloth without saying so: W0612, with a note at the hidden entry.
  write(lab / "ribbed-cloth.hmat", "material \"ribbed-cloth\" {\n  describes \"our ribbed cloth\"\n" + entry_head +
                                        "  like world:ribbed-cloth\n  roughness 0.5\n  source by-ear \"ours is rougher\"\n}\n");
  // Says overrides and hides world:fine-rib: fine. Says overrides and hides nothing: W0613.
  write(lab / "fine-rib.hmat", "material \"fine-rib\" {\n  describes \"our fine rib\"\n" + entry_head +
                                    "  overrides\n  like world:fine-rib\n}\n");
  write(lab / "velvet.hmat", "material \"velvet\" {\n  describes \"velvet\"\n" + entry_head +
                                  "  overrides\n  like rib-cloth\n}\n");
  std::ostringstream sink;
  curation::Progress quiet("checking", 0, true, sink, false);
  curation::CheckOptions o;
  o.library_path = {lab, world};
  auto r = curation::check_library(o, quiet);
  EXPECT_EQ(r.errors(), 0u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.entries, 3u + 5u);  // the lab's three, then the world's five against nothing below
  const auto shadow = with_code(r.diagnostics, "W0612");
  ASSERT_EQ(shadow.size(), 1u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NE(shadow[0]->message.find("'lab:ribbed-cloth' hides 'world:ribbed-cloth'"), std::string::npos) << shadow[0]->message;
  EXPECT_TRUE(ends_with(shadow[0]->location.file->name, "lab/ribbed-cloth.hmat")) << shadow[0]->location.file->name;
  ASSERT_EQ(shadow[0]->notes.size(), 1u);
  EXPECT_TRUE(ends_with(shadow[0]->notes[0].location.file->name, "check-layers" + std::string() + "") ||
              shadow[0]->notes[0].location.file->name.find("textiles/ribbed-cloth.hmat") != std::string::npos)
      << shadow[0]->notes[0].location.file->name;
  EXPECT_NE(shadow[0]->suggestion.find("overrides"), std::string::npos);
  const auto nothing = with_code(r.diagnostics, "W0613");
  ASSERT_EQ(nothing.size(), 1u);
  EXPECT_TRUE(ends_with(nothing[0]->location.file->name, "lab/velvet.hmat"));
  EXPECT_EQ(nothing[0]->location.line, 5);

  // --root lab: only the lab's entries.
  o.root = "lab";
  r = curation::check_library(o, quiet);
  EXPECT_EQ(r.entries, 3u);
  o.root = "nowhere";
  EXPECT_THROW(curation::check_library(o, quiet), std::invalid_argument);

  // Without the world below, the lab does not compile (its `like world:...` names nothing).
  o.root.clear();
  o.library_path = {lab};
  r = curation::check_library(o, quiet);
  EXPECT_FALSE(with_code(r.diagnostics, "E0610").empty()) << compiler::format_diagnostics(r.diagnostics);

  // Two roots with one id: E0613.
  edit(lab / "library.toml", "id = \"lab\"", "id = \"world\"");
  o.library_path = {lab, world};
  r = curation::check_library(o, quiet);
  EXPECT_EQ(with_code(r.diagnostics, "E0613").size(), 1u);
}

}  // namespace
}  // namespace sandpaper::test
