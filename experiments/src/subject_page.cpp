// The page observer: one screen at a time. The session thread sets a screen and waits; the page,
// on the server's threads, reads the screen and posts the answer; a condition variable hands it over.
#include "sandpaper/experiment/subject_page.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "sandpaper/experiment/page_answer.hpp"
#include "sandpaper/experiment/percept_quantity.hpp"
#include "sandpaper/http/local_server.hpp"

namespace sandpaper::experiment {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxRequestBytes = 64 * 1024;
// One page and a script or two: each open long-poll holds a pool thread.
constexpr std::size_t kServerThreads = 8;
constexpr auto kLongPoll = std::chrono::seconds(15);

class PageObserverImpl final : public Observer {
 public:
  PageObserverImpl(const std::string& listen, const std::atomic<bool>* stop, std::string& url)
      : stop_(stop), server_({kServerThreads, kMaxRequestBytes}) {
    httplib::Server& api = server_.server();
    server_.serve_assets(page_assets());
    api.Get("/api/screen", [this](const httplib::Request& req, httplib::Response& res) {
      long after = -1;
      page_seen_ = true;
      if (req.has_param("after")) after = std::strtol(req.get_param_value("after").c_str(), nullptr, 10);
      std::unique_lock lock(mutex_);
      changed_.wait_for(lock, kLongPoll, [&] { return screen_seq_ > after || closing_; });
      json j = screen_;
      j["seq"] = screen_seq_;
      delivered_seq_ = std::max(delivered_seq_, screen_seq_);
      delivered_.notify_all();
      res.set_header("Cache-Control", "no-store");
      http::send_json(res, j);
    });
    api.Post("/api/answer", [this](const httplib::Request& req, httplib::Response& res) {
      json body;
      std::lock_guard lock(mutex_);
      if (const std::string why = parse_page_answer(req.body, screen_seq_, body); !why.empty()) return refuse(res, why);
      if (!waiting_) return refuse(res, "no question is waiting for an answer");
      if (const std::string why = page_answer_refusal(screen_, body); !why.empty()) return refuse(res, why);
      answer_ = body;
      waiting_ = false;
      answered_.notify_all();
      http::send_json(res, json{{"ok", true}});
    });
    server_.bind(http::parse_listen(listen));
    url = server_.url();
    server_.start();
  }

  ~PageObserverImpl() override {
    {
      // The last screen ("Thank you", "Paused") reaches an open page before the server goes: wait
      // until the page has fetched it, for 10 s at most (the page may have been closed).
      std::unique_lock lock(mutex_);
      delivered_.wait_for(lock, std::chrono::seconds(10), [&] { return delivered_seq_ >= screen_seq_ || !page_seen_; });
      closing_ = true;
    }
    changed_.notify_all();
    server_.stop();
  }

  std::string describe() const override { return "page"; }

  void instructions(const std::string& title, const std::string& text) override {
    ask({{"kind", "instructions"}, {"title", title}, {"text", text}, {"paragraphs", instruction_paragraphs(text)}});
  }
  void rest(int done, int total) override { ask({{"kind", "rest"}, {"done", done}, {"total", total}}); }
  void announce(const Trial& t, int total) override {
    show({{"kind", "feel"}, {"trial", t.index + 1}, {"total", total}, {"practice", t.practice},
          {"patches", t.stimuli.size()}});
  }
  std::optional<double> estimate(const Trial& t, const Presented& p, bool confidence) override {
    const auto* q = find_percept_quantity(p.percept);
    auto a = ask({{"kind", confidence ? "confidence" : "estimate"}, {"trial", t.index + 1}, {"practice", t.practice},
                  {"question", q ? std::string(q->question) + "?" : "How rough was it?"},
                  {"hint", q ? "Any positive number: " + std::string(q->more) + "." : "Any positive number: larger for rougher."}});
    if (!a) return std::nullopt;
    return answer_value(*a);
  }
  std::optional<int> choose_interval(const Trial& t, const Presented&) override {
    auto a = ask({{"kind", "interval"}, {"trial", t.index + 1}, {"practice", t.practice}});
    if (!a) return std::nullopt;
    return answer_interval(*a);
  }
  std::optional<std::vector<int>> sort(const Trial& t, const Presented& p, int piles) override {
    auto a = ask({{"kind", "sort"}, {"trial", t.index + 1}, {"patches", p.names.size()}, {"piles", piles}});
    if (!a) return std::nullopt;
    return answer_piles(*a);
  }
  void ended(bool finished) override { show({{"kind", finished ? "done" : "paused"}}); }

 private:
  static void refuse(httplib::Response& res, const std::string& why) { http::send_error(res, 400, why); }

  void show(json screen) {
    std::lock_guard lock(mutex_);
    screen_ = std::move(screen);
    ++screen_seq_;
    waiting_ = false;
    changed_.notify_all();
  }

  // Shows a screen that needs an answer and waits for it; nullopt when stopped (a signal).
  std::optional<json> ask(json screen) {
    std::unique_lock lock(mutex_);
    screen_ = std::move(screen);
    ++screen_seq_;
    waiting_ = true;
    changed_.notify_all();
    while (waiting_) {
      if (stop_ && stop_->load()) {
        waiting_ = false;
        return std::nullopt;
      }
      answered_.wait_for(lock, std::chrono::milliseconds(100));
    }
    return answer_;
  }

  const std::atomic<bool>* stop_;
  http::LocalServer server_;
  std::mutex mutex_;
  std::condition_variable changed_, answered_;
  json screen_ = json{{"kind", "starting"}};
  std::int64_t screen_seq_ = 0, delivered_seq_ = -1;
  std::condition_variable delivered_;
  std::atomic<bool> page_seen_{false};  // a page has asked for a screen at least once
  bool waiting_ = false, closing_ = false;
  json answer_;
};

}  // namespace

std::unique_ptr<Observer> make_page_observer(const std::string& listen, const std::atomic<bool>* stop, std::string& url) {
  return std::make_unique<PageObserverImpl>(listen, stop, url);
}

}  // namespace sandpaper::experiment
