// sandpaper-lab-post: sends one JSON POST over a connection it opened before, as a page that has
// loaded sends a slider move, and prints the guest's CLOCK_MONOTONIC (the clock of the lab
// device's logs) just before the request leaves and once the answer is in. A shell in the TCG guest
// takes tens of milliseconds to start a program or read /proc/timer_list, more than the latency the
// lab measures (usb-lab/scenarios/studio.sh).
#include <httplib.h>
#include <time.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <string>

namespace {

std::int64_t monotonic_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Sends one JSON POST and prints when it left and when the answer came (CLOCK_MONOTONIC, ns)"};
  std::string host = "127.0.0.1", path, body, answer_file, warm_path = "/";
  int port = 0;
  app.add_option("--host", host)->capture_default_str();
  app.add_option("--port", port)->required()->check(CLI::Range(1, 65535));
  app.add_option("--path", path, "the request's path, e.g. /api/parameter")->required();
  app.add_option("--json", body, "the request's body")->required();
  app.add_option("--warm", warm_path, "GET this first on the same connection, outside the timing")->capture_default_str();
  app.add_option("--answer", answer_file, "write the answer's body here");
  CLI11_PARSE(app, argc, argv);

  httplib::Client client(host, port);
  client.set_keep_alive(true);
  client.set_tcp_nodelay(true);  // as browsers send: a request's body does not wait for an ACK of its headers
  client.set_connection_timeout(10);
  client.set_read_timeout(30);
  if (auto warm = client.Get(warm_path); !warm) {
    std::cerr << "sandpaper-lab-post: cannot reach " << host << ":" << port << ": " << httplib::to_string(warm.error()) << "\n";
    return 1;
  }
  // A second GET on the open connection: the round trip of a request that does no work.
  const std::int64_t get_sent = monotonic_ns();
  if (auto again = client.Get(warm_path); !again) return 1;
  const std::int64_t get_answered = monotonic_ns();
  const std::int64_t sent = monotonic_ns();
  auto answer = client.Post(path, body, "application/json");
  const std::int64_t answered = monotonic_ns();
  if (!answer) {
    std::cerr << "sandpaper-lab-post: POST " << path << " failed: " << httplib::to_string(answer.error()) << "\n";
    return 1;
  }
  if (!answer_file.empty()) std::ofstream(answer_file) << answer->body;
  std::cout << "get_round_trip_ns=" << get_answered - get_sent << "\nsent_ns=" << sent << "\nanswered_ns=" << answered
            << "\nstatus=" << answer->status << "\n";
  return answer->status == 200 ? 0 : 1;
}
