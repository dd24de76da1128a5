// What `sandpaper lsp` reads from its editor (editors/lsp): a stream of framed JSON-RPC messages, run
// through the same serve() loop as the CLI with the shipped compiler behind it. Checked: serve()
// returns 0 or 1 and throws nothing, and everything it writes is framed JSON-RPC 2.0 (a response
// with an id, or a notification with a method), whatever came in.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/lsp/jsonrpc.hpp"
#include "sandpaper/lsp/server.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::ostringstream out, log;
  const int status = lsp::serve(in, out, log, fuzz::shipped_compiler());
  fuzz::check(status == 0 || status == 1, "serve() returned " + std::to_string(status));
  std::istringstream replies(out.str());
  try {
    while (auto body = lsp::read_message(replies)) {
      const auto m = nlohmann::json::parse(*body, nullptr, false);
      fuzz::check(!m.is_discarded() && m.is_object() && m.value("jsonrpc", "") == "2.0",
                  "the server wrote a message that is not JSON-RPC: " + body->substr(0, 200));
      fuzz::check(m.contains("id") != m.contains("method"), "neither a response nor a notification: " + body->substr(0, 200));
    }
  } catch (const lsp::FramingError& e) {
    fuzz::fail(std::string("the server's own output is badly framed: ") + e.what());
  }
  return 0;
}
