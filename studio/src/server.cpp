#include "sandpaper/studio/server.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/json_text.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include <httplib.h>

namespace sandpaper::studio {
namespace {

// Connections a browser keeps open (up to 6 per host, one of them the event stream) plus scripts:
// cpp-httplib holds a pool thread per open connection.
constexpr std::size_t kServerThreads = 32;
// A request carries at most a source file the compiler reads, JSON-escaped (a quote or backslash
// takes two bytes), and a little more.
constexpr std::size_t kMaxRequestBytes = 2 * schema::limits::kMaxSourceBytes + (64 << 10);
// The event stream's rate: a strip chart and a force arrow at 30 frames a second.
constexpr auto kEventPeriod = std::chrono::milliseconds(33);

using http::send_error;
using http::send_json;

nlohmann::json body_json(const httplib::Request& req) {
  try {
    return nlohmann::json::parse(req.body);
  } catch (const nlohmann::json::parse_error& e) {
    throw RequestError(400, std::string("the request body is not JSON: ") + e.what());
  }
}

double number_field(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number())
    throw RequestError(400, std::string("expected a number \"") + key + "\" in the JSON body");
  const double v = j[key].get<double>();
  if (!std::isfinite(v)) throw RequestError(400, std::string("\"") + key + "\" must be finite");
  return v;
}

std::string string_field(const nlohmann::json& j, const char* key, bool required = true) {
  if (!j.is_object() || !j.contains(key)) {
    if (required) throw RequestError(400, std::string("expected a string \"") + key + "\" in the JSON body");
    return {};
  }
  if (!j[key].is_string()) throw RequestError(400, std::string("\"") + key + "\" must be a string");
  return j[key].get<std::string>();
}

// A point of the scene (metres, its frame) as three finite numbers under `key`; nullopt when the key
// is absent and not required.
std::optional<SceneView::Point_m> point_field(const nlohmann::json& j, const char* key, bool required) {
  if (!j.is_object() || !j.contains(key) || j[key].is_null()) {
    if (required) throw RequestError(400, std::string("expected \"") + key + "\": [x, y, z] (metres) in the JSON body");
    return std::nullopt;
  }
  const auto& a = j[key];
  if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number())
    throw RequestError(400, std::string("\"") + key + "\" is [x, y, z]: three numbers, metres");
  SceneView::Point_m p{a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
  for (const double v : p)
    if (!std::isfinite(v)) throw RequestError(400, std::string("\"") + key + "\" must be finite");
  return p;
}

// A length for a message: 4 significant figures, so 1e300 reads 1e+300 and 114.3 reads 114.3.
std::string fmt_mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string content_type_of(const std::string& name) {
  if (name.ends_with(".png")) return "image/png";
  if (name.ends_with(".svg")) return "image/svg+xml";
  return "application/json";
}

}  // namespace

nlohmann::json state_json(const LoopState& s, bool dummy_hand) {
  return {{"ticks", s.ticks},
          {"rate_hz", s.rate_hz},
          {"overruns", s.overruns},
          {"compiled_max_lateral_force_N", s.compiled_max_lateral_force_N},
          {"felt_max_lateral_force_N", s.felt_max_lateral_force_N},
          {"material", s.material},
          {"material_version", s.material_version},
          {"compiled_roughness", s.compiled_roughness},
          {"hand", {s.hand_mm.x, s.hand_mm.y}},
          {"force_N", {s.force_N.x, s.force_N.y}},
          {"running", s.running},
          {"stop_cause", s.stop_cause},
          {"restarts", s.restarts},
          {"telemetry_dropped", s.telemetry_dropped},
          {"dummy_hand", dummy_hand}};
}

struct Server::Impl {
  Session& session;
  LiveLoop& loop;
  LibraryBrowser& library;
  std::string version;
  http::LocalServer server{{kServerThreads, kMaxRequestBytes}};
  httplib::Server& api = server.server();

