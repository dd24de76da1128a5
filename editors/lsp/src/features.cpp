#include "sandpaper/lsp/features.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/workspace_parser.hpp"
#include "sandpaper/lsp/text_positions.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::lsp {
namespace {

using nlohmann::json;
using compiler::Token;
using compiler::TokenKind;

// LSP CompletionItemKind values.
constexpr int kKindModule = 9, kKindUnit = 11, kKindValue = 12, kKindKeyword = 14;

struct Cursor {
  int line = 0;           // 1-based, as the compiler counts
  std::size_t byte = 0;   // 0-based byte offset in the line
};

Cursor cursor_of(const json& position, const compiler::SourceFile& file) {
  Cursor c;
  c.line = position.at("line").get<int>() + 1;
  c.byte = byte_offset(file.line_text(c.line), position.at("character").get<int>());
  return c;
}

std::vector<Token> tokens_of(const Document& d) {
  compiler::Diagnostics ignored;  // the document's own diagnostics were published already
  return compiler::lex(d.source, ignored, {.commas = d.workspace});
}

// The token the cursor is on or just after (an editor's cursor sits after the word it hovers).
std::optional<std::size_t> token_at(const std::vector<Token>& tokens, Cursor c) {
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const auto& loc = tokens[i].location;
    if (loc.line != c.line || tokens[i].kind == TokenKind::End || tokens[i].kind == TokenKind::Eof) continue;
    const auto start = static_cast<std::size_t>(loc.column - 1);
    if (c.byte >= start && c.byte <= start + static_cast<std::size_t>(loc.length)) return i;
  }
  return std::nullopt;
}

// The statement holding token `i`: [first, last] token indices, without its End.
std::pair<std::size_t, std::size_t> statement_of(const std::vector<Token>& tokens, std::size_t i) {
  std::size_t first = i, last = i;
  while (first > 0 && tokens[first - 1].kind != TokenKind::End && tokens[first - 1].kind != TokenKind::LBrace) --first;
  while (last + 1 < tokens.size() && tokens[last + 1].kind != TokenKind::End && tokens[last + 1].kind != TokenKind::Eof &&
         tokens[last + 1].kind != TokenKind::RBrace)
    ++last;
  return {first, last};
}

// The name a `like` statement under the cursor gives, as written: its text from the first token
// after `like` to the statement's last. Empty if the cursor is not on one.
std::string like_name_at(const Document& d, const std::vector<Token>& tokens, Cursor c) {
  const auto i = token_at(tokens, c);
  if (!i) return {};
  const auto [first, last] = statement_of(tokens, *i);
  if (first >= last || tokens[first].kind != TokenKind::Word || tokens[first].text != "like" || *i == first) return {};
  const auto& a = tokens[first + 1].location;
  const auto& b = tokens[last].location;
  if (a.line != b.line) return {};
  const std::string_view line = d.source->line_text(a.line);
  const auto from = static_cast<std::size_t>(a.column - 1);
  const auto to = static_cast<std::size_t>(b.column - 1 + b.length);
  return to <= line.size() ? std::string(line.substr(from, to - from)) : std::string();
}

json item(const std::string& label, int kind, const std::string& detail) {
  json j = {{"label", label}, {"kind", kind}};
  if (!detail.empty()) j["detail"] = detail;
  return j;
}

bool is_number_text(const std::string& w) {
  if (w.empty()) return false;
  std::size_t used = 0;
  try {
    (void)std::stod(w, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == w.size();
}

// The dimensions the parser takes for a unit at the cursor: the document with the word being typed
// replaced by one unit of each dimension, parsed, and the dimensions whose unit draws no unit error
// (E0204, E0205) there kept. The parser's own rules, so that the offer never drifts from what compiles.
std::vector<schema::Dimension> dimensions_at(const Document& d, Cursor c, std::size_t word_start) {
  const std::string& text = d.source->text;
  std::size_t line_start = 0;
  for (int l = 1; l < c.line && line_start != std::string::npos; ++l) {
    line_start = text.find('\n', line_start);
    if (line_start != std::string::npos) ++line_start;
  }
  if (line_start == std::string::npos) return {};
  const std::size_t from = line_start + word_start, to = std::min(line_start + c.byte, text.size());
  std::size_t end = to;
  while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '/' ||
                               text[end] == '*' || text[end] == '%'))
    ++end;
  std::vector<schema::Dimension> kept, tried;
  for (const auto& u : schema::all_units()) {
    if (std::find(tried.begin(), tried.end(), u.dimension) != tried.end()) continue;
    tried.push_back(u.dimension);
    const std::string trial = text.substr(0, from) + std::string(u.name) + text.substr(end);
    const auto file = std::make_shared<const compiler::SourceFile>(d.name, trial);
    compiler::Diagnostics diags;
    const auto tokens = compiler::lex(file, diags, {.commas = d.workspace});
    if (d.workspace) (void)compiler::parse_workspace(tokens, file, diags);
    else (void)compiler::parse(tokens, file, diags);
    const bool refused = std::any_of(diags.all().begin(), diags.all().end(), [&](const compiler::Diagnostic& x) {
      return (x.code == "E0204" || x.code == "E0205") && x.location.line == c.line &&
             static_cast<std::size_t>(x.location.column - 1) == word_start;
    });
    if (!refused) kept.push_back(u.dimension);
  }
  return kept;
}

}  // namespace

