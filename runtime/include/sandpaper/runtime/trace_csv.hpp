#pragma once
// The trace file `sandpaper run --trace` writes and `--replay` reads: CSV with the header
// t_s,x_m,y_m,force_x_N,force_y_N and one row per tick (s, m, m, N, N). Numbers are written with 17
// significant digits, so a trace read back gives the very doubles that were recorded.
#include <string>
#include <vector>

#include "sandpaper/runtime/recording_device.hpp"

namespace sandpaper::runtime {

std::string format_trace_csv(const std::vector<TickRecord>& records);
// Throws std::invalid_argument naming the line for a missing or different header, a row without
// five numbers, or a non-finite number. Accepts traces written with fewer digits (older builds).
std::vector<TickRecord> parse_trace_csv(const std::string& text);

}  // namespace sandpaper::runtime
