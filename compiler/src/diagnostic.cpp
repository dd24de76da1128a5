#include "sandpaper/compiler/diagnostic.hpp"

#include <algorithm>

namespace sandpaper::compiler {

Diagnostic& Diagnostics::error(std::string code, SourceLocation loc, std::string message, std::string suggestion) {
  ++errors_;
  list_.push_back({std::move(code), Severity::Error, std::move(loc), std::move(message), std::move(suggestion), {}});
  return list_.back();
}

Diagnostic& Diagnostics::warning(std::string code, SourceLocation loc, std::string message, std::string suggestion) {
  list_.push_back({std::move(code), Severity::Warning, std::move(loc), std::move(message), std::move(suggestion), {}});
  return list_.back();
}

void Diagnostics::append(const Diagnostics& other) {
  for (const auto& d : other.list_) {
    list_.push_back(d);
    if (d.severity == Severity::Error) ++errors_;
  }
}

namespace {

const char* severity_name(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "?";
}

// The source line with a gutter, and a caret line under the location (Souffle/clang style).
void append_excerpt(std::string& out, const SourceLocation& loc) {
  if (!loc.file || loc.line <= 0) return;
  std::string_view text = loc.file->line_text(loc.line);
  std::string num = std::to_string(loc.line);
  std::string pad(num.size(), ' ');
  out += " " + num + " | " + std::string(text) + "\n";
  out += " " + pad + " | ";
  // Keep tabs as tabs so the caret lines up under the same characters in a terminal.
  int col = std::max(1, loc.column);
  for (int i = 1; i < col; ++i) {
    auto idx = static_cast<std::size_t>(i - 1);
    out += (idx < text.size() && text[idx] == '\t') ? '\t' : ' ';
  }
  out += '^';
  for (int i = 1; i < loc.length; ++i) out += '~';
  out += '\n';
}

}  // namespace

std::string format_diagnostic(const Diagnostic& d) {
  std::string out = d.location.str() + ": " + severity_name(d.severity) + "[" + d.code + "]: " + d.message + "\n";
  append_excerpt(out, d.location);
  if (!d.suggestion.empty()) out += " = help: " + d.suggestion + "\n";
  for (const auto& n : d.notes) {
    out += n.location.str() + ": note: " + n.message + "\n";
    append_excerpt(out, n.location);
  }
  return out;
}

std::string format_diagnostics(const Diagnostics& ds) {
  std::string out;
  for (const auto& d : ds.all()) out += format_diagnostic(d);
  return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const auto& c : candidates) {
    std::size_t d = edit_distance(word, c);
    // On a tie, prefer the candidate closest in length ("N/mn" -> "N/mm", not "N/m").
    auto len_gap = [&](const std::string& s) { return s.size() > word.size() ? s.size() - word.size() : word.size() - s.size(); };
    if (d < best_d || (d == best_d && len_gap(c) < len_gap(best))) {
      best_d = d;
      best = c;
    }
  }
  // A third of the word's length (at least 1, at most 3) keeps suggestions to plausible typos.
  std::size_t limit = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  if (best_d == 0 || best_d > limit) return {};
  return best;
}

}  // namespace sandpaper::compiler