json completion(const Document& d, const json& position, const compiler::Compiler& c) {
  const Cursor cur = cursor_of(position, *d.source);
  const std::string_view line = d.source->line_text(cur.line);
  std::string prefix(line.substr(0, std::min(cur.byte, line.size())));
  // Nothing to complete inside a comment or a quoted text.
  bool quoted = false;
  for (const char ch : prefix) {
    if (ch == '"') quoted = !quoted;
    if (ch == '#' && !quoted) return json::array();
  }
  if (quoted) return json::array();
  if (const auto cut = prefix.find_last_of(";{"); cut != std::string::npos) prefix.erase(0, cut + 1);
  std::vector<std::string> words;
  std::istringstream ss(prefix);
  for (std::string w; ss >> w;) words.push_back(w);
  // The word being typed is not yet a complete word of the statement.
  if (!prefix.empty() && !std::isspace(static_cast<unsigned char>(prefix.back())) && !words.empty()) words.pop_back();

  json items = json::array();
  if (words.empty()) {
    if (d.workspace) {
      items.push_back(item("size", kKindKeyword, "size W [x H]: the workspace's size"));
      items.push_back(item("patch", kKindKeyword, "patch \"MATERIAL\" at X, Y [size W [x H]]"));
    } else {
      for (const auto& k : compiler::statement_keywords()) items.push_back(item(k, kKindKeyword, "statement"));
    }
  } else if (words.front() == "like" && words.size() == 1) {
    for (const auto& e : c.library().entries()) {
      items.push_back(item(e.name, kKindModule, e.describes));
      for (const auto& a : e.aliases) items.push_back(item(a, kKindModule, "alias of " + e.name));
    }
  } else if (words.front() == "roughness" && words.size() == 1) {
    for (const auto& l : c.calibration().roughness_levels()) {
      std::ostringstream detail;
      detail << "roughness " << l.value << (l.rationale.empty() ? "" : ": " + l.rationale);
      items.push_back(item(l.name, kKindValue, detail.str()));
    }
  } else if (is_number_text(words.back())) {
    // Only the units the place takes (a length after `period 3.2`; none after `roughness 0.5`).
    std::size_t word_start = std::min(cur.byte, line.size());
    while (word_start > 0 && !std::isspace(static_cast<unsigned char>(line[word_start - 1]))) --word_start;
    const auto dims = dimensions_at(d, cur, word_start);
    for (const auto& u : schema::all_units())
      if (std::find(dims.begin(), dims.end(), u.dimension) != dims.end())
        items.push_back(item(std::string(u.name), kKindUnit, std::string(schema::dimension_name(u.dimension))));
  }
  return items;
}

json hover(const Document& d, const json& position, const compiler::Compiler& c) {
  const Cursor cur = cursor_of(position, *d.source);
  const auto tokens = tokens_of(d);
  auto i = token_at(tokens, cur);
  if (!i) return nullptr;
  if (const std::string name = like_name_at(d, tokens, cur); !name.empty()) {
    const auto* e = c.library().entry(name);
    if (!e) return nullptr;
    std::string text = "**" + e->name + "** (library entry";
    if (!e->family.empty()) text += ", family " + e->family;
    text += ")\n\n";
    if (!e->describes.empty()) text += e->describes + "\n\n";
    text += "`" + e->relative_path + "`";
    if (!e->deprecated_by.empty()) text += "\n\ndeprecated: use `" + e->deprecated_by + "`";
    return {{"contents", {{"kind", "markdown"}, {"value", text}}}};
  }
  // On a unit, the number before it.
  if (tokens[*i].kind == TokenKind::Word && *i > 0 && tokens[*i - 1].kind == TokenKind::Number &&
      tokens[*i - 1].location.line == tokens[*i].location.line)
    --*i;
  if (tokens[*i].kind != TokenKind::Number || !d.compiled || !d.compiled->program) return nullptr;
  const auto& loc = tokens[*i].location;
  const std::string key = d.name + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column);
  std::string lines;
  for (const auto& pv : d.compiled->program->provenance) {
    // The key, not followed by another digit (":5:1" is not ":5:13").
    for (auto at = pv.source.find(key); at != std::string::npos; at = pv.source.find(key, at + 1)) {
      const auto after = at + key.size();
      if (after < pv.source.size() && std::isdigit(static_cast<unsigned char>(pv.source[after]))) continue;
      const std::string value = pv.si_unit.empty() ? "" : schema::display_value(pv.value_si, pv.si_unit);
      lines += pv.parameter + "  " + value + "  " + pv.layer + "  " + pv.source;
      if (!pv.stated.empty()) lines += "  (" + pv.stated + ")";
      lines += "\n";
      break;
    }
  }
  if (lines.empty()) return nullptr;
  const auto start = static_cast<std::size_t>(loc.column - 1);
  const std::string_view text = d.source->line_text(loc.line);
  return {{"contents", {{"kind", "markdown"}, {"value", "```text\n" + lines + "```"}}},
          {"range",
           {{"start", {{"line", loc.line - 1}, {"character", utf16_units(text, start)}}},
            {"end", {{"line", loc.line - 1}, {"character", utf16_units(text, start + static_cast<std::size_t>(loc.length))}}}}}};
}

json definition(const Document& d, const json& position, const compiler::Compiler& c) {
  const Cursor cur = cursor_of(position, *d.source);
  const std::string name = like_name_at(d, tokens_of(d), cur);
  const auto* e = name.empty() ? nullptr : c.library().entry(name);
  if (!e) return nullptr;
  // The entry's `material "NAME" {` line, where a reader starts.
  int line = 0;
  std::ifstream in(e->file);
  int n = 0;
  for (std::string text; std::getline(in, text) && n < 100000; ++n) {
    const auto first = text.find_first_not_of(" \t");
    if (first != std::string::npos && text.compare(first, 9, "material ") == 0) {
      line = n;
      break;
    }
  }
  const json pos = {{"line", line}, {"character", 0}};
  return {{"uri", uri_of_path(std::filesystem::absolute(e->file).string())}, {"range", {{"start", pos}, {"end", pos}}}};
}

}  // namespace sandpaper::lsp
