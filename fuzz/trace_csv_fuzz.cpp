// Trace files (`sandpaper run --trace` writes them, `--replay` reads them; runtime/trace_csv.hpp):
// parse_trace_csv, whose records must come back exactly through format_trace_csv (17 significant
// digits). Expected rejection: std::invalid_argument.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "sandpaper/runtime/trace_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<runtime::TickRecord> records;
  try {
    records = runtime::parse_trace_csv(text);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  const std::string written = runtime::format_trace_csv(records);
  std::vector<runtime::TickRecord> again;
  try {
    again = runtime::parse_trace_csv(written);
  } catch (const std::invalid_argument& e) {
    fuzz::fail(std::string("a written trace does not read back: ") + e.what());
  }
  fuzz::check(again.size() == records.size(), "a trace read back has another number of rows");
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto &a = records[i], &b = again[i];
    fuzz::check(a.t_s == b.t_s && a.position_m == b.position_m && a.force_N == b.force_N,
                "a trace read back differs at row " + std::to_string(i + 1));
  }
  return 0;
}
