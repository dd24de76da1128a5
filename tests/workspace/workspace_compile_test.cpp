// The workspace compiler: .hws text -> WorkspaceProgram, with diagnostics E05xx, the unit rules,
// materials compiled through the material compiler, and placement checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <set>
#include <stdexcept>

#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#include "sandpaper/schema/workspace_json.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;

compiler::WorkspaceResult compile(const std::string& text, const fs::path& base = ".") {
  return compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", base);
}

std::vector<std::string> codes(const compiler::Diagnostics& d, compiler::Severity s = compiler::Severity::Error) {
  std::vector<std::string> out;
  for (const auto& x : d.all())
    if (x.severity == s) out.push_back(x.code);
  return out;
}

TEST(WorkspaceCompile, TheExampleSamplerCompiles) {
  auto r = compiler::compile_workspace_file(test::shipped_compiler(), "examples/workspace/sampler.hws");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& ws = *r.program;
  EXPECT_EQ(ws.name, "thesis sampler");
  EXPECT_DOUBLE_EQ(ws.size_m[0], 228.6e-3);
  ASSERT_EQ(ws.patches.size(), 7u);
  // File order is painting order; positions and sizes in SI; the placed size replaces the material's.
  EXPECT_EQ(ws.patches[0].source, "silk-satin");
  EXPECT_DOUBLE_EQ(ws.patches[0].centre_m[0], -0.090);
  EXPECT_DOUBLE_EQ(ws.patches[0].centre_m[1], 0.0);
  EXPECT_DOUBLE_EQ(ws.patches[0].size_m[0], 0.032);
  EXPECT_DOUBLE_EQ(ws.patches[0].size_m[1], 0.060);
  for (const auto& p : ws.patches) {
    EXPECT_EQ(p.program->size_m[0], p.size_m[0]);
    EXPECT_EQ(p.program->size_m[1], p.size_m[1]);
  }
  EXPECT_EQ(ws.patches[3].program->name, "a19p100");
  EXPECT_EQ(ws.patches[6].source, "roughness 0.3; grating period 5 mm");
  EXPECT_DOUBLE_EQ(ws.patches[6].size_m[1], 0.020);  // `size 20 mm`: square
}

TEST(WorkspaceCompile, PatchesKeepWhatTheMaterialCompilerGives) {
  auto r = compile("workspace \"w\" {\n  patch \"a10p25\" at 10 mm, -20 mm size 30 mm x 40 mm\n}\n");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  auto direct = test::shipped_compiler().compile_text("a10p25");
  ASSERT_TRUE(direct.ok());
  const auto& placed = *r.program->patches.at(0).program;
  EXPECT_EQ(placed.name, direct.program->name);
  EXPECT_EQ(placed.max_lateral_force_N, direct.program->max_lateral_force_N);
  EXPECT_EQ(placed.terms.size(), direct.program->terms.size());
  // Table 8: A10 P25 is command 400 joystick units, 7.0 oz; within 2 % of 7 x 28.349523125 gf.
  EXPECT_NEAR(placed.max_lateral_force_N, 7.0 * 28.349523125e-3 * 9.80665, 0.02 * 1.946);
}

TEST(WorkspaceCompile, DefaultsAreTheThesisWorkspaceAndTheMaterialsOwnSize) {
  auto r = compile("workspace \"w\" { \n patch \"corduroy\" at 0 mm, 0 mm\n}");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_DOUBLE_EQ(r.program->size_m[0], 9 * 0.0254);  // Table 2: 9 in
  EXPECT_DOUBLE_EQ(r.program->size_m[1], 9 * 0.0254);
  auto direct = test::shipped_compiler().compile_text("corduroy");
  EXPECT_EQ(r.program->patches[0].size_m[0], direct.program->size_m[0]);
}

TEST(WorkspaceCompile, MaterialFilesAreRelativeToTheWorkspace) {
  const fs::path dir = test::temp_dir("ws-relative");
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / "ribs.hmat") << "grating period 4 mm amplitude 1 N\n";
  std::ofstream(dir / "w.hws") << "workspace \"w\" {\n  patch \"sub/ribs.hmat\" at 0 mm, 0 mm size 20 mm\n}\n";
  auto r = compiler::compile_workspace_file(test::shipped_compiler(), dir / "w.hws");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NEAR(r.program->patches[0].program->max_lateral_force_N, 1.0, 1e-9);
  EXPECT_EQ(r.program->patches[0].source, "sub/ribs.hmat");
}

