// Golden files per compiler phase (tests/golden/stages/): for every shipped example and each tricky
// input, the tokens, the syntax, the resolved material and the patch program (its JSON), so a change
// in one phase shows in that phase's files. Regenerate with the update-golden target and review the diff.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/stage_dumps.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "golden_support.hpp"
#include "test_support.hpp"

using namespace sandpaper;
namespace fs = std::filesystem;

namespace {

using test::check_golden;
using test::read_bytes;

std::vector<fs::path> materials(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".hmat") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Writes (or checks) <out>/<stem>.tokens, .syntax, .resolved and .patch.json for `input`; a phase
// that reports errors gets <stem>.diagnostics and the phases after it are not dumped.
void check_stages(const fs::path& input, const fs::path& out) {
  SCOPED_TRACE(input.string());
  const std::string stem = input.stem().string();
  auto file = std::make_shared<const compiler::SourceFile>(input.string(), read_bytes(input));
  compiler::Diagnostics front;
  const auto tokens = compiler::lex(file, front);
  check_golden(out / (stem + ".tokens"), compiler::dump_tokens(tokens));
  const auto syntax = compiler::parse(tokens, file, front);
  check_golden(out / (stem + ".syntax"), compiler::dump_syntax(syntax));
  const auto r = test::shipped_compiler().compile_file(input);
  if (!r.ok()) {
    check_golden(out / (stem + ".diagnostics"), compiler::format_diagnostics(r.diagnostics));
    EXPECT_FALSE(fs::exists(out / (stem + ".resolved"))) << "a failed compile's resolved material has a golden file";
    return;
  }
  ASSERT_TRUE(r.material);
  check_golden(out / (stem + ".resolved"), compiler::dump_resolved(*r.material));
  check_golden(out / (stem + ".patch.json"), schema::to_json(*r.program).dump(2) + "\n");
}

}  // namespace

TEST(GoldenStages, EveryShippedExample) {
  std::vector<fs::path> inputs = materials("examples");
  for (const auto& p : materials("examples/laws")) inputs.push_back(p);
  ASSERT_GE(inputs.size(), 12u);
  for (const auto& in : inputs) check_stages(in, "tests/golden/stages/examples");
}

TEST(GoldenStages, EveryTrickyInput) {
  const auto inputs = materials("tests/golden/stages/tricky");
  ASSERT_GE(inputs.size(), 5u);
  for (const auto& in : inputs) check_stages(in, "tests/golden/stages/tricky");
}

// The dumps are of what each phase really made: the syntax of a file with a broken statement keeps
// the statements around it and drops that one, and a token's number is the value the lexer read.
TEST(GoldenStages, TheDumpsShowWhatEachPhaseMade) {
  auto file = std::make_shared<const compiler::SourceFile>("<t>", "spring 2.5e2 N/m\ngrating period hill 50%\ndamper 1 N*s/m\n");
  compiler::Diagnostics d;
  const auto tokens = compiler::lex(file, d);
  EXPECT_NE(compiler::dump_tokens(tokens).find("1:8 Number 2.5e2 [250]"), std::string::npos) << compiler::dump_tokens(tokens);
  const std::string syntax = compiler::dump_syntax(compiler::parse(tokens, file, d));
  EXPECT_TRUE(d.has_errors());
  EXPECT_EQ(syntax, "1:1 spring stiffness=250 N/m [250]\n3:1 damper damping=1 N*s/m [1]\n");
}
