#include "sandpaper/lsp/server.hpp"

#include <filesystem>
#include <istream>
#include <ostream>

#include "sandpaper/compiler/brought_in.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/lsp/features.hpp"
#include "sandpaper/lsp/jsonrpc.hpp"
#include "sandpaper/lsp/text_positions.hpp"
#include "sandpaper/schema/diagnostic_codes.hpp"

namespace sandpaper::lsp {
namespace {

using nlohmann::json;

// JSON-RPC 2.0 and LSP error codes.
constexpr int kParseError = -32700, kInvalidRequest = -32600, kMethodNotFound = -32601, kInvalidParams = -32602;
constexpr int kServerNotInitialized = -32002;

struct RpcError {
  int code;
  std::string message;
};

json error_response(const json& id, int code, const std::string& message) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}};
}

// The folder that holds schema/LANGUAGE.md beside the data, when Sandpaper runs from its source
// tree: diagnostics then link to their row of the table. An installed package has no docs to link.
std::string docs_root(const compiler::Compiler& c) {
  const auto root = c.library().directory().parent_path();
  std::error_code ec;
  return std::filesystem::exists(root / "schema/LANGUAGE.md", ec) ? root.string() : std::string();
}

}  // namespace

LanguageServer::LanguageServer(const compiler::Compiler& compiler) : compiler_(compiler) {}

std::vector<json> LanguageServer::handle(const json& message) {
  std::vector<json> out;
  if (!message.is_object()) {
    out.push_back(error_response(nullptr, kInvalidRequest, "a JSON-RPC message is an object"));
    return out;
  }
  const auto method = message.find("method");
  const auto id = message.find("id");
  const bool request = id != message.end();
  if (method == message.end()) return out;  // a response to a request of ours: we send none
  if (!method->is_string()) {
    if (request) out.push_back(error_response(*id, kInvalidRequest, "`method` must be a string"));
    return out;
  }
  const json params = message.value("params", json::object());
  try {
    json result = dispatch(method->get<std::string>(), params, out);
    if (request) out.insert(out.begin(), json{{"jsonrpc", "2.0"}, {"id", *id}, {"result", std::move(result)}});
  } catch (const RpcError& e) {
    if (request) out.insert(out.begin(), error_response(*id, e.code, e.message));
  } catch (const json::exception& e) {
    // Params of the wrong shape: the client's bug, answered, never fatal.
    if (request) out.insert(out.begin(), error_response(*id, kInvalidParams, std::string("invalid params: ") + e.what()));
  }
  return out;
}

json LanguageServer::dispatch(const std::string& method, const json& params, std::vector<json>& out) {
  if (method == "initialize") {
    initialized_ = true;
    return {{"capabilities",
             {{"textDocumentSync", {{"openClose", true}, {"change", 1}}},  // 1: the whole text on each change
              {"completionProvider", {{"triggerCharacters", json::array({" "})}}},
              {"hoverProvider", true},
              {"definitionProvider", true}}},
            {"serverInfo", {{"name", "sandpaper"}, {"version", SANDPAPER_VERSION}}}};
  }
  if (method == "exit") {
    exited_ = true;
    return nullptr;
  }
  if (!initialized_) throw RpcError{kServerNotInitialized, "send `initialize` first"};
  if (method == "initialized" || method == "$/cancelRequest" || method == "$/setTrace" ||
      method == "workspace/didChangeConfiguration")
    return nullptr;
  if (method == "shutdown") {
    shutdown_ = true;
    return nullptr;
  }
  if (method == "textDocument/didOpen") {
    const json& td = params.at("textDocument");
    open(td.at("uri").get<std::string>(), td.at("text").get<std::string>(), out);
    return nullptr;
  }
  if (method == "textDocument/didChange") {
    const std::string uri = params.at("textDocument").at("uri").get<std::string>();
    const json& changes = params.at("contentChanges");
    if (!changes.is_array() || changes.empty()) throw RpcError{kInvalidParams, "contentChanges is an array of changes"};
    // Full synchronisation (we announced change = 1): the last change is the whole text.
    open(uri, changes.back().at("text").get<std::string>(), out);
    return nullptr;
  }
  if (method == "textDocument/didClose") {
    const std::string uri = params.at("textDocument").at("uri").get<std::string>();
    documents_.erase(uri);
    out.push_back({{"jsonrpc", "2.0"},
                   {"method", "textDocument/publishDiagnostics"},
                   {"params", {{"uri", uri}, {"diagnostics", json::array()}}}});
    return nullptr;
  }
  if (method == "textDocument/completion") return completion(document(params), params.at("position"), compiler_);
  if (method == "textDocument/hover") return hover(document(params), params.at("position"), compiler_);
  if (method == "textDocument/definition") return definition(document(params), params.at("position"), compiler_);
  throw RpcError{kMethodNotFound, "sandpaper lsp does not implement " + method};
}

