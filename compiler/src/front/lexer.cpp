#include "sandpaper/compiler/lexer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <string_view>

#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {
namespace {

bool is_word_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '%'; }
bool is_word_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '/' || c == '*';
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }

class Lexer {
 public:
  Lexer(const std::shared_ptr<const SourceFile>& file, Diagnostics& diags, LexOptions options)
      : file_(file), src_(file->text), diags_(diags), options_(options) {}

  std::vector<Token> run() {
    while (pos_ < src_.size()) {
      char c = src_[pos_];
      if (c == '\n' || c == ';') {
        add(TokenKind::End, std::string(1, c), 1);
        advance();
      } else if (c == ' ' || c == '\t' || c == '\r') {
        advance();
      } else if (c == '#') {
        while (pos_ < src_.size() && src_[pos_] != '\n') advance();
      } else if (c == '{') {
        add(TokenKind::LBrace, "{", 1);
        advance();
      } else if (c == '}') {
        add(TokenKind::RBrace, "}", 1);
        advance();
      } else if (c == ',' && options_.commas) {
        add(TokenKind::Comma, ",", 1);
        advance();
      } else if (c == '"') {
        string();
      } else if (is_digit(c) || c == '.' ||
                 ((c == '-' || c == '+') && pos_ + 1 < src_.size() &&
                  (is_digit(src_[pos_ + 1]) || src_[pos_ + 1] == '.'))) {
        number();
      } else if (is_word_start(c)) {
        std::size_t b = pos_;
        int col = col_;
        advance();  // the start character, which may be '%' (not a word character after the start)
        // A ':' between word characters joins a root's id to an entry name (like world:corduroy).
        while (src_[b] != '%' && pos_ < src_.size() &&
               (is_word_char(src_[pos_]) ||
                (src_[pos_] == ':' && pos_ + 1 < src_.size() && is_word_start(src_[pos_ + 1]) && src_[pos_ + 1] != '%')))
          advance();
        push(TokenKind::Word, src_.substr(b, pos_ - b), line_, col, static_cast<int>(pos_ - b));
      } else {
        unexpected();
      }
    }
    push(TokenKind::End, "", line_, col_, 1);
    push(TokenKind::Eof, "", line_, col_, 1);
    return std::move(tokens_);
  }

 private:
  bool starts_token(std::size_t i) const {
    const char c = src_[i];
    if (c == '\n' || c == ';' || c == ' ' || c == '\t' || c == '\r' || c == '#' || c == '{' || c == '}' || c == '"' ||
        is_digit(c) || c == '.' || is_word_start(c) || (c == ',' && options_.commas))
      return true;
    return (c == '-' || c == '+') && i + 1 < src_.size() && (is_digit(src_[i + 1]) || src_[i + 1] == '.');
  }

  // A run of characters that start no token is one error, not one per byte: a line of 40,000 stray
  // characters gives one diagnostic. The text is valid UTF-8 here (lex() checked).
  void unexpected() {
    const std::size_t b = pos_;
    const int col = col_;
    do advance();
    while (pos_ < src_.size() && !starts_token(pos_));
    const std::size_t n = pos_ - b;
    // Quote at most 16 bytes, cut at a character boundary.
    std::size_t shown = std::min<std::size_t>(n, 16);
    while (shown < n && (static_cast<unsigned char>(src_[b + shown]) & 0xC0) == 0x80) --shown;
    const std::string quoted = src_.substr(b, shown) + (shown < n ? "..." : "");
    const auto chars = std::count_if(src_.begin() + static_cast<std::ptrdiff_t>(b),
                                     src_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                     [](char ch) { return (static_cast<unsigned char>(ch) & 0xC0) != 0x80; });
    const bool one = chars == 1;
    diags_.error("E0102", loc(line_, col, static_cast<int>(std::min<std::size_t>(n, 1u << 20))),
                 std::string(one ? "unexpected character '" : "unexpected characters '") + quoted + "'",
                 "remove it; words, numbers with units, \"strings\", { } and ; are what a material file holds");
  }

  // number := [+-]? digits ('.' digits?)? exponent? | [+-]? '.' digits exponent?
  void number() {
    std::size_t b = pos_;
    int col = col_;
    if (src_[pos_] == '-' || src_[pos_] == '+') advance();
    while (pos_ < src_.size() && is_digit(src_[pos_])) advance();
    if (pos_ < src_.size() && src_[pos_] == '.') {
      advance();
      while (pos_ < src_.size() && is_digit(src_[pos_])) advance();
    }
    // An exponent only if digits follow, so "2em" stays "2" "em" rather than a broken number.
    if (pos_ < src_.size() && (src_[pos_] == 'e' || src_[pos_] == 'E')) {
      std::size_t q = pos_ + 1;
      if (q < src_.size() && (src_[q] == '+' || src_[q] == '-')) ++q;
      if (q < src_.size() && is_digit(src_[q])) {
        while (pos_ < q) advance();
        while (pos_ < src_.size() && is_digit(src_[pos_])) advance();
      }
    }
    std::string text = src_.substr(b, pos_ - b);
    double v = 0;
    const char* first = text.data() + (text[0] == '+' ? 1 : 0);
    auto [ptr, ec] = std::from_chars(first, text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size()) {
      diags_.error("E0103", loc(line_, col, static_cast<int>(text.size())), "malformed number '" + text + "'",
                   "write numbers as 3, 3.2, 0.5 or 2e-3");
      return;
    }
    Token t{TokenKind::Number, text, v, loc(line_, col, static_cast<int>(text.size()))};
    tokens_.push_back(std::move(t));
  }

