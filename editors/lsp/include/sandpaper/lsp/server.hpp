#pragma once
// `sandpaper lsp`: a Language Server Protocol 3.17 server for material (.hmat) and workspace (.hws)
// files. It publishes the compiler's diagnostics as the text changes, completes statement keywords,
// units, library names and roughness levels, shows `explain`'s line for the number under the cursor,
// and goes from `like NAME` to the library entry's file (docs/EDITORS.md).
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::lsp {

// One open document: its text as the client last sent it, and what that text compiled to.
struct Document {
  std::string uri;
  std::string name;  // the file's path for file: URIs (relative images resolve against its folder), else the URI
  bool workspace = false;  // a .hws file
  std::shared_ptr<const compiler::SourceFile> source;
  std::optional<compiler::CompileResult> compiled;  // materials only; empty for workspaces
};

class LanguageServer {
 public:
  // `compiler` must outlive the server; every document compiles with it (its device, library and
  // calibration).
  explicit LanguageServer(const compiler::Compiler& compiler);

  // One incoming JSON-RPC message (request, notification or response) -> the messages to send back,
  // in order: its response, if it was a request, and any publishDiagnostics notifications.
  std::vector<nlohmann::json> handle(const nlohmann::json& message);

  bool exited() const { return exited_; }
  // LSP's rule: 0 if `shutdown` came before `exit`, else 1.
  int exit_code() const { return shutdown_ ? 0 : 1; }

 private:
  nlohmann::json dispatch(const std::string& method, const nlohmann::json& params, std::vector<nlohmann::json>& out);
  void open(const std::string& uri, std::string text, std::vector<nlohmann::json>& out);
  nlohmann::json diagnostics_of(const Document& d, const compiler::Diagnostics& ds) const;
  const Document& document(const nlohmann::json& params) const;

  const compiler::Compiler& compiler_;
  std::map<std::string, Document> documents_;
  bool initialized_ = false, shutdown_ = false, exited_ = false;
};

// Reads framed messages from `in` and answers on `out` until `exit` or the end of input; notes
// (the readiness line, framing errors) go to `log`. Returns the process's exit status.
int serve(std::istream& in, std::ostream& out, std::ostream& log, const compiler::Compiler& compiler);

}  // namespace sandpaper::lsp