const Document& LanguageServer::document(const json& params) const {
  const std::string uri = params.at("textDocument").at("uri").get<std::string>();
  const auto it = documents_.find(uri);
  if (it == documents_.end()) throw RpcError{kInvalidParams, "no open document " + uri};
  return it->second;
}

void LanguageServer::open(const std::string& uri, std::string text, std::vector<json>& out) {
  Document d;
  d.uri = uri;
  const std::string path = path_of_uri(uri);
  d.name = path.empty() ? uri : path;
  d.workspace = compiler::is_workspace_path(d.name);
  compiler::Diagnostics diags;
  if (d.workspace) {
    const auto base = path.empty() ? std::filesystem::current_path() : std::filesystem::path(path).parent_path();
    auto r = compiler::compile_workspace_text(compiler_, text, d.name, base);
    diags = std::move(r.diagnostics);
  } else {
    d.compiled = compiler_.compile_text(text, d.name);
    diags = d.compiled->diagnostics;
  }
  d.source = std::make_shared<const compiler::SourceFile>(d.name, std::move(text));
  json published = diagnostics_of(d, diags);
  documents_[uri] = std::move(d);
  out.push_back({{"jsonrpc", "2.0"},
                 {"method", "textDocument/publishDiagnostics"},
                 {"params", {{"uri", uri}, {"diagnostics", std::move(published)}}}});
}

json LanguageServer::diagnostics_of(const Document& d, const compiler::Diagnostics& ds) const {
  static const std::string docs = docs_root(compiler_);
  json list = json::array();
  for (const auto& x : ds.all()) {
    const bool here = x.location.file && x.location.file->name == d.name && x.location.line > 0;
    std::string message = x.message;
    // A problem in another file (a library entry this one builds on) is marked where this text
    // brought the entry in (its `like`, or the workspace patch), says where it lies, and links
    // there as related information, which editors open on click.
    json range = range_of(x.location, *d.source);
    json related = json::array();
    if (!here && x.location.file) {
      message = x.location.str() + ": " + message;
      const auto b = compiler::brought_in(x, d.source, compiler_.library());
      if (b) range = range_of(b->at, *d.source);
      related.push_back({{"location", {{"uri", uri_of_path(std::filesystem::absolute(x.location.file->name).string())},
                                       {"range", range_of(x.location, *x.location.file)}}},
                         {"message", b && !b->entry.empty() ? "in library entry " + b->entry : "here"}});
    }
    if (!x.suggestion.empty()) message += "\nhelp: " + x.suggestion;
    json item = {{"range", std::move(range)},
                 {"severity", x.severity == compiler::Severity::Error ? 1 : x.severity == compiler::Severity::Warning ? 2 : 3},
                 {"code", x.code},
                 {"source", "sandpaper"},
                 {"message", message}};
    if (const auto* entry = schema::find_diagnostic_code(x.code); entry && !docs.empty()) {
      const std::string link = schema::diagnostic_doc_link(*entry);
      const auto hash = link.find('#');
      item["codeDescription"] = {{"href", uri_of_path(docs + "/" + link.substr(0, hash)) + link.substr(hash)}};
    }
    for (const auto& n : x.notes) {
      if (!n.location.file) continue;
      const std::string name = n.location.file->name;
      const std::string uri = name == d.name ? d.uri : uri_of_path(std::filesystem::absolute(name).string());
      related.push_back({{"location", {{"uri", uri}, {"range", range_of(n.location, *n.location.file)}}}, {"message", n.message}});
    }
    if (!related.empty()) item["relatedInformation"] = std::move(related);
    list.push_back(std::move(item));
  }
  return list;
}

int serve(std::istream& in, std::ostream& out, std::ostream& log, const compiler::Compiler& compiler) {
  LanguageServer server(compiler);
  log << "sandpaper lsp: ready on stdio (library " << compiler.library().directory().string() << ", "
      << compiler.library().entries().size() << (compiler.library().entries().size() == 1 ? " entry" : " entries") << "; device " << compiler.device().name << ")" << std::endl;
  for (;;) {
    std::optional<std::string> body;
    try {
      body = read_message(in);
    } catch (const FramingError& e) {
      log << "sandpaper lsp: error: " << e.what() << "; stopping (the editor restarts the server)" << std::endl;
      return 1;
    }
    if (!body) return server.exited() ? server.exit_code() : 1;  // input closed without `exit`
    const json message = json::parse(*body, nullptr, /*allow_exceptions=*/false);
    const std::vector<json> replies =
        message.is_discarded() ? std::vector<json>{error_response(nullptr, kParseError, "the message is not JSON")}
                               : server.handle(message);
    for (const auto& r : replies) write_message(out, r);
    if (server.exited()) return server.exit_code();
  }
}

}  // namespace sandpaper::lsp
