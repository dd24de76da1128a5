// The language server driven as an editor drives it: framed JSON-RPC in, framed JSON-RPC out,
// through the same serve() loop `sandpaper lsp` runs on stdio (tests/lsp/lsp_stdio_test.py runs
// the real process).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/lsp/jsonrpc.hpp"
#include "sandpaper/lsp/server.hpp"
#include "sandpaper/lsp/text_positions.hpp"
#include "test_support.hpp"

namespace {

using nlohmann::json;
namespace lsp = sandpaper::lsp;

std::string frame(const json& j) {
  std::ostringstream os;
  lsp::write_message(os, j);
  return os.str();
}

json request(int id, const std::string& method, json params = json::object()) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}};
}
json notification(const std::string& method, json params = json::object()) {
  return {{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
}

struct Session {
  std::vector<json> replies;
  int status = -1;
  std::string log;
  // The reply to request `id`.
  json response(int id) const {
    for (const auto& r : replies)
      if (r.contains("id") && r["id"] == id) return r;
    ADD_FAILURE() << "no response to request " << id;
    return {};
  }
  std::vector<json> diagnostics_published() const {
    std::vector<json> out;
    for (const auto& r : replies)
      if (r.value("method", "") == "textDocument/publishDiagnostics") out.push_back(r["params"]);
    return out;
  }
};

Session run(const std::string& input) {
  std::istringstream in(input);
  std::ostringstream out, log;
  Session s;
  s.status = lsp::serve(in, out, log, sandpaper::test::shipped_compiler());
  s.log = log.str();
  std::istringstream replies(out.str());
  while (auto body = lsp::read_message(replies)) s.replies.push_back(json::parse(*body));
  return s;
}

const std::string kUri = lsp::uri_of_path(std::string(SANDPAPER_SOURCE_DIR) + "/examples/lsp test.hmat");
json doc(const std::string& text) { return {{"textDocument", {{"uri", kUri}, {"languageId", "sandpaper"}, {"version", 1}, {"text", text}}}}; }
json at(int line, int character) { return {{"textDocument", {{"uri", kUri}}}, {"position", {{"line", line}, {"character", character}}}}; }

std::vector<std::string> labels(const json& items) {
  std::vector<std::string> out;
  for (const auto& i : items) out.push_back(i["label"].get<std::string>());
  return out;
}
bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

const std::string kMaterial =
    "material \"wale\" {\n"               // line 0
    "  like corduroy\n"                   // line 1
    "  roughness 0.55\n"                  // line 2
    "  grating period 3.2 mm hill 50%\n"  // line 3
    "}\n";

TEST(LspFraming, ReadsMessagesBackToBackAndStopsCleanlyAtTheEnd) {
  std::istringstream in("Content-Length: 2\r\nContent-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n{}"
                        "content-length:  7 \r\n\r\n[1,2,3]");
  EXPECT_EQ(lsp::read_message(in), "{}");
  EXPECT_EQ(lsp::read_message(in), "[1,2,3]");
  EXPECT_EQ(lsp::read_message(in), std::nullopt);
}

TEST(LspFraming, RefusesWhatCannotBeResynchronised) {
  for (const char* bad : {"Content-Type: x\r\n\r\n{}", "Content-Length: two\r\n\r\n{}", "Content-Length: -2\r\n\r\n{}",
                          "Content-Length: 999999999999\r\n\r\n", "Content-Length: 10\r\n\r\n{}", "no colon here\r\n\r\n",
                          "Content-Length: 2\r\n"}) {
    std::istringstream in(bad);
    EXPECT_THROW(lsp::read_message(in), lsp::FramingError) << bad;
  }
  std::istringstream long_line(std::string(5000, 'x'));
  EXPECT_THROW(lsp::read_message(long_line), lsp::FramingError);
}

TEST(LspPositions, Utf16ColumnsAndFileUris) {
  const std::string line = "describes \"caf\xC3\xA9 \xF0\x9F\x98\x80\" x";  // e-acute: 2 bytes, 1 unit; emoji: 4 bytes, 2 units
  EXPECT_EQ(lsp::utf16_units(line, 14), 14);
  EXPECT_EQ(lsp::utf16_units(line, 16), 15);
  EXPECT_EQ(lsp::utf16_units(line, 21), 18);
  EXPECT_EQ(lsp::byte_offset(line, 18), 21u);
  EXPECT_EQ(lsp::byte_offset(line, 15), 16u);
  EXPECT_EQ(lsp::path_of_uri("file:///home/a%20b/x.hmat"), "/home/a b/x.hmat");
  EXPECT_EQ(lsp::path_of_uri("file://localhost/x.hmat"), "/x.hmat");
  EXPECT_EQ(lsp::path_of_uri("untitled:Untitled-1"), "");
  EXPECT_EQ(lsp::path_of_uri("file://otherhost/x.hmat"), "");
  EXPECT_EQ(lsp::uri_of_path("/home/a b/x#1.hmat"), "file:///home/a%20b/x%231.hmat");
}

TEST(Lsp, DiagnosticsAsYouTypeWithCodeRangeAndDocLink) {
  // "é" before the error: the range must count UTF-16 units, not bytes.
  const std::string bad = "material \"caf\xC3\xA9\" {\n  describes \"caf\xC3\xA9\"; grating period 3 zz\n}\n";
  const Session s = run(frame(request(1, "initialize", {{"capabilities", json::object()}})) +
                        frame(notification("initialized")) + frame(notification("textDocument/didOpen", doc(bad))) +
                        frame(notification("textDocument/didChange",
                                           {{"textDocument", {{"uri", kUri}, {"version", 2}}},
                                            {"contentChanges", json::array({{{"text", kMaterial}}})}})) +
                        frame(request(2, "shutdown")) + frame(notification("exit")));
  EXPECT_EQ(s.status, 0);
  EXPECT_NE(s.log.find("ready"), std::string::npos);
  const json caps = s.response(1)["result"]["capabilities"];
  EXPECT_EQ(caps["textDocumentSync"]["change"], 1);
  EXPECT_TRUE(caps["hoverProvider"].get<bool>());
  const auto published = s.diagnostics_published();
  ASSERT_EQ(published.size(), 2u);
  ASSERT_EQ(published[0]["diagnostics"].size(), 1u) << published[0].dump(2);
  const json d = published[0]["diagnostics"][0];
  EXPECT_EQ(d["code"], "E0203");  // `3` has no unit
  EXPECT_EQ(d["severity"], 1);
  EXPECT_EQ(d["source"], "sandpaper");
  // "  describes "café"; grating period 3 zz": the 3 is byte 36 (0-based) but UTF-16 unit 35.
  EXPECT_EQ(d["range"]["start"], (json{{"line", 1}, {"character", 35}}));
  EXPECT_EQ(d["range"]["end"], (json{{"line", 1}, {"character", 36}}));
  EXPECT_NE(d["message"].get<std::string>().find("help:"), std::string::npos);
  const std::string href = d["codeDescription"]["href"];
  EXPECT_EQ(href.substr(0, 7), "file://");
  EXPECT_EQ(href.substr(href.size() - 24), "schema/LANGUAGE.md#e0203");
  EXPECT_TRUE(published[1]["diagnostics"].empty()) << published[1].dump(2);  // fixed by the change
  EXPECT_EQ(s.response(2)["result"], nullptr);
}

TEST(Lsp, CompletesKeywordsLibraryNamesLevelsAndUnits) {
  const std::string text = "\n  like \n  roughness \n  grating period 3 \n  # like \n  grating amplitude 2 \n  roughness 0.5 \n";
  const Session s = run(frame(request(1, "initialize")) + frame(notification("textDocument/didOpen", doc(text))) +
                        frame(request(2, "textDocument/completion", at(0, 0))) +
                        frame(request(3, "textDocument/completion", at(1, 7))) +
                        frame(request(4, "textDocument/completion", at(2, 12))) +
                        frame(request(5, "textDocument/completion", at(3, 19))) +
                        frame(request(6, "textDocument/completion", at(4, 9))) +
                        frame(request(8, "textDocument/completion", at(5, 22))) +
                        frame(request(9, "textDocument/completion", at(6, 16))) + frame(request(7, "shutdown")) +
                        frame(notification("exit")));
  const auto keywords = labels(s.response(2)["result"]);
  EXPECT_TRUE(has(keywords, "grating") && has(keywords, "like") && has(keywords, "roughness")) << s.response(2).dump();
  const auto names = labels(s.response(3)["result"]);
  EXPECT_TRUE(has(names, "corduroy")) << s.response(3).dump();
  EXPECT_FALSE(has(names, "grating"));
  const auto levels = labels(s.response(4)["result"]);
  EXPECT_TRUE(has(levels, "coarse") && has(levels, "very-fine")) << s.response(4).dump();
  const auto units = labels(s.response(5)["result"]);
  // The units the place takes (schema/LANGUAGE.md): a period is a length, an amplitude a force,
  // roughness a plain ratio-scale number.
  EXPECT_TRUE(has(units, "mm") && has(units, "in")) << s.response(5).dump();
  EXPECT_FALSE(has(units, "N") || has(units, "N/m") || has(units, "%")) << s.response(5).dump();
  const auto forces = labels(s.response(8)["result"]);
  EXPECT_TRUE(has(forces, "N") && has(forces, "gf")) << s.response(8).dump();
  EXPECT_FALSE(has(forces, "mm")) << s.response(8).dump();
  EXPECT_TRUE(s.response(9)["result"].empty()) << "roughness takes no unit: " << s.response(9).dump();
  EXPECT_TRUE(s.response(6)["result"].empty()) << "nothing to complete in a comment";
}

TEST(Lsp, HoverShowsExplainsLineForTheNumberAndTheLibraryEntry) {
  const Session s = run(frame(request(1, "initialize")) + frame(notification("textDocument/didOpen", doc(kMaterial))) +
                        frame(request(2, "textDocument/hover", at(3, 18))) +   // on "3.2"
                        frame(request(3, "textDocument/hover", at(3, 21))) +   // on "mm"
                        frame(request(4, "textDocument/hover", at(2, 14))) +   // on "0.55"
                        frame(request(5, "textDocument/hover", at(1, 9))) +    // on "corduroy"
                        frame(request(6, "textDocument/hover", at(0, 2))) +    // on "material": nothing
                        frame(request(7, "shutdown")) + frame(notification("exit")));
  const std::string period = s.response(2)["result"]["contents"]["value"];
  EXPECT_NE(period.find("texture.period"), std::string::npos) << period;
  EXPECT_NE(period.find("3.2 mm"), std::string::npos) << period;
  EXPECT_NE(period.find("physical"), std::string::npos) << period;
  EXPECT_EQ(s.response(2)["result"]["range"]["start"], (json{{"line", 3}, {"character", 17}}));
  EXPECT_EQ(s.response(3)["result"]["contents"], s.response(2)["result"]["contents"]);
  const std::string roughness = s.response(4)["result"]["contents"]["value"];
  EXPECT_NE(roughness.find("perceptual"), std::string::npos) << roughness;
  EXPECT_NE(roughness.find("0.55"), std::string::npos) << roughness;
  const std::string entry = s.response(5)["result"]["contents"]["value"];
  EXPECT_NE(entry.find("**corduroy**"), std::string::npos) << entry;
  EXPECT_NE(entry.find("corduroy.hmat"), std::string::npos) << entry;
  EXPECT_EQ(s.response(6)["result"], nullptr);
}

TEST(Lsp, DefinitionOfLikeGoesToTheLibraryEntrysMaterialLine) {
  const Session s = run(frame(request(1, "initialize")) + frame(notification("textDocument/didOpen", doc(kMaterial))) +
                        frame(request(2, "textDocument/definition", at(1, 10))) +
                        frame(request(3, "textDocument/definition", at(3, 5))) + frame(request(4, "shutdown")) +
                        frame(notification("exit")));
  const json loc = s.response(2)["result"];
  const std::string uri = loc["uri"];
  const auto* entry = sandpaper::test::shipped_compiler().library().entry("corduroy");
  ASSERT_NE(entry, nullptr);
  EXPECT_EQ(lsp::path_of_uri(uri), std::filesystem::absolute(entry->file).string());
  std::ifstream in(entry->file);
  std::string line;
  for (int n = 0; n <= loc["range"]["start"]["line"].get<int>(); ++n) std::getline(in, line);
  EXPECT_EQ(line.rfind("material \"corduroy\"", 0), 0u) << line;
  EXPECT_EQ(s.response(3)["result"], nullptr);
}

TEST(Lsp, ProtocolErrorsAreAnsweredNotFatal) {
  const Session s = run(frame(request(1, "textDocument/hover", at(0, 0))) +  // before initialize
                        "Content-Length: 5\r\n\r\n{oops" + frame(request(2, "initialize")) +
                        frame(request(3, "workspace/symbol", {{"query", ""}})) +
                        frame(request(4, "textDocument/hover", {{"textDocument", 7}})) +
                        frame(request(5, "textDocument/hover", at(0, 0))) +  // not open
                        frame(notification("exit")));                          // without shutdown
  EXPECT_EQ(s.response(1)["error"]["code"], -32002);
  bool parse_error = false;
  for (const auto& r : s.replies) parse_error |= r.contains("error") && r["error"]["code"] == -32700 && r["id"] == nullptr;
  EXPECT_TRUE(parse_error);
  EXPECT_TRUE(s.response(2).contains("result"));
  EXPECT_EQ(s.response(3)["error"]["code"], -32601);
  EXPECT_EQ(s.response(4)["error"]["code"], -32602);
  EXPECT_EQ(s.response(5)["error"]["code"], -32602);
  EXPECT_EQ(s.status, 1) << "exit without shutdown";
}

TEST(Lsp, AProblemInALibraryEntryIsMarkedOnTheLikeThatBroughtItInAndLinksToTheEntry) {
  // silk-satin's fine grating loses more than a force JND on sim's 1000 Hz servo: its warning lies
  // in the entry's file, not in the open text, which has three lines.
  const std::string text = "material \"sheen\" {\n  like silk-satin\n}\n";
  const Session s = run(frame(request(1, "initialize")) + frame(notification("textDocument/didOpen", doc(text))) +
                        frame(request(2, "shutdown")) + frame(notification("exit")));
  const auto published = s.diagnostics_published();
  ASSERT_EQ(published.size(), 1u);
  const std::string entry_file = std::string(SANDPAPER_SOURCE_DIR) + "/library/textiles/silk-satin.hmat";
  json from_entry;
  for (const auto& d : published[0]["diagnostics"])
    if (d.contains("relatedInformation") && d["relatedInformation"][0]["location"]["uri"] == lsp::uri_of_path(entry_file))
      from_entry = d;
  ASSERT_TRUE(from_entry.is_object()) << "no diagnostic links to the entry's file: " << published[0].dump(2);
  // Marked on `silk-satin` in `  like silk-satin` (line 1, characters 7-17), not on a line the text lacks.
  EXPECT_EQ(from_entry["range"]["start"], (json{{"line", 1}, {"character", 7}})) << from_entry.dump(2);
  EXPECT_EQ(from_entry["range"]["end"], (json{{"line", 1}, {"character", 17}})) << from_entry.dump(2);
  EXPECT_NE(from_entry["message"].get<std::string>().find("silk-satin.hmat:"), std::string::npos) << from_entry["message"];
  const json where = from_entry["relatedInformation"][0];
  EXPECT_GT(where["location"]["range"]["start"]["line"].get<int>(), 0) << "the entry's own line, not its start";
  EXPECT_NE(where["message"].get<std::string>().find("silk-satin"), std::string::npos) << where.dump();
}

TEST(Lsp, WorkspaceFilesGetTheWorkspaceCompilersDiagnostics) {
  const std::string uri = lsp::uri_of_path(std::string(SANDPAPER_SOURCE_DIR) + "/examples/workspace/lsp.hws");
  const std::string text = "workspace \"w\" {\n  patch \"roughness 0.4; grating period 2 mm\" at 0 mm, 0 mm size 400 mm\n}\n";
  const Session s = run(frame(request(1, "initialize")) +
                        frame(notification("textDocument/didOpen",
                                           {{"textDocument", {{"uri", uri}, {"languageId", "sandpaper"}, {"version", 1}, {"text", text}}}})) +
                        frame(request(2, "shutdown")) + frame(notification("exit")));
  const auto published = s.diagnostics_published();
  ASSERT_EQ(published.size(), 1u);
  json outside;  // the patch reaches outside the workspace
  for (const auto& d : published[0]["diagnostics"])
    if (d["code"] == "E0507") outside = d;
  ASSERT_TRUE(outside.is_object()) << published[0].dump(2);
  EXPECT_EQ(outside["severity"], 1);
  EXPECT_EQ(outside["range"]["start"]["line"], 1);
}

}  // namespace
