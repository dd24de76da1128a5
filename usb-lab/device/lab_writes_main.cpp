// sandpaper-lab-writes: COUNT blocking writes of one output report to a hidraw node, back to back,
// and the time they took on CLOCK_MONOTONIC: how often the lab's bus carries an interrupt OUT
// transaction when a host keeps the endpoint busy (usb-lab/scenarios/busrate.sh). Each write returns
// once usbhid's OUT transfer is done, so the rate is the bus's, or the device's if it is slower.
//   sandpaper-lab-writes NODE COUNT HEX    prints: writes N seconds S max_gap_ms G min_gap_ms M
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: sandpaper-lab-writes NODE COUNT HEX (the report, its ID byte first)\n");
    return 2;
  }
  const long count = std::strtol(argv[2], nullptr, 10);
  std::vector<unsigned char> report;
  const std::string hex = argv[3];
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    report.push_back(static_cast<unsigned char>(std::strtoul(hex.substr(i, 2).c_str(), nullptr, 16)));
  if (count < 2 || report.empty() || hex.size() % 2 != 0) {
    std::fprintf(stderr, "sandpaper-lab-writes: COUNT must be 2 or more and HEX whole bytes\n");
    return 2;
  }
  const int fd = ::open(argv[1], O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    std::fprintf(stderr, "sandpaper-lab-writes: %s: %s\n", argv[1], std::strerror(errno));
    return 1;
  }
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last = start;
  double min_gap = 1e9, max_gap = 0;
  long done = 0;
  for (; done < count; ++done) {
    if (::write(fd, report.data(), report.size()) != static_cast<ssize_t>(report.size())) {
      std::fprintf(stderr, "sandpaper-lab-writes: write %ld: %s\n", done + 1, std::strerror(errno));
      break;
    }
    const auto now = clock::now();
    if (done > 0) {
      const double gap = std::chrono::duration<double, std::milli>(now - last).count();
      min_gap = std::min(min_gap, gap);
      max_gap = std::max(max_gap, gap);
    }
    last = now;
  }
  ::close(fd);
  const double seconds = std::chrono::duration<double>(last - start).count();
  std::printf("writes %ld seconds %.6f max_gap_ms %.3f min_gap_ms %.3f\n", done, seconds, max_gap, min_gap);
  return done == count ? 0 : 1;
}