TEST(WorkspaceCompile, MaterialErrorsCarryANoteAtThePatch) {
  auto r = compile("workspace \"w\" {\n  patch \"roughness 5; grating period 2 mm\" at 0 mm, 0 mm size 20 mm\n}\n");
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(r.program.has_value());
  ASSERT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0303"});
  const auto& d = r.diagnostics.all().front();
  ASSERT_FALSE(d.notes.empty());
  EXPECT_EQ(d.notes.back().location.str(), "<test.hws>:2:9");
  EXPECT_NE(d.notes.back().message.find("patch 1"), std::string::npos);
}

TEST(WorkspaceCompile, ASharedMaterialIsReportedOnceWithEveryPatch) {
  auto r = compile("workspace \"w\" {\n  patch \"unobtainium\" at 0 mm, 0 mm size 20 mm\n  patch \"unobtainium\" at 30 mm, 0 mm size 20 mm\n}\n");
  ASSERT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0301"});
  EXPECT_EQ(r.diagnostics.all().front().notes.size(), 2u);
}

TEST(WorkspaceCompile, UnitsAreRequired) {
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"corduroy\" at 0, 0 mm size 20 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0203"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"corduroy\" at 0 mm, 0 mm size 20 N\n}\n").diagnostics),
            std::vector<std::string>{"E0205"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  size 20 mn\n}\n").diagnostics), std::vector<std::string>{"E0204"});
}

TEST(WorkspaceCompile, SyntaxErrors) {
  EXPECT_EQ(codes(compile("patch \"corduroy\" at 0 mm, 0 mm\n").diagnostics), std::vector<std::string>{"E0501"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"corduroy\" at 0 mm 0 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0532"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  pach \"corduroy\" at 0 mm, 0 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0502"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"corduroy\" at 0 mm, 0 mm\n").diagnostics),
            std::vector<std::string>{"E0503"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n}\nsize 1 m\n").diagnostics), std::vector<std::string>{"E0504"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  size 1 m\n  size 2 m\n}\n").diagnostics), std::vector<std::string>{"E0505"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"corduroy\" at 0 mm, 0 mm size -2 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0506"});
  // A size the workspace program's reader would refuse (fuzz finding F9: 42e-30 mm compiled, then
  // did not read back).
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"corduroy\" at 0 mm, 0 mm size 42e-30 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0506"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  size 1e16 mm\n  patch \"corduroy\" at 0 mm, 0 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0506"});
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  patch \"  \" at 0 mm, 0 mm size 2 mm\n}\n").diagnostics),
            std::vector<std::string>{"E0508"});
  // Every error in the file, not just the first.
  EXPECT_EQ(codes(compile("workspace \"w\" {\n  pach 1\n  patch \"a\" at 0, 0 mm\n  size 2 N\n}\n").diagnostics),
            (std::vector<std::string>{"E0502", "E0203", "E0205"}));
}

TEST(WorkspaceCompile, APatchOutsideTheWorkspaceIsAnError) {
  // 9 in workspace: x within +-114.3 mm. A 40 mm patch at 100 mm reaches 120 mm.
  auto r = compile("workspace \"w\" {\n  patch \"corduroy\" at 100 mm, 0 mm size 40 mm\n}\n");
  EXPECT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0507"});
  EXPECT_FALSE(r.program.has_value());
  // Flush with the edge is inside.
  EXPECT_TRUE(compile("workspace \"w\" {\n  size 100 mm\n  patch \"corduroy\" at 30 mm, -30 mm size 40 mm\n}\n").ok());
  EXPECT_FALSE(compile("workspace \"w\" {\n  size 100 mm x 50 mm\n  patch \"corduroy\" at 0 mm, 10 mm size 40 mm\n}\n").ok());
}

TEST(WorkspaceCompile, HiddenPatchesAndEmptyWorkspacesWarn) {
  // corduroy (3.2 mm) and a10p100 (10 mm): neither grating is fine enough for W0350 (felt at speed).
  auto r = compile("workspace \"w\" {\n  patch \"corduroy\" at 0 mm, 0 mm size 10 mm\n  patch \"a10p100\" at 0 mm, 0 mm size 30 mm\n}\n");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(codes(r.diagnostics, compiler::Severity::Warning), std::vector<std::string>{"W0502"});
  auto e = compile("workspace \"w\" {\n}\n");
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(codes(e.diagnostics, compiler::Severity::Warning), std::vector<std::string>{"W0501"});
}

