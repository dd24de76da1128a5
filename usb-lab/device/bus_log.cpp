#include "bus_log.hpp"

#include <time.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace sandpaper::usb_lab {

std::int64_t monotonic_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

namespace {

template <class Write>
void write_atomically(const std::string& path, Write write) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    write(out);
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

void write_report_log(const std::string& path, std::span<const ReportRecord> records) {
  write_atomically(path, [&](std::ofstream& out) {
    out << "t_ns,pipe,type,bytes\n";
    char hex[3];
    for (const ReportRecord& r : records) {
      out << r.t_ns << ',' << static_cast<char>(r.pipe) << ',' << int(r.type) << ',';
      const std::size_t n = std::min<std::size_t>(r.length, sizeof r.bytes);
      for (std::size_t i = 0; i < n; ++i) {
        std::snprintf(hex, sizeof hex, "%02x", r.bytes[i]);
        out << hex;
      }
      out << '\n';
    }
  });
}

void write_torque_log(const std::string& path, std::span<const TorqueRecord> records) {
  write_atomically(path, [&](std::ofstream& out) {
    out << "t_ns,axis,torque\n";
    for (const TorqueRecord& r : records) out << r.t_ns << ',' << r.axis << ',' << r.torque << '\n';
  });
}

}  // namespace sandpaper::usb_lab
