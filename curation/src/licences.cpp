// The licences `library check` knows: SPDX ids (https://spdx.org/licenses/) that suit data and
// creative content, and the common software ones. An id outside the list is a warning (W0603), not
// an error: SPDX has hundreds; the list catches misspellings of the likely ones.
#include "sandpaper/curation/licences.hpp"

#include <cctype>
#include <fstream>

#include "sandpaper/compiler/diagnostic.hpp"

namespace sandpaper::curation {

const std::vector<std::string>& known_licences() {
  static const std::vector<std::string> ids{
      "CC0-1.0",      "CC-BY-4.0",     "CC-BY-SA-4.0", "CC-BY-NC-4.0", "CC-BY-NC-SA-4.0", "CC-BY-ND-4.0",
      "CC-BY-NC-ND-4.0", "CC-BY-3.0",  "CC-BY-SA-3.0", "CC-PDDC",      "PDDL-1.0",         "ODC-By-1.0",
      "ODbL-1.0",     "Unlicense",     "MIT",          "Apache-2.0",   "BSD-2-Clause",     "BSD-3-Clause",
      "GPL-2.0-or-later", "GPL-3.0-or-later", "LGPL-3.0-or-later", "MPL-2.0"};
  return ids;
}

bool known_licence(const std::string& id) {
  if (id.rfind("LicenseRef-", 0) == 0 && id.size() > 11) return true;
  for (const auto& k : known_licences())
    if (k == id) return true;
  return false;
}

std::string licence_guess(const std::string& id) {
  // A version left off ("CC0", "CC-BY-SA") is the likeliest slip: the list gives the newest first.
  for (const auto& k : known_licences())
    if (k.size() > id.size() + 1 && k.compare(0, id.size(), id) == 0 && k[id.size()] == '-') return k;
  return compiler::closest_match(id, known_licences());
}

namespace {

bool id_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.'; }

class ExpressionParser {
 public:
  explicit ExpressionParser(const std::string& t) : t_(t) {}

  LicenceExpression run() {
    skip();
    if (pos_ >= t_.size()) return fail("the licence is empty");
    expression(0);
    skip();
    if (r_.ok() && pos_ < t_.size()) fail("expected AND, OR or WITH here");
    return r_;
  }

 private:
  // expression := and-expr ('OR' and-expr)*
  void expression(int depth) {
    if (depth > 32) return (void)fail("parentheses nested too deep");
    and_expr(depth);
    while (r_.ok() && keyword("OR")) and_expr(depth);
  }
  // and-expr := term ('AND' term)*
  void and_expr(int depth) {
    term(depth);
    while (r_.ok() && keyword("AND")) term(depth);
  }
  // term := '(' expression ')' | simple ['WITH' exception-id]
  void term(int depth) {
    skip();
    if (!r_.ok()) return;
    if (pos_ < t_.size() && t_[pos_] == '(') {
      ++pos_;
      expression(depth + 1);
      skip();
      if (r_.ok() && (pos_ >= t_.size() || t_[pos_] != ')')) fail("expected ')'");
      else if (r_.ok()) ++pos_;
      return;
    }
    auto id = word();
    if (!r_.ok()) return;
    if (id == "AND" || id == "OR" || id == "WITH") return (void)fail("expected a licence id before " + id, pos_ - id.size());
    if (pos_ < t_.size() && t_[pos_] == '+') ++pos_;  // "or later"
    else if (pos_ < t_.size() && t_[pos_] == ':' && id.rfind("DocumentRef-", 0) == 0) {
      ++pos_;
      id = word();
      if (!r_.ok()) return;
      if (id.rfind("LicenseRef-", 0) != 0) return (void)fail("expected LicenseRef-... after the DocumentRef", pos_ - id.size());
    }
    r_.ids.push_back(id);
    if (keyword("WITH")) {
      const auto ex = word();
      if (r_.ok()) r_.exceptions.push_back(ex);
    }
  }
  // idstring := 1*(ALPHA / DIGIT / "-" / ".")
  std::string word() {
    skip();
    const auto start = pos_;
    while (pos_ < t_.size() && id_char(t_[pos_])) ++pos_;
    if (pos_ == start) fail(pos_ < t_.size() ? std::string("unexpected '") + t_[pos_] + "'" : "expected a licence id");
    return t_.substr(start, pos_ - start);
  }
  // The operators are case-sensitive (SPDX 2.3 D.3): "and" is an id, and then an error.
  bool keyword(const char* k) {
    skip();
    const std::string w(k);
    if (t_.compare(pos_, w.size(), w) != 0) return false;
    const auto after = pos_ + w.size();
    if (after < t_.size() && id_char(t_[after])) return false;
    pos_ = after;
    return true;
  }
  void skip() {
    while (pos_ < t_.size() && (t_[pos_] == ' ' || t_[pos_] == '\t')) ++pos_;
  }
  LicenceExpression fail(const std::string& why, std::size_t at = std::string::npos) {
    if (r_.ok()) {
      r_.error = why;
      r_.error_at = at == std::string::npos ? pos_ : at;
    }
    return r_;
  }
  const std::string& t_;
  std::size_t pos_ = 0;
  LicenceExpression r_;
};

}  // namespace

LicenceExpression parse_licence_expression(const std::string& text) { return ExpressionParser(text).run(); }

bool well_formed_licence(const std::string& text) { return parse_licence_expression(text).ok(); }

ImageLicence parse_image_licence(const std::string& text) {
  ImageLicence r;
  int line = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string l = text.substr(start, end - start);
    ++line;
    if (!l.empty() && l.back() == '\r') l.pop_back();
    const auto tag = [&](const std::string& name, std::string& value, int& at) {
      if (l.compare(0, name.size(), name) != 0) return;
      auto v = l.substr(name.size());
      const auto a = v.find_first_not_of(" \t"), b = v.find_last_not_of(" \t");
      value = a == std::string::npos ? std::string() : v.substr(a, b - a + 1);
      at = line;
    };
    tag("SPDX-License-Identifier:", r.licence, r.licence_line);
    tag("SPDX-FileCopyrightText:", r.credit, r.credit_line);
    if (end == text.size()) break;
    start = end + 1;
  }
  return r;
}

std::optional<ImageLicence> read_image_licence(const std::filesystem::path& image) {
  auto sidecar = image;
  sidecar += ".license";
  std::ifstream in(sidecar, std::ios::binary);
  if (!in) return std::nullopt;
  std::string text(64 * 1024, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  auto r = parse_image_licence(text);
  r.sidecar = sidecar;
  return r;
}

}  // namespace sandpaper::curation