TEST(WorkspaceCompile, CommasStayErrorsInMaterials) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm, hill 50%; roughness 0.3");
  EXPECT_EQ(test::codes(r).front(), "E0102");
}

TEST(WorkspaceCompile, JsonHasEveryPatchWithUnits) {
  auto r = compiler::compile_workspace_file(test::shipped_compiler(), "examples/workspace/sampler.hws");
  ASSERT_TRUE(r.ok());
  const auto j = schema::to_json(*r.program);
  EXPECT_EQ(j["workspace"], "thesis sampler");
  ASSERT_EQ(j["patches"].size(), 7u);
  EXPECT_EQ(j["patches"][3]["index"], 3);
  EXPECT_DOUBLE_EQ(j["patches"][3]["centre_m"][0].get<double>(), 0.018);
  EXPECT_DOUBLE_EQ(j["patches"][3]["size_m"][1].get<double>(), 0.060);
  EXPECT_EQ(j["patches"][3]["program"]["material"], "a19p100");
  EXPECT_EQ(j["patches"][3]["source"], "a19p100");
}

TEST(WorkspaceCompile, MissingFile) {
  auto r = compiler::compile_workspace_file(test::shipped_compiler(), "no/such/workspace.hws");
  EXPECT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0500"});
}

// Issue 16: a workspace states its limit on patches, and close pairs of materials are summarised.
TEST(WorkspaceCompile, MorePatchesThanTheLimitAreRefused) {
  std::string text = "workspace \"w\" {\n  size 10000 mm\n";
  for (std::size_t i = 0; i <= schema::limits::kMaxWorkspacePatches; ++i) text += "  patch \"like corduroy\" at 0 mm, 0 mm size 1 mm\n";
  text += "}\n";
  const auto r = compile(text);
  EXPECT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0509"});
}

