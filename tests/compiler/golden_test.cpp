// Golden files: the exact diagnostics for each tests/golden/diagnostics/*.hmat, and the compiled
// summary (JSON) and explanation for each tests/golden/compile/*.hmat. Regenerate with
// `cmake --build --preset release --target update-golden`, then review the diff.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sandpaper/compiler/explain.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "golden_support.hpp"
#include "test_support.hpp"

using namespace sandpaper;
namespace fs = std::filesystem;

namespace {

using test::check_golden;

std::vector<fs::path> inputs(const char* dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".hmat") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(GoldenDiagnostics, EveryCaseMatches) {
  auto cases = inputs("tests/golden/diagnostics");
  ASSERT_GE(cases.size(), 10u);
  for (const auto& in : cases) {
    SCOPED_TRACE(in.string());
    auto r = test::shipped_compiler().compile_file(in);
    EXPECT_FALSE(r.diagnostics.all().empty()) << "a diagnostics case must produce diagnostics";
    auto expected = in;
    check_golden(expected.replace_extension(".expected"), compiler::format_diagnostics(r.diagnostics));
  }
}

TEST(GoldenCompile, EveryCaseMatches) {
  auto cases = inputs("tests/golden/compile");
  ASSERT_GE(cases.size(), 3u);
  for (const auto& in : cases) {
    SCOPED_TRACE(in.string());
    auto r = test::shipped_compiler().compile_file(in);
    ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
    auto json = in, text = in;
    check_golden(json.replace_extension(".json"), schema::to_json(*r.program).dump(2) + "\n");
    check_golden(text.replace_extension(".explain"),
                 compiler::explain_text(*r.material, *r.program, test::shipped_compiler().calibration(),
                                        test::shipped_compiler().device()));
  }
}
