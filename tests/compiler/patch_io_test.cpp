// The patch-program file: round trip, determinism, integrity checks, atomic writes.
#include <filesystem>
#include <fstream>
#include <functional>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sandpaper/schema/patch_io.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {
schema::PatchProgram sample() {
  auto r = test::shipped_compiler().compile_text("like corduroy; spring 100 N/m; damper 1 N*s/m; roughness 0.05");
  EXPECT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  return *r.program;
}
}  // namespace

TEST(PatchIO, RoundTripKeepsEverything) {
  auto p = sample();
  auto q = schema::deserialize(schema::serialize(p));
  EXPECT_EQ(q.name, p.name);
  EXPECT_EQ(q.describes, p.describes);
  EXPECT_EQ(q.device, "sim");
  EXPECT_EQ(q.size_m[0], p.size_m[0]);
  EXPECT_EQ(q.max_lateral_force_N, p.max_lateral_force_N);
  EXPECT_EQ(q.roughness, p.roughness);
  ASSERT_EQ(q.terms.size(), 3u);
  EXPECT_EQ(std::get<schema::GratingTerm>(q.terms[0]).force_N, std::get<schema::GratingTerm>(p.terms[0]).force_N);
  EXPECT_EQ(std::get<schema::SpringTerm>(q.terms[1]).stiffness_N_per_m, 100);
  EXPECT_EQ(std::get<schema::DamperTerm>(q.terms[2]).damping_Ns_per_m, 1);
  ASSERT_EQ(q.provenance.size(), p.provenance.size());
  for (std::size_t i = 0; i < p.provenance.size(); ++i) {
    EXPECT_EQ(q.provenance[i].parameter, p.provenance[i].parameter);
    EXPECT_EQ(q.provenance[i].source, p.provenance[i].source);
  }
  ASSERT_EQ(q.warnings.size(), 1u);
  EXPECT_EQ(q.warnings[0].code, "W0301");
}

TEST(PatchIO, SameInputSameBytes) {
  for (const char* src : {"corduroy", "gravel", "sandpaper-80-grit"}) {
    auto a = test::shipped_compiler().compile_text(src);
    auto b = test::shipped_compiler().compile_text(src);
    ASSERT_TRUE(a.ok() && b.ok()) << src;
    EXPECT_EQ(schema::serialize(*a.program), schema::serialize(*b.program)) << src;
  }
  auto f1 = test::shipped_compiler().compile_file("examples/gravel.hmat");
  auto f2 = test::shipped_compiler().compile_file("examples/gravel.hmat");
  EXPECT_EQ(schema::serialize(*f1.program), schema::serialize(*f2.program));
}

TEST(PatchIO, DifferentInputDifferentBytes) {
  auto a = test::shipped_compiler().compile_text("grating period 2 mm; roughness 0.5");
  auto b = test::shipped_compiler().compile_text("grating period 2 mm; roughness 0.51");
  EXPECT_NE(schema::serialize(*a.program), schema::serialize(*b.program));
}

TEST(PatchIO, CorruptionIsDetected) {
  auto bytes = schema::serialize(sample());
  auto flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x01;
  EXPECT_THROW(schema::deserialize(flipped), schema::PatchFormatError);
  auto truncated = bytes;
  truncated.resize(bytes.size() - 1);
  EXPECT_THROW(schema::deserialize(truncated), schema::PatchFormatError);
  auto magic = bytes;
  magic[0] = 'X';
  EXPECT_THROW(schema::deserialize(magic), schema::PatchFormatError);
  auto version = bytes;
  version[8] = 99;
  EXPECT_THROW(schema::deserialize(version), schema::PatchFormatError);
  EXPECT_THROW(schema::deserialize({}), schema::PatchFormatError);
}

TEST(PatchIO, WritesAtomicallyAndLeavesNoTemporaryFiles) {
  auto dir = test::temp_dir("io");
  auto path = dir + "/m.patch";
  schema::write_patch_file(path, sample());
  EXPECT_TRUE(schema::looks_like_patch_file(path));
  EXPECT_EQ(schema::read_patch_file(path).name, sample().name);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  EXPECT_THROW(schema::write_patch_file(dir + "/no/such/dir/m.patch", sample()), std::runtime_error);
}

// F42: a compile wrote a picture's channel name, or a Latin-1 file name in a location, as raw bytes
// into the program, and the reader refused the file the compile had just written. The writer now
// writes every string as text, each byte that does not begin a whole UTF-8 character as U+FFFD (as
// JSON output does), so what it writes reads back.
TEST(PatchIO, TheWriterWritesEveryStringAsTextTheReaderTakes) {
  const auto p = sample();
  const std::vector<std::function<std::string&(schema::PatchProgram&)>> fields = {
      [](schema::PatchProgram& q) -> std::string& { return q.name; },
      [](schema::PatchProgram& q) -> std::string& { return q.describes; },
      [](schema::PatchProgram& q) -> std::string& { return q.provenance.at(0).source; },
      [](schema::PatchProgram& q) -> std::string& { return q.warnings.at(0).message; },
  };
  // A stray byte, an overlong '/', a surrogate, a character cut short.
  const std::vector<std::pair<std::string, std::string>> spoilt = {
      {"caf\xe9.hmat", "caf\uFFFD.hmat"},
      {"a\xc0\xaf" "b", "a\uFFFD\uFFFDb"},
      {"\xed\xa0\x80", "\uFFFD\uFFFD\uFFFD"},
      {"x\xe2\x82", "x\uFFFD\uFFFD"},
  };
  for (std::size_t i = 0; i < fields.size(); ++i) {
    auto q = p;
    fields[i](q) = spoilt[i].first;
    schema::PatchProgram back;
    ASSERT_NO_THROW(back = schema::deserialize(schema::serialize(q))) << i;
    EXPECT_EQ(fields[i](back), spoilt[i].second) << i;
  }
}