// F35: patches share a material's program, but distinct textures did not count against anything:
// six materials of 4000 x 4000 samples took 1.1 GB. The force tables a workspace holds (each distinct
// material's program and each placed copy) now have a budget; here a small one, in units of one
// material's tables, to see each way of crossing it.
TEST(WorkspaceCompile, ForceTablesPastTheBudgetAreRefusedAtThePatchThatCrossesIt) {
  // Material text in a workspace names images from the working directory (the source tree's root).
  const std::string a = "heightmap \\\"library/images/brick.png\\\" size 20 mm amplitude 1 N";
  const auto alone = test::shipped_compiler().compile_text("heightmap \"library/images/brick.png\" size 20 mm amplitude 1 N");
  ASSERT_TRUE(alone.ok()) << compiler::format_diagnostics(alone.diagnostics);
  const std::uint64_t one = schema::grid_bytes(*alone.program);
  ASSERT_GT(one, 0u);
  auto ws = [&](const std::vector<std::string>& patches, double budget_in_ones) {
    std::string text = "workspace \"w\" {\n  size 400 mm\n";
    for (const auto& p : patches) text += "  " + p + "\n";
    compiler::WorkspaceOptions o;
    o.max_grid_bytes = static_cast<std::uint64_t>(budget_in_ones * static_cast<double>(one));
    return compiler::compile_workspace_text(test::shipped_compiler(), text + "}\n", "<test.hws>", ".", o);
  };
  const std::string a_here = "patch \"" + a + "\" at -100 mm, 0 mm size 50 mm";
  const std::string a_there = "patch \"" + a + "\" at 100 mm, 0 mm size 50 mm";
  const std::string a_smaller = "patch \"" + a + "\" at 0 mm, 100 mm size 40 mm";
  const std::string b = "patch \"heightmap \\\"library/images/brick.png\\\" size 20 mm amplitude 0.9 N\" at 0 mm, -100 mm size 50 mm";

  // One material placed twice at one size: its program and one placed copy.
  auto r = ws({a_here, a_there}, 2.5);
  EXPECT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  // Materials are compiled before any patch is placed: a second distinct material is 2 tables, over 1.5.
  r = ws({a_here, b}, 1.5);
  ASSERT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0535"}) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_FALSE(r.program.has_value());
  const auto& e = r.diagnostics.all().front();
  EXPECT_EQ(e.location.line, 4u);  // patch 2's line
  EXPECT_NE(e.message.find("patch 2 needs"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("for its material's program"), std::string::npos) << e.message;
  // The same material at another size is another copy: its program and two copies are 3 tables.
  r = ws({a_here, a_smaller}, 2.5);
  ASSERT_EQ(codes(r.diagnostics), std::vector<std::string>{"E0535"}) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NE(r.diagnostics.all().front().message.find("placed at 40 mm x 40 mm"), std::string::npos)
      << r.diagnostics.all().front().message;
  // With room for them, both compile.
  EXPECT_TRUE(ws({a_here, a_smaller, b}, 5).ok());
}

// Every shipped workspace is far inside the budget: each distinct material's tables plus each
// placed copy, as the compiler counts them.
TEST(WorkspaceCompile, ShippedWorkspacesHoldFarLessThanTheForceTableBudget) {
  std::uint64_t most = 0;
  std::string which;
  for (const auto& entry : fs::recursive_directory_iterator("examples")) {
    if (entry.path().extension() != ".hws") continue;
    const auto r = compiler::compile_workspace_file(test::shipped_compiler(), entry.path());
    ASSERT_TRUE(r.ok()) << entry.path() << "\n" << compiler::format_diagnostics(r.diagnostics);
    std::set<const schema::PatchProgram*> placed;
    std::set<std::string> materials;
    std::uint64_t held = 0;
    for (const auto& p : r.program->patches) {
      if (placed.insert(p.program.get()).second) held += schema::grid_bytes(*p.program);
      if (materials.insert(p.source).second) held += schema::grid_bytes(*p.program);
    }
    if (held > most) most = held, which = entry.path().string();
  }
  std::cout << "largest shipped workspace: " << which << ", " << most << " bytes of force tables\n";
  EXPECT_GT(most, 0u);
  EXPECT_LT(most, schema::limits::kMaxWorkspaceGridBytes / 16);
}

// 2,000 distinct materials used to give one W0503 per close pair (591 MB of warnings): now the
// first 20 pairs and one summary with the count of the rest.
TEST(WorkspaceCompile, CloseMaterialPairsAreListedThenCounted) {
  std::string text = "workspace \"w\" {\n  size 1000 mm\n";
  constexpr int kMaterials = 60;  // forces 0.1% apart: every pair within one JND is close
  for (int i = 0; i < kMaterials; ++i)
    text += "  patch \"grating period 2 mm amplitude " + std::to_string(1.0 + 0.001 * i) + " N\" at " +
            std::to_string(-450 + 15 * i) + " mm, 0 mm size 10 mm\n";
  text += "}\n";
  const auto r = compile(text);
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics).substr(0, 2000);
  const auto w = codes(r.diagnostics, compiler::Severity::Warning);
  EXPECT_EQ(std::count(w.begin(), w.end(), "W0503"), 21);
  const auto& last = r.diagnostics.all().back();
  EXPECT_EQ(last.code, "W0503");
  // 60 materials, every pair closer than one JND: 1770 pairs, 20 listed.
  EXPECT_NE(last.message.find("and 1750 more pairs"), std::string::npos) << last.message;
}

// 100,000 patches of one material used to hold 100,000 copies of its program (3.25 GB): patches of
// one material at one size now share one program, in the compiler's output and read back from a
// workspace program file.
TEST(WorkspaceCompile, PatchesOfOneMaterialAndSizeShareOneProgram) {
  std::string text = "workspace \"w\" {\n  size 1000 mm\n";
  constexpr int kPatches = 5000;
  for (int i = 0; i < kPatches; ++i)
    text += "  patch \"like corduroy\" at " + std::to_string(-400 + (i % 80) * 10) + " mm, " +
            std::to_string(-400 + (i / 80) * 10) + " mm size " + (i % 2 ? "8 mm" : "6 mm") + "\n";
  text += "}\n";
  const auto r = compile(text);
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics).substr(0, 2000);
  std::set<const schema::PatchProgram*> distinct;
  for (const auto& p : r.program->patches) {
    distinct.insert(p.program.get());
    EXPECT_EQ(p.program->size_m[0], p.size_m[0]);
  }
  EXPECT_EQ(distinct.size(), 2u);  // one per size
  const fs::path dir = test::temp_dir("ws-shared");
  schema::write_workspace_program_file(dir / "w.wsp", *r.program);
  const auto back = schema::read_workspace_program_file(dir / "w.wsp");
  std::set<const schema::PatchProgram*> read_distinct;
  for (const auto& p : back.patches) read_distinct.insert(p.program.get());
  EXPECT_EQ(read_distinct.size(), 2u);
  ASSERT_EQ(back.patches.size(), static_cast<std::size_t>(kPatches));
  EXPECT_EQ(back.patches[1].program->size_m[0], 0.008);
}