  void string() {
    int col = col_;
    int line = line_;
    std::size_t b = pos_;
    advance();  // opening quote
    std::string value;
    while (pos_ < src_.size() && src_[pos_] != '"' && src_[pos_] != '\n') {
      if (src_[pos_] == '\\' && pos_ + 1 < src_.size() && (src_[pos_ + 1] == '"' || src_[pos_ + 1] == '\\')) advance();
      value += src_[pos_];
      advance();
    }
    if (pos_ >= src_.size() || src_[pos_] != '"') {
      diags_.error("E0101", loc(line, col, static_cast<int>(pos_ - b)), "unterminated string",
                   "close the string with \" on the same line");
      // Keep the text as a string so the statement around it does not report a second error.
      push(TokenKind::String, std::move(value), line, col, static_cast<int>(pos_ - b));
      return;
    }
    advance();  // closing quote
    push(TokenKind::String, std::move(value), line, col, static_cast<int>(pos_ - b));
  }

  void advance() {
    if (src_[pos_] == '\n') {
      ++line_;
      col_ = 1;
    } else {
      ++col_;
    }
    ++pos_;
  }
  SourceLocation loc(int line, int col, int len) const { return SourceLocation{file_, line, col, len}; }
  void add(TokenKind k, std::string text, int len) { push(k, std::move(text), line_, col_, len); }
  void push(TokenKind k, std::string text, int line, int col, int len) {
    tokens_.push_back(Token{k, std::move(text), 0, loc(line, col, len)});
  }

  std::shared_ptr<const SourceFile> file_;
  const std::string& src_;
  Diagnostics& diags_;
  LexOptions options_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int col_ = 1;
};

}  // namespace

std::vector<Token> lex(const std::shared_ptr<const SourceFile>& file, Diagnostics& diags, LexOptions options) {
  const auto nothing = [&] {
    const SourceLocation at{file, 1, 1, 1};
    return std::vector<Token>{Token{TokenKind::End, "", 0, at}, Token{TokenKind::Eof, "", 0, at}};
  };
  // Bounded before anything is built from the text: a 50 MB file must not become 50 M tokens.
  if (file->text.size() > schema::limits::kMaxSourceBytes) {
    diags.error("E0105", SourceLocation{file, 0, 0, 1},
                "the file is " + std::to_string(file->text.size()) + " bytes, over the limit of " +
                    std::to_string(schema::limits::kMaxSourceBytes) + " bytes for a material or workspace file",
                "split it into several files, or keep large data in an image that `heightmap` reads");
    return nothing();
  }
  // Names and strings end up in JSON and patch files, which hold only UTF-8: refuse other bytes at
  // their place rather than fail later in a JSON writer. One error per line is enough.
  std::string_view rest = file->text;
  std::size_t offset = 0, bad = 0;
  bool any_bad = false;
  while (!schema::is_valid_utf8(rest, bad)) {
    any_bad = true;
    const std::size_t at = offset + bad;
    const auto line_it = std::upper_bound(file->line_starts.begin(), file->line_starts.end(), at);
    const auto line = static_cast<int>(line_it - file->line_starts.begin());
    const std::size_t line_start = file->line_starts[static_cast<std::size_t>(line - 1)];
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(file->text[at])));
    diags.error("E0104", SourceLocation{file, line, static_cast<int>(at - line_start + 1), 1},
                std::string("byte ") + hex + " is not UTF-8 text",
                "save the file as UTF-8; material and workspace files hold UTF-8 text only");
    if (diags.error_limit_reached()) break;
    const std::size_t next_line =
        line_it == file->line_starts.end() ? file->text.size() : static_cast<std::size_t>(*line_it);
    offset = next_line;
    rest = std::string_view(file->text).substr(next_line);
  }
  if (any_bad) return nothing();
  return Lexer(file, diags, options).run();
}

const char* token_kind_name(TokenKind k) {
  switch (k) {
    case TokenKind::Word: return "a word";
    case TokenKind::Number: return "a number";
    case TokenKind::String: return "a string";
    case TokenKind::LBrace: return "'{'";
    case TokenKind::RBrace: return "'}'";
    case TokenKind::Comma: return "','";
    case TokenKind::End: return "the end of the statement";
    case TokenKind::Eof: return "the end of the file";
  }
  return "?";
}

}  // namespace sandpaper::compiler
