#include "sandpaper/http/local_server.hpp"

#include <httplib.h>

#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::http {

void send_json(httplib::Response& res, const nlohmann::json& body, int status) {
  res.status = status;
  res.set_content(schema::json_text(body), "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, {{"error", message}}, status);
}

LocalServer::LocalServer(Options options) : http_(std::make_unique<httplib::Server>()) {
  http_->set_payload_max_length(options.max_request_bytes);
  // An answer goes out as headers then body; with Nagle's algorithm the body waits for the page's
  // delayed ACK of the headers, 40 ms on Linux, on every request (measured in the USB lab).
  http_->set_tcp_nodelay(true);
  const std::size_t threads = options.threads;
  http_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  // The guard: a request for another host name (DNS rebinding) or from another origin (a web page
  // elsewhere posting to localhost) is refused before any handler runs.
  http_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    const std::string why = refusal(req.get_header_value("Host"), req.get_header_value("Origin"), listen_);
    if (why.empty()) return httplib::Server::HandlerResponse::Unhandled;
    send_error(res, 403, why);
    return httplib::Server::HandlerResponse::Handled;
  });
}

LocalServer::~LocalServer() { stop(); }

httplib::Server& LocalServer::server() { return *http_; }

void LocalServer::serve_assets(const std::vector<Asset>& assets) {
  for (const Asset& asset : assets)
    http_->Get(asset.path, [asset](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      res.set_content(asset.body, std::string(asset.content_type) + "; charset=utf-8");
    });
}

void LocalServer::event_stream(const std::string& path, std::chrono::milliseconds period,
                               std::function<nlohmann::json()> event) {
  http_->Get(path, [this, period, event](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider("text/event-stream", [this, period, event](std::size_t, httplib::DataSink& sink) {
      std::this_thread::sleep_for(period);
      if (stopping_.load()) return false;
      const std::string text = "data: " + schema::json_text(event()) + "\n\n";
      return sink.write(text.data(), text.size());
    });
  });
}

int LocalServer::bind(const Listen& listen) {
  listen_ = listen;
  int port = listen.port;
  if (port == 0) {
    port = http_->bind_to_any_port(listen.host);
  } else if (!http_->bind_to_port(listen.host, port)) {
    port = -1;
  }
  if (port < 0) throw std::runtime_error("cannot listen on " + listen.host + ":" + std::to_string(listen.port));
  listen_.port = port;
  return port;
}

std::string LocalServer::url() const {
  const bool v6 = listen_.host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + listen_.host + "]" : listen_.host) + ":" + std::to_string(listen_.port) + "/";
}

void LocalServer::serve() { http_->listen_after_bind(); }

void LocalServer::start() {
  thread_ = std::thread([this] { http_->listen_after_bind(); });
}

void LocalServer::stop() {
  stopping_.store(true);
  http_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace sandpaper::http