// WorkspaceOptions::compile_material: asked once per distinct material, with the .hmat resolved and
// material text named as the compiler would name it; a hook that compiles gives the same workspace,
// byte for byte, as none.
TEST(WorkspaceCompile, TheMaterialHookIsAskedOncePerDistinctMaterial) {
  const std::string text =
      "workspace \"w\" {\n"
      "  patch \"corduroy\" at -60 mm, 0 mm size 20 mm\n"
      "  patch \"../corduroy.hmat\" at -30 mm, 0 mm size 20 mm\n"
      "  patch \"corduroy\" at 0 mm, 0 mm size 30 mm\n"
      "  patch \"roughness 0.3; grating period 5 mm\" at 30 mm, 0 mm size 20 mm\n"
      "}\n";
  const fs::path base = fs::path(SANDPAPER_SOURCE_DIR) / "examples" / "workspace";
  std::vector<compiler::WorkspaceMaterial> asked;
  compiler::WorkspaceOptions options;
  options.compile_material = [&](const compiler::Compiler& c, const compiler::WorkspaceMaterial& m) {
    asked.push_back(m);
    return compiler::compile_workspace_material(c, m);
  };
  const auto hooked = compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", base, options);
  const auto plain = compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", base);
  ASSERT_TRUE(plain.ok()) << compiler::format_diagnostics(plain.diagnostics);
  ASSERT_TRUE(hooked.ok()) << compiler::format_diagnostics(hooked.diagnostics);
  ASSERT_EQ(asked.size(), 3u);
  EXPECT_EQ(asked[0].text, "corduroy");
  EXPECT_TRUE(asked[0].file.empty());
  EXPECT_EQ(asked[0].display_name, "<patch 1>");
  EXPECT_EQ(asked[1].text, "../corduroy.hmat");
  EXPECT_EQ(asked[1].file, (base / "../corduroy.hmat").lexically_normal());
  EXPECT_EQ(asked[2].display_name, "<patch 4>");
  EXPECT_EQ(compiler::format_diagnostics(hooked.diagnostics), compiler::format_diagnostics(plain.diagnostics));
  const fs::path dir = test::temp_dir("ws-hook");
  schema::write_workspace_program_file(dir / "plain.wsp", *plain.program);
  schema::write_workspace_program_file(dir / "hooked.wsp", *hooked.program);
  const auto bytes = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(bytes(dir / "hooked.wsp"), bytes(dir / "plain.wsp"));
}

// What the hook answers is what the workspace places, errors included.
TEST(WorkspaceCompile, WhatTheMaterialHookAnswersIsPlaced) {
  const std::string text = "workspace \"w\" {\n  patch \"corduroy\" at 0 mm, 0 mm size 20 mm\n}\n";
  compiler::WorkspaceOptions options;
  std::string answer = "silk-satin";
  options.compile_material = [&](const compiler::Compiler& c, const compiler::WorkspaceMaterial& m) {
    return std::make_shared<const compiler::CompileResult>(c.compile_text(answer, m.display_name));
  };
  const auto swapped = compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", ".", options);
  ASSERT_TRUE(swapped.ok()) << compiler::format_diagnostics(swapped.diagnostics);
  EXPECT_EQ(swapped.program->patches.at(0).program->name, "silk-satin");
  EXPECT_EQ(swapped.program->patches.at(0).source, "corduroy");

  answer = "unobtainium";
  const auto failed = compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", ".", options);
  EXPECT_FALSE(failed.program.has_value());
  EXPECT_EQ(codes(failed.diagnostics), std::vector<std::string>{"E0301"});

  options.compile_material = [](const compiler::Compiler&, const compiler::WorkspaceMaterial&) {
    return std::shared_ptr<const compiler::CompileResult>();
  };
  EXPECT_THROW(compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", ".", options), std::logic_error);
}

}  // namespace
}  // namespace sandpaper
