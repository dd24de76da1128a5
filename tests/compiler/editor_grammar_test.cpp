// The editors' TextMate grammar (editors/vscode/syntaxes/sandpaper.tmLanguage.json) against the
// compiler: its statement words and units are exactly the language's, and its patterns colour real
// material files as the compiler reads them. The patterns use only what ECMAScript regexes share
// with Oniguruma (groups, alternation, lookahead), so std::regex runs them here as an editor would.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/units.hpp"

namespace {

const std::filesystem::path kSource = SANDPAPER_SOURCE_DIR;

nlohmann::json grammar() {
  std::ifstream in(kSource / "editors/vscode/syntaxes/sandpaper.tmLanguage.json");
  return nlohmann::json::parse(in);
}

std::string pattern(const std::string& rule) { return grammar()["repository"][rule]["match"].get<std::string>(); }

// The words of the first group of alternatives "(a|b|c)" after `after` in a pattern, unescaped.
std::set<std::string> alternatives(const std::string& match, const std::string& after) {
  const auto start = match.find(after);
  EXPECT_NE(start, std::string::npos) << after << " not in " << match;
  const auto open = match.find('(', start + after.size() - 1);
  const auto close = match.find(')', open);
  std::set<std::string> words;
  std::stringstream ss(match.substr(open + 1, close - open - 1));
  for (std::string w; std::getline(ss, w, '|');) {
    w.erase(std::remove(w.begin(), w.end(), '\\'), w.end());
    words.insert(w);
  }
  return words;
}

std::vector<std::pair<std::string, std::string>> quantities(const std::string& line) {
  const std::regex re(pattern("quantity"));
  std::vector<std::pair<std::string, std::string>> out;
  for (std::sregex_iterator it(line.begin(), line.end(), re), end; it != end; ++it) out.emplace_back((*it)[1], (*it)[2]);
  return out;
}

TEST(EditorGrammar, StatementWordsAreExactlyTheLanguages) {
  const auto& keywords = sandpaper::compiler::statement_keywords();
  const std::set<std::string> language(keywords.begin(), keywords.end());
  EXPECT_EQ(alternatives(pattern("statement"), "\\s*("), language);
}

TEST(EditorGrammar, UnitsAreExactlyTheLanguages) {
  std::set<std::string> language;
  for (const auto& u : sandpaper::schema::all_units()) language.insert(std::string(u.name));
  EXPECT_EQ(alternatives(pattern("quantity"), ")\\s*("), language);
}

// The words of the JavaScript `const NAME = new Set([...])` in `text`.
std::set<std::string> js_set(const std::string& text, const std::string& name) {
  const auto start = text.find("const " + name + " = new Set([");
  EXPECT_NE(start, std::string::npos) << "no Set " << name;
  const auto end = text.find("])", start);
  const std::string list = text.substr(start, end - start);
  std::set<std::string> words;
  const std::regex quoted("\"([^\"]+)\"");
  for (std::sregex_iterator it(list.begin(), list.end(), quoted), e; it != e; ++it) words.insert((*it)[1]);
  return words;
}

std::string read_source(const std::filesystem::path& relative) {
  std::ifstream in(kSource / relative);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The studio's highlighter (studio/web/src/hmat.js) keeps lists of its own: its statement words
// are the language's, with the block openers and the licence's American spelling the parser takes,
// and its units are the language's.
TEST(EditorGrammar, TheStudiosHighlighterKnowsTheLanguagesWordsAndUnits) {
  const std::string js = read_source("studio/web/src/hmat.js");
  const auto& keywords = sandpaper::compiler::statement_keywords();
  std::set<std::string> language(keywords.begin(), keywords.end());
  language.insert({"material", "workspace", "patch", "license"});
  EXPECT_EQ(js_set(js, "statements"), language);
  std::set<std::string> units;
  for (const auto& u : sandpaper::schema::all_units()) units.insert(std::string(u.name));
  EXPECT_EQ(js_set(js, "units"), units);
}

// The fuzzing dictionary (fuzz/dict/material.dict) holds every statement word and unit, so that
// the material target starts from the whole language.
TEST(EditorGrammar, TheFuzzDictionaryHoldsEveryWordAndUnit) {
  const std::string dict = read_source("fuzz/dict/material.dict");
  std::set<std::string> entries;
  std::stringstream lines(dict);
  for (std::string l; std::getline(lines, l);)
    if (l.size() >= 2 && l.front() == '"' && l.back() == '"') entries.insert(l.substr(1, l.size() - 2));
  for (const auto& k : sandpaper::compiler::statement_keywords()) EXPECT_TRUE(entries.count(k)) << k << " not in material.dict";
  for (const auto& u : sandpaper::schema::all_units())
    EXPECT_TRUE(entries.count(std::string(u.name))) << u.name << " not in material.dict";
}

TEST(EditorGrammar, QuantitiesTakeTheWholeUnit) {
  using Q = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(quantities("grating period 3.2 mm hill 50%"), (Q{{"3.2", "mm"}, {"50", "%"}}));
  EXPECT_EQ(quantities("spring 200 N/m; damper 2 N*s/m"), (Q{{"200", "N/m"}, {"2", "N*s/m"}}));
  EXPECT_EQ(quantities("speed 50 mm/s, 1e-3 m, stiff 0.2 N/mm"), (Q{{"50", "mm/s"}, {"1e-3", "m"}, {"0.2", "N/mm"}}));
  EXPECT_EQ(quantities("size 228.6 mm x 228.6 mm"), (Q{{"228.6", "mm"}, {"228.6", "mm"}}));
  EXPECT_TRUE(quantities("like corduroy; roughness coarse").empty());
  EXPECT_TRUE(quantities("period 3 mmx").empty()) << "a unit is a whole word";
}

// Every statement of every shipped material file starts with a word the grammar colours as one
// (a statement word, or the `material "name" {` and workspace words that open a block).
TEST(EditorGrammar, ColoursEveryStatementOfTheShippedFiles) {
  const std::regex statement(pattern("statement"));
  const std::regex material(pattern("material"));
  const std::regex workspace(pattern("workspace"));
  int files = 0, lines = 0;
  for (const char* dir : {"examples", "library"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(kSource / dir)) {
      const auto ext = e.path().extension();
      if (ext != ".hmat" && ext != ".hws") continue;
      ++files;
      std::ifstream in(e.path());
      for (std::string line; std::getline(in, line);) {
        const auto text = line.substr(0, line.find('#'));
        const auto first = text.find_first_not_of(" \t");
        if (first == std::string::npos || text[first] == '}' || text[first] == '"') continue;
        ++lines;
        const bool coloured = std::regex_search(text, statement) || std::regex_search(text, material) ||
                              (ext == ".hws" && std::regex_search(text.substr(first), workspace));
        EXPECT_TRUE(coloured) << e.path().string() << ": " << line;
      }
    }
  EXPECT_GT(files, 100);
  EXPECT_GT(lines, 500);
}

}  // namespace
