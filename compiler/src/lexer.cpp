#include "sandpaper/compiler/lexer.hpp"

#include <cctype>
#include <charconv>

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
        while (src_[b] != '%' && pos_ < src_.size() && is_word_char(src_[pos_])) advance();
        push(TokenKind::Word, src_.substr(b, pos_ - b), line_, col, static_cast<int>(pos_ - b));
      } else {
        diags_.error("E0102", loc(line_, col_, 1), std::string("unexpected character '") + c + "'",
                               "remove it; words, numbers with units, \"strings\", { } and ; are what a material file holds");
        advance();
      }
    }
    push(TokenKind::End, "", line_, col_, 1);
    push(TokenKind::Eof, "", line_, col_, 1);
    return std::move(tokens_);
  }

 private:
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
