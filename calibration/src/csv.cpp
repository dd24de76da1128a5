// The CSV reader of csv.hpp: one line at a time, quotes within a line only.
#include "sandpaper/calibration/csv.hpp"
#include "sandpaper/schema/input_limits.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sandpaper/calibration/fit_error.hpp"

namespace sandpaper::calibration {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string> split_line(std::string_view line, const std::string& path, int lineno) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string field;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          ++i;
          closed = true;
          break;
        }
        field += line[i++];
      }
      if (!closed)
        throw FitError(path, lineno, "unterminated quoted field (quoted fields may not span lines)");
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i < line.size() && line[i] != ',')
        throw FitError(path, lineno, "text after a closing quote; write \"\" for a quote inside a quoted field");
    } else {
      std::size_t start = i;
      while (i < line.size() && line[i] != ',') ++i;
      field = std::string(trim(line.substr(start, i - start)));
      if (field.find('"') != std::string::npos)
        throw FitError(path, lineno, "a quote inside an unquoted field; quote the whole field and write \"\" for the quote");
    }
    out.push_back(std::move(field));
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return out;
}

}  // namespace

std::optional<std::size_t> CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return i;
  return std::nullopt;
}

CsvTable parse_csv(std::string_view text, const std::string& path) {
  CsvTable t;
  t.path = path;
  int lineno = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lineno;
    std::string_view body = trim(line);
    if (body.empty() || body.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    // Fields reach JSON output and fitted files, which must be UTF-8 (F25); comments are not read.
    if (std::size_t bad = 0; !schema::is_valid_utf8(line, bad)) {
      static const char* hex = "0123456789ABCDEF";
      const auto b = static_cast<unsigned char>(line[bad]);
      throw FitError(path, lineno, "byte " + std::to_string(bad + 1) + " of the line (0x" + std::string{hex[b >> 4], hex[b & 15]} +
                                       ") is not UTF-8; save the file as UTF-8 (a spreadsheet's \"CSV UTF-8\")");
    }
    auto fields = split_line(line, path, lineno);
    if (t.header_line == 0) {
      t.header_line = lineno;
      for (std::size_t i = 0; i < fields.size(); ++i) {
        if (fields[i].empty()) throw FitError(path, lineno, "header column " + std::to_string(i + 1) + " has no name");
        for (std::size_t j = 0; j < i; ++j)
          if (fields[j] == fields[i]) throw FitError(path, lineno, "column `" + fields[i] + "` appears twice in the header");
      }
      t.columns = std::move(fields);
    } else {
      if (fields.size() != t.columns.size())
        throw FitError(path, lineno, std::to_string(fields.size()) + " fields, but the header (line " +
                                         std::to_string(t.header_line) + ") has " + std::to_string(t.columns.size()) +
                                         " columns");
      t.rows.push_back({lineno, std::move(fields)});
    }
    if (end == text.size()) break;
  }
  if (t.header_line == 0) throw FitError(path, 0, "no header line: the file is empty or holds only comments");
  return t;
}

CsvTable read_csv(const std::filesystem::path& path) {
  std::string text;
  try {
    text = schema::read_input_file(path, schema::limits::kMaxTextFileBytes);
  } catch (const schema::InputFileError& e) {
    throw FitError(path.string(), 0, "cannot read the file: " + e.reason);
  }
  return parse_csv(text, path.string());
}

void require_columns(const CsvTable& t, const std::vector<std::string>& required) {
  std::string missing, all;
  for (const auto& c : required) {
    all += (all.empty() ? "" : ",") + c;
    if (!t.column(c)) missing += (missing.empty() ? "`" : ", `") + c + "`";
  }
  if (!missing.empty())
    throw FitError(t.path, t.header_line, "missing column " + missing + "; the header must contain " + all +
                                             " (any order, other columns ignored)");
}

double number_field(const CsvTable& t, const CsvRow& row, std::size_t column) {
  std::string_view s = row.fields[column];
  std::string_view body = s;
  if (!body.empty() && body.front() == '+') body.remove_prefix(1);
  double v = 0;
  auto [p, ec] = std::from_chars(body.data(), body.data() + body.size(), v);
  if (body.empty() || ec != std::errc() || p != body.data() + body.size())
    throw FitError(t.path, row.line, "`" + t.columns[column] + "` is `" + std::string(s) + "`, not a number");
  if (!std::isfinite(v))
    throw FitError(t.path, row.line, "`" + t.columns[column] + "` is `" + std::string(s) + "`, not a finite number");
  if (std::abs(v) > schema::limits::kMaxMeasurement || (v != 0 && std::abs(v) < schema::limits::kMinMeasurement))
    throw FitError(t.path, row.line, "`" + t.columns[column] + "` is `" + std::string(s) +
                                         "`: a number here is 0, or 1e-12 to 1e12 in magnitude (a force in N, a command, "
                                         "a period in mm, an estimate)");
  return v;
}

}  // namespace sandpaper::calibration
