#pragma once
// Diagnostics are data: a stable code, a severity, where, what, and how to fix it. User errors
// (bad material files) are Diagnostics; internal errors (bugs) are exceptions of type
// InternalError and are never shown as the user's fault.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/compiler/source.hpp"
#include "sandpaper/schema/diagnostic_codes.hpp"

namespace sandpaper::compiler {

enum class Severity { Error, Warning, Note };

struct DiagnosticNote {
  SourceLocation location;
  std::string message;
};

struct Diagnostic {
  std::string code;        // "E0202"; codes are listed in schema/LANGUAGE.md, "Diagnostics"
  Severity severity = Severity::Error;
  SourceLocation location;
  std::string message;     // what is wrong, one line
  std::string suggestion;  // how to fix it, e.g. "did you mean `corduroy`?"; may be empty
  std::vector<DiagnosticNote> notes;  // other places involved, e.g. the first of two conflicting lines
};

// Collects diagnostics in the order they were found, at most schema::limits::kMaxErrorsPerFile
// errors and kMaxWarningsPerFile warnings: past a limit, one E0009 / W0009 says how many more there
// were and the rest are counted, not kept (a hostile file cannot fill memory with diagnostics).
class Diagnostics {
 public:
  // `code` is a literal checked when compiling ("E0202"), or schema::Code::of(text) for one copied
  // from another diagnostic; raising an E code as a warning or a W code as an error is an
  // InternalError. The returned reference may be a scratch entry (past the limit); notes added to it
  // are dropped.
  Diagnostic& error(schema::Code code, SourceLocation loc, std::string message, std::string suggestion = {});
  Diagnostic& warning(schema::Code code, SourceLocation loc, std::string message, std::string suggestion = {});
  // A warning the material accepts (`accept CODE "reason"`): kept as a note with the warning's
  // code, so that it is shown but neither counted as a warning nor listed in the patch program.
  Diagnostic& accepted(schema::Code code, SourceLocation loc, std::string message, std::string suggestion = {});
  void append(const Diagnostics& other);
  bool has_errors() const noexcept { return errors_ > 0; }
  // True once errors are no longer kept: a phase may stop looking for more.
  bool error_limit_reached() const noexcept;
  const std::vector<Diagnostic>& all() const noexcept { return list_; }

 private:
  Diagnostic& add(Severity severity, schema::Code code, SourceLocation loc, std::string message,
                  std::string suggestion);
  void drop(bool is_error, SourceLocation loc, std::size_t count);
  std::vector<Diagnostic> list_;
  std::size_t errors_ = 0, warnings_ = 0;
  std::size_t dropped_errors_ = 0, dropped_warnings_ = 0;
  std::size_t summary_error_ = SIZE_MAX, summary_warning_ = SIZE_MAX;  // index of the E0009 / W0009 entry
  Diagnostic scratch_;
};

// Clang-style text: "file:line:col: error[E0202]: message", the source line, a caret under the
// offending text, then "help: suggestion" and any notes, each with its own caret.
std::string format_diagnostic(const Diagnostic& d);
std::string format_diagnostics(const Diagnostics& ds);

// A bug in Sandpaper, not in the user's input.
struct InternalError : std::logic_error {
  using std::logic_error::logic_error;
};

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);
// The candidate closest to `word` if it is close enough to be a likely typo; empty otherwise.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace sandpaper::compiler