  Impl(Session& s, LiveLoop& l, LibraryBrowser& b, std::string v) : session(s), loop(l), library(b), version(std::move(v)) {}

  // The loop's state and the open document's: one event tells every page what plays and which text
  // the studio holds, whoever changed it.
  nlohmann::json event_json() const {
    nlohmann::json j = state_json(loop.state_nonrt(), loop.has_dummy_hand());
    j["document"] = session.document_state();
    return j;
  }

  // Runs `f`, answering a RequestError with its status and message and anything else as a 500 that
  // says it is the studio's fault, not the request's.
  template <class F>
  static void guarded(httplib::Response& res, F&& f) {
    try {
      f();
    } catch (const RequestError& e) {
      send_error(res, e.status, e.what());
    } catch (const std::exception& e) {
      send_error(res, 500, std::string("internal error (a bug in Sandpaper, please report it): ") + e.what());
    }
  }

  void routes() {
    server.serve_assets(web_assets());
    api.Get("/api/health", [this](const httplib::Request&, httplib::Response& res) {
      send_json(res, {{"ok", true}, {"version", version}});
    });
    api.Get("/api/files", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.files()); });
    });
    api.Get("/api/current", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.current()); });
    });
    api.Post("/api/open", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.open(string_field(body_json(req), "file"))); });
    });
    api.Post("/api/compile", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.compile_only(req.body)); });
    });
    api.Post("/api/material", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.update(req.body)); });
    });
    api.Post("/api/parameter", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto j = body_json(req);
        send_json(res, session.set_parameter(string_field(j, "name"), number_field(j, "value"),
                                             string_field(j, "unit", false)));
      });
    });
    api.Post("/api/language", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto j = body_json(req);
        const double line = number_field(j, "line"), character = number_field(j, "character");
        if (line != std::floor(line) || character != std::floor(character) || line > 1e7 || character > 1e7)
          throw RequestError(400, "\"line\" and \"character\" are whole numbers (0-based)");
        send_json(res, session.language(string_field(j, "feature"), static_cast<int>(line), static_cast<int>(character)));
      });
    });
    // The library browser: search (the SQLite index), an entry's numbers and text, its picture.
    api.Get("/api/library/search", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] { send_json(res, library.search(req.has_param("q") ? req.get_param_value("q") : "")); });
    });
    api.Get("/api/library/entry", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        if (!req.has_param("name")) throw RequestError(400, "?name= names the library entry");
        send_json(res, library.entry(req.get_param_value("name")));
      });
    });
    api.Get("/api/library/picture", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto file = req.has_param("name") ? library.picture(req.get_param_value("name")) : std::nullopt;
        if (!file) throw RequestError(404, "no picture for that library entry");
        std::ifstream in(*file, std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        res.set_content(ss.str(), "image/png");
      });
    });
    api.Post("/api/new", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.create(string_field(body_json(req), "file"))); });
    });
    api.Post("/api/save-as", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.save_as(string_field(body_json(req), "file"))); });
    });
    api.Post("/api/save", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.save()); });
    });
    api.Post("/api/hand", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto j = body_json(req);
        const double x = number_field(j, "x_mm"), y = number_field(j, "y_mm");
        const auto target = loop.set_hand_nonrt(x, y);
        if (!target) throw RequestError(409, "the hand is a real joystick's; Dummy mode needs --device sim");
        nlohmann::json answer = {{"ok", true}, {"requested_mm", {x, y}}, {"target_mm", {target->x, target->y}},
                                 {"clipped", *target != glm::dvec2(x, y)}};
        // The answer says where the hand goes and why, so a script asking for 500 mm is not left to
        // find out from /api/state that the hand stopped at the edge.
        if (answer["clipped"].get<bool>()) {
          const double radius_mm = loop.limits().workspace_radius_m * 1e3;
          answer["why"] = "(" + fmt_mm(x) + ", " + fmt_mm(y) + ") mm is outside the " + loop.limits().name +
                          " joystick's workspace, a circle of radius " + fmt_mm(radius_mm) +
                          " mm: the hand goes to its edge in that direction";
        }
        send_json(res, answer);
      });
    });
    api.Get("/api/state", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, event_json()); });
    });
    // Server-Sent Events: the state 30 times a second while the page is open.
    server.event_stream("/api/events", kEventPeriod, [this] { return event_json(); });
    // Scenes in 3-D: the geometry to draw, and the 3-D Dummy mode's simulated device.
    api.Get("/api/scene", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.scene()); });
    });
    api.Post("/api/scene/device", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto j = body_json(req);
        send_json(res, session.scene_touch(*point_field(j, "device_m", true), point_field(j, "from_m", false)));
      });
    });
    api.Get("/api/scene/device", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.scene_device()); });
    });
    api.Get("/api/workspace", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { send_json(res, session.workspace()); });
    });
    api.Post("/api/workspace/patch", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto j = body_json(req);
        const double index = number_field(j, "index");
        if (index != std::floor(index) || index < 0 || index > 1e6) throw RequestError(400, "\"index\" must be a patch number");
        send_json(res, session.place_patch(static_cast<int>(index), number_field(j, "x_mm"), number_field(j, "y_mm"),
                                           number_field(j, "width_mm"), number_field(j, "height_mm")));
      });
    });
    // Zoom and pan over the whole patch: a picture of any window, drawn on request.
    api.Get("/api/view", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        auto number = [&](const char* key) {
          if (!req.has_param(key)) throw RequestError(400, std::string("?") + key + "= is required (mm)");
          const std::string text = req.get_param_value(key);
          std::size_t used = 0;
          double v = 0;
          try {
            v = std::stod(text, &used);
          } catch (const std::exception&) {
            used = 0;
          }
          if (used == 0 || used != text.size() || !std::isfinite(v))
            throw RequestError(400, std::string("?") + key + "= takes a number of millimetres");
          return v;
        };
        const double centre[2] = {number("x_mm"), number("y_mm")};
        const double window[2] = {number("w_mm"), number("h_mm")};
        send_json(res, session.render_view(req.has_param("kind") ? req.get_param_value("kind") : "height", centre, window));
      });
    });
    api.Get(R"(/api/view/([A-Za-z0-9.\-]+))", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const auto path = session.view_file(req.matches[1]);
        if (!path) throw RequestError(404, "no view picture '" + std::string(req.matches[1]) + "' (only the last " +
                                               std::to_string(Session::kKeptViews) + " are kept)");
        std::ifstream in(*path, std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        res.set_header("Cache-Control", "no-store");
        res.set_content(ss.str(), "image/png");
      });
    });
    api.Get(R"(/api/preview/([A-Za-z0-9.\-]+))", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const std::string name = req.matches[1];
        std::uint64_t load = 0;
        if (req.has_param("v")) {
          try {
            load = std::stoull(req.get_param_value("v"));
          } catch (const std::exception&) {
            throw RequestError(400, "?v= takes the version number of a load");
          }
        }
        const auto path = session.preview_file(name, load);
        if (!path) throw RequestError(404, "no preview picture '" + name + "' for the material playing");
        std::ifstream in(*path, std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        res.set_header("Cache-Control", "no-store");
        res.set_content(ss.str(), content_type_of(name).c_str());
      });
    });
  }
};

Server::Server(Session& session, LiveLoop& loop, LibraryBrowser& library, std::string version)
    : impl_(std::make_unique<Impl>(session, loop, library, std::move(version))) {
  impl_->routes();
}

Server::~Server() { stop(); }

int Server::bind(const http::Listen& listen) { return impl_->server.bind(listen); }

void Server::serve() { impl_->server.serve(); }

void Server::stop() { impl_->server.stop(); }

}  // namespace sandpaper::studio
