#pragma once
// JSON-RPC 2.0 framing as the Language Server Protocol uses it on stdio: a header block
// ("Content-Length: N", optionally "Content-Type: ...", each line ended by CRLF), an empty line,
// then N bytes of UTF-8 JSON (LSP 3.17, "Base Protocol").
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace sandpaper::lsp {

// A message body larger than this is refused: a material file is at most 4 MiB
// (schema::limits::kMaxSourceBytes), which JSON escaping can at most quadruple... plus the envelope.
inline constexpr std::size_t kMaxMessageBytes = 20u << 20;
inline constexpr std::size_t kMaxHeaderLineBytes = 1024;
inline constexpr int kMaxHeaderLines = 16;

// The header block is malformed, oversized or cut short: the stream cannot be resynchronised, so
// the server stops (the client restarts it).
struct FramingError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One message's body. nullopt when the input ends cleanly before a message begins; FramingError
// for anything else that is not a well-formed message.
std::optional<std::string> read_message(std::istream& in);

// Writes `message` with its Content-Length header (bytes of its UTF-8 serialisation).
void write_message(std::ostream& out, const nlohmann::json& message);

}  // namespace sandpaper::lsp
