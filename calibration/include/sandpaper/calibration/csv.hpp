#pragma once
// A small, strict CSV reader for measurement files (magnitude estimates, force-gauge readings).
// Format: comma-separated, first non-comment line is the header; fields may be double-quoted with ""
// for a literal quote (RFC 4180) but may not span lines; spaces around unquoted fields are trimmed;
// blank lines and lines starting with '#' are skipped (the shipped examples say in '#' lines how
// they were made). Every row must have as many fields as the header.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sandpaper::calibration {

struct CsvRow {
  int line = 0;                     // 1-based line in the file
  std::vector<std::string> fields;  // one per header column
};

struct CsvTable {
  std::string path;                  // as given, for diagnostics
  int header_line = 0;
  std::vector<std::string> columns;  // header names, trimmed
  std::vector<CsvRow> rows;
  // Index of the column named `name` (exact, case-sensitive), or nullopt.
  std::optional<std::size_t> column(std::string_view name) const;
};

// Parses `text`; `path` only names the file in diagnostics. Throws FitError (file:line) for a
// missing header, a duplicated column, a row with the wrong number of fields or a bad quote.
CsvTable parse_csv(std::string_view text, const std::string& path);
// Reads and parses a file. Throws FitError (line 0) if it cannot be read.
CsvTable read_csv(const std::filesystem::path& path);

// Columns that must be present; throws FitError at the header line naming the missing ones and the
// full list required.
void require_columns(const CsvTable& t, const std::vector<std::string>& required);

// The field as a finite number, 0 or 1e-12 to 1e12 in magnitude (std::from_chars, '.' decimal
// point, optional leading '+'). Throws FitError at the row's line naming the column and the text.
double number_field(const CsvTable& t, const CsvRow& row, std::size_t column);

}  // namespace sandpaper::calibration
