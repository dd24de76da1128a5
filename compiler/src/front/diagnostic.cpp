#include "sandpaper/compiler/diagnostic.hpp"

#include <algorithm>

#include "sandpaper/schema/diagnostic_codes.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/no_coverage.hpp"

namespace sandpaper::compiler {

Diagnostic& Diagnostics::error(schema::Code code, SourceLocation loc, std::string message, std::string suggestion) {
  return add(Severity::Error, code, std::move(loc), std::move(message), std::move(suggestion));
}

Diagnostic& Diagnostics::warning(schema::Code code, SourceLocation loc, std::string message, std::string suggestion) {
  return add(Severity::Warning, code, std::move(loc), std::move(message), std::move(suggestion));
}

Diagnostic& Diagnostics::accepted(schema::Code code, SourceLocation loc, std::string message, std::string suggestion) {
  return add(Severity::Note, code, std::move(loc), std::move(message), std::move(suggestion));
}

bool Diagnostics::error_limit_reached() const noexcept { return errors_ >= schema::limits::kMaxErrorsPerFile; }

Diagnostic& Diagnostics::add(Severity severity, schema::Code code, SourceLocation loc, std::string message,
                             std::string suggestion) {
  const bool is_error = severity == Severity::Error;
  // The table knows whether a code is an error or a warning; raising it as the other would show
  // users a severity its documentation contradicts: that is Sandpaper's bug, whatever the input.
  if ((code.severity() == schema::DiagnosticSeverity::Error) != is_error)
    throw InternalError("diagnostic code " + std::string(code.text()) + " raised with the wrong severity");
  std::size_t& kept = is_error ? errors_ : warnings_;
  const std::size_t limit = is_error ? schema::limits::kMaxErrorsPerFile : schema::limits::kMaxWarningsPerFile;
  if (kept < limit) {
    ++kept;
    list_.push_back({std::string(code.text()), severity, std::move(loc), std::move(message), std::move(suggestion), {}});
    return list_.back();
  }
  drop(is_error, std::move(loc), 1);
  scratch_ = {};
  return scratch_;
}

// Past the limit: one summary entry, its count kept current, and nothing else stored.
void Diagnostics::drop(bool is_error, SourceLocation loc, std::size_t count) {
  std::size_t& dropped = is_error ? dropped_errors_ : dropped_warnings_;
  std::size_t& summary = is_error ? summary_error_ : summary_warning_;
  const std::size_t limit = is_error ? schema::limits::kMaxErrorsPerFile : schema::limits::kMaxWarningsPerFile;
  dropped += count;
  if (summary == SIZE_MAX) {
    summary = list_.size();
    list_.push_back({is_error ? "E0009" : "W0009", is_error ? Severity::Error : Severity::Warning, std::move(loc), {},
                     is_error ? "fix the errors above first; the rest are often consequences of them"
                              : "fix the warnings above first, or compile the parts separately",
                     {}});
  }
  list_[summary].message = "too many " + std::string(is_error ? "errors" : "warnings") + ": " +
                           std::to_string(dropped) + " more not shown (at most " + std::to_string(limit) +
                           " are reported)";
}

void Diagnostics::append(const Diagnostics& other) {
  for (const auto& d : other.list_) {
    if (d.code == "E0009" || d.code == "W0009") continue;  // recounted here
    Diagnostic& added = add(d.severity, schema::Code::of(d.code), d.location, d.message, d.suggestion);
    added.notes = d.notes;
  }
  if (other.dropped_errors_ > 0) drop(true, other.list_[other.summary_error_].location, other.dropped_errors_);
  if (other.dropped_warnings_ > 0) drop(false, other.list_[other.summary_warning_].location, other.dropped_warnings_);
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

// The source line with a gutter, and a caret line under the location (Souffle/clang style). A long
// line is clipped to a window around the caret, marked with "...", so that a 40 KB line echoed under
// each of its errors cannot grow the output with the square of its length.
void append_excerpt(std::string& out, const SourceLocation& loc) {
  if (!loc.file || loc.line <= 0) return;
  std::string_view text = loc.file->line_text(loc.line);
  std::size_t caret = static_cast<std::size_t>(std::max(1, loc.column) - 1);
  std::size_t width = static_cast<std::size_t>(std::max(1, loc.length));
  std::string_view before, after;
  constexpr std::size_t kWindow = schema::limits::kMaxEchoedLineBytes;
  if (text.size() > kWindow) {
    const auto boundary = [&](std::size_t i) {  // back to the start of a UTF-8 character
      while (i > 0 && i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) --i;
      return i;
    };
    std::size_t begin = boundary(caret > kWindow / 3 ? caret - kWindow / 3 : 0);
    std::size_t end = boundary(std::min(text.size(), begin + kWindow));
    if (caret > text.size()) caret = text.size();
    if (begin > 0) before = "...";
    if (end < text.size()) after = "...";
    text = text.substr(begin, end - begin);
    caret = caret - begin + before.size();
    width = std::min(width, text.size() + before.size() + 1 - std::min(caret, text.size() + before.size()));
  }
  std::string num = std::to_string(loc.line);
  std::string pad(num.size(), ' ');
  out += " " + num + " | " + std::string(before) + std::string(text) + std::string(after) + "\n";
  out += " " + pad + " | ";
  // Keep tabs as tabs so the caret lines up under the same characters in a terminal.
  for (std::size_t i = 0; i < caret; ++i) {
    const std::size_t idx = i - std::min(i, before.size());
    out += (i >= before.size() && idx < text.size() && text[idx] == '\t') ? '\t' : ' ';
  }
  out += '^';
  for (std::size_t i = 1; i < std::max<std::size_t>(1, width); ++i) out += '~';
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

namespace {

// Levenshtein distance of a and b when it is at most `bound`; otherwise some value over `bound`,
// returned as soon as a whole row is over it (a row's minimum never falls). `rows` is scratch, kept
// by the caller across candidates. Uninstrumented: the fuzzing build's per-cell comparisons in this
// loop were a fifth of the material target's time on typos (docs/RELIABILITY.md).
SANDPAPER_NO_COVERAGE std::size_t bounded_edit_distance(std::string_view a, std::string_view b, std::size_t bound,
                                                        std::vector<std::size_t>& rows) {
  const std::size_t n = b.size() + 1;
  rows.resize(2 * n);
  std::size_t* prev = rows.data();
  std::size_t* cur = prev + n;
  for (std::size_t j = 0; j < n; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    std::size_t row_min = i;
    for (std::size_t j = 1; j < n; ++j) {
      const std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      const std::size_t del = prev[j] + 1, ins = cur[j - 1] + 1;
      std::size_t d = sub < del ? sub : del;
      d = d < ins ? d : ins;
      cur[j] = d;
      row_min = d < row_min ? d : row_min;
    }
    if (row_min > bound) return bound + 1;
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::size_t length_gap(std::string_view a, std::string_view b) {
  return a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> rows;
  // The distance is never over the longer length, so this bound never cuts the walk short.
  return bounded_edit_distance(a, b, std::max(a.size(), b.size()), rows);
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  // A third of the word's length (at least 1, at most 3) keeps suggestions to plausible typos.
  const std::size_t limit = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  std::vector<std::size_t> rows;
  const std::string* best = nullptr;
  std::size_t best_d = limit + 1;  // only a candidate within the limit is ever suggested
  for (const auto& c : candidates) {
    // The distance is at least the length gap: a candidate whose gap is over the best distance so far
    // can neither beat it nor tie it with a smaller gap, so it needs no walk.
    const std::size_t gap = length_gap(word, c);
    if (gap > best_d) continue;
    const std::size_t d = bounded_edit_distance(word, c, best_d, rows);
    // On a tie, prefer the candidate closest in length ("N/mn" -> "N/mm", not "N/m").
    if (d < best_d || (d == best_d && best && gap < length_gap(word, *best))) {
      best_d = d;
      best = &c;
    }
  }
  if (!best || best_d == 0 || best_d > limit) return {};
  return *best;
}

}  // namespace sandpaper::compiler
