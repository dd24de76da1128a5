// Golden files: the exact diagnostics for each tests/golden/workspace/*.hws. Regenerate with the
// update-golden target, then read the diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "sandpaper/compiler/workspace.hpp"
#include "test_support.hpp"
#include "workspace_test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;

TEST(GoldenWorkspaceDiagnostics, EveryCaseMatches) {
  std::vector<fs::path> cases;
  for (const auto& e : fs::directory_iterator("tests/golden/workspace"))
    if (e.path().extension() == ".hws") cases.push_back(e.path());
  std::sort(cases.begin(), cases.end());
  ASSERT_GE(cases.size(), 8u);
  for (const auto& in : cases) {
    SCOPED_TRACE(in.string());
    auto r = compiler::compile_workspace_file(test::shipped_compiler(), in);
    EXPECT_FALSE(r.diagnostics.all().empty()) << "a diagnostics case must produce diagnostics";
    auto expected = in;
    testws::check_golden(expected.replace_extension(".expected").string(), compiler::format_diagnostics(r.diagnostics));
  }
}

}  // namespace
}  // namespace sandpaper
