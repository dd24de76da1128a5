// The studio's parts below HTTP: the request guard (Host, Origin, folder confinement), the Dummy-mode
// joystick, and the session on a running loop (a broken compile leaves the last good program playing;
// saving rewrites only the file's text, atomically).
#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "sandpaper/runtime/dummy_joystick.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/http/request_guard.hpp"
#include "sandpaper/studio/session.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;
using http::Listen;

TEST(RequestGuard, AcceptsOnlyThisServersHostNames) {
  const Listen l{"127.0.0.1", 4780};
  EXPECT_TRUE(http::host_allowed("127.0.0.1:4780", l));
  EXPECT_TRUE(http::host_allowed("localhost:4780", l));
  EXPECT_TRUE(http::host_allowed("LOCALHOST:4780", l));
  EXPECT_TRUE(http::host_allowed("[::1]:4780", l));
  EXPECT_FALSE(http::host_allowed("127.0.0.1:4781", l));
  EXPECT_FALSE(http::host_allowed("evil.example:4780", l));  // DNS rebinding
  EXPECT_FALSE(http::host_allowed("localhost", l));
  EXPECT_FALSE(http::host_allowed("", l));
  const Listen lan{"192.0.2.7", 80};
  EXPECT_TRUE(http::host_allowed("192.0.2.7:80", lan));
  EXPECT_FALSE(http::host_allowed("localhost:80", lan));
}

TEST(RequestGuard, AcceptsNoOriginOrItsOwnOnly) {
  const Listen l{"127.0.0.1", 4780};
  EXPECT_TRUE(http::origin_allowed("", l));
  EXPECT_TRUE(http::origin_allowed("http://127.0.0.1:4780", l));
  EXPECT_TRUE(http::origin_allowed("http://localhost:4780", l));
  EXPECT_FALSE(http::origin_allowed("http://evil.example", l));
  EXPECT_FALSE(http::origin_allowed("https://127.0.0.1:4780", l));
  EXPECT_FALSE(http::origin_allowed("null", l));
}

TEST(RequestGuard, ParsesListenAddresses) {
  EXPECT_EQ(http::parse_listen("127.0.0.1:0").port, 0);
  EXPECT_EQ(http::parse_listen("[::1]:8000").host, "::1");
  EXPECT_THROW(http::parse_listen("127.0.0.1"), std::invalid_argument);
  EXPECT_THROW(http::parse_listen("127.0.0.1:99999"), std::invalid_argument);
  EXPECT_TRUE(http::is_loopback("127.0.0.2"));
  EXPECT_FALSE(http::is_loopback("0.0.0.0"));
}

TEST(RequestGuard, ConfinesPathsToTheFolder) {
  const fs::path root = test::temp_dir("studio-confine");
  fs::create_directories(root / "sub");
  std::ofstream(root / "sub" / "a.hmat") << "roughness 0.5\n";
  const fs::path outside = test::temp_dir("studio-outside");
  fs::create_directory_symlink(outside, root / "link");
  EXPECT_EQ(http::confined_path(root, "sub/a.hmat"), fs::canonical(root / "sub" / "a.hmat"));
  EXPECT_EQ(http::confined_path(root, "sub/../sub/new.hmat"), fs::canonical(root) / "sub" / "new.hmat");
  EXPECT_THROW(http::confined_path(root, "../x.hmat"), http::OutsideFolder);
  EXPECT_THROW(http::confined_path(root, "sub/../../x.hmat"), http::OutsideFolder);
  EXPECT_THROW(http::confined_path(root, "/etc/passwd"), http::OutsideFolder);
  EXPECT_THROW(http::confined_path(root, "link/x.hmat"), http::OutsideFolder);  // a link that leads out
  EXPECT_THROW(http::confined_path(root, ""), http::OutsideFolder);
  // Found by fuzzing (issue 16): `..` after a folder that does not exist, then the link out; and a
  // name too long for the file system, which threw std::filesystem_error instead of a refusal.
  EXPECT_THROW(http::confined_path(root, "missing/../link/passwd"), http::OutsideFolder);
  EXPECT_THROW(http::confined_path(root, std::string(300, 'a')), http::OutsideFolder);
}

TEST(DummyJoystick, MovesTowardTheTargetNoFasterThanItsTopSpeed) {
  runtime::DummyJoystick j(runtime::sim_device_limits(), 0.2);
  glm::dvec2 p;
  ASSERT_TRUE(j.read_position_rt(0.0, p));
  EXPECT_EQ(p, glm::dvec2(0, 0));
  j.set_target_nonrt({0.01, 0});
  ASSERT_TRUE(j.read_position_rt(0.001, p));  // 1 ms at 0.2 m/s: 0.2 mm
  EXPECT_NEAR(p.x, 0.0002, 1e-12);
  for (int i = 2; i <= 60; ++i) j.read_position_rt(i * 0.001, p);
  EXPECT_NEAR(p.x, 0.01, 1e-12);  // arrived after 50 ms, and stays
  ASSERT_TRUE(j.write_force_rt({0.5, -0.25}));
  EXPECT_EQ(j.force_nonrt(), glm::dvec2(0.5, -0.25));
  EXPECT_EQ(j.position_nonrt(), p);
  const glm::dvec2 clipped = j.set_target_nonrt({1.0, 0});  // beyond the 114 mm workspace radius: clipped to it
  EXPECT_NEAR(j.target_nonrt().x, runtime::sim_device_limits().workspace_radius_m, 1e-12);
  EXPECT_EQ(clipped, j.target_nonrt());  // and says so
  j.set_target_nonrt({std::nan(""), 0});
  EXPECT_NEAR(j.target_nonrt().x, runtime::sim_device_limits().workspace_radius_m, 1e-12);
  // A target whose square overflows (POST /api/hand takes any finite number of mm): still clipped to
  // the edge in its direction, not sent to the centre.
  j.set_target_nonrt({1e300, -1e300});
  const double edge = runtime::sim_device_limits().workspace_radius_m / std::sqrt(2.0);
  EXPECT_NEAR(j.target_nonrt().x, edge, 1e-12);
  EXPECT_NEAR(j.target_nonrt().y, -edge, 1e-12);
}

// A session on a running loop with the Dummy-mode joystick.
struct LiveSession {
  fs::path root = test::temp_dir("studio-session");
  runtime::DummyJoystick* dummy = nullptr;
  std::unique_ptr<studio::LiveLoop> loop;
  std::unique_ptr<studio::Session> session;

  LiveSession() {
    auto d = std::make_unique<runtime::DummyJoystick>(runtime::sim_device_limits());
    dummy = d.get();
    loop = std::make_unique<studio::LiveLoop>(std::move(d), dummy, studio::LoopOptions{});
    session = std::make_unique<studio::Session>(test::shipped_compiler(), *loop, root, root / ".previews");
    loop->start_nonrt();
  }
  ~LiveSession() { loop->stop_nonrt(); }

  // Waits (bounded) until the loop plays load `version` and has ticked past `ticks`.
  studio::LoopState wait_for(std::uint64_t version, std::uint64_t ticks = 0) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    studio::LoopState s;
    do {
      s = loop->state_nonrt();
      if (s.material_version == version && s.ticks > ticks) return s;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    } while (std::chrono::steady_clock::now() < deadline);
    ADD_FAILURE() << "the loop never played version " << version << " past tick " << ticks << " (it plays "
                  << s.material_version << " at tick " << s.ticks << ")";
    return s;
  }
};

TEST(StudioSession, ABrokenCompileLeavesTheLastGoodProgramPlaying) {
  LiveSession live;
  std::ofstream(live.root / "m.hmat") << "# mine\nroughness 0.5\ngrating period 3 mm\n";
  const auto opened = live.session->open("m.hmat");
  ASSERT_TRUE(opened["ok"].get<bool>()) << opened.dump(2);
  const auto v1 = opened["version"].get<std::uint64_t>();
  const auto s1 = live.wait_for(v1, 10);
  const double f1 = s1.compiled_max_lateral_force_N;
  EXPECT_GT(f1, 0);

  const auto broken = live.session->update("# mine\nroughness 0.5\ngrating period 3 m m\n");
  EXPECT_FALSE(broken["ok"].get<bool>());
  ASSERT_FALSE(broken["diagnostics"].empty());
  EXPECT_EQ(broken["diagnostics"][0]["line"], 3);
  EXPECT_EQ(broken["version"].get<std::uint64_t>(), v1);  // nothing new offered
  const auto s2 = live.wait_for(v1, s1.ticks + 20);       // still v1, and still ticking
  EXPECT_TRUE(s2.running);
  EXPECT_DOUBLE_EQ(s2.compiled_max_lateral_force_N, f1);

  const auto fixed = live.session->set_parameter("roughness", 0.8, "");
  EXPECT_FALSE(fixed["ok"].get<bool>()) << "the period's typo is still there";
  const auto good = live.session->update("# mine\nroughness 0.8\ngrating period 3 mm\n");
  ASSERT_TRUE(good["ok"].get<bool>());
  const auto s3 = live.wait_for(good["version"].get<std::uint64_t>(), s2.ticks);
  EXPECT_GT(s3.compiled_max_lateral_force_N, f1);  // rougher is a larger force (Figure 19)
}

TEST(StudioSession, SavingRewritesTheFileWithItsCommentsAndNothingElse) {
  LiveSession live;
  const std::string original = "# a comment that stays\nroughness 0.5   # and this one\ngrating period 3 mm hill 40%\n";
  std::ofstream(live.root / "m.hmat") << original;
  ASSERT_TRUE(live.session->open("m.hmat")["ok"].get<bool>());
  const auto r = live.session->set_parameter("grating.period", 4.5, "mm");
  ASSERT_TRUE(r["ok"].get<bool>());
  live.session->save();
  std::ifstream in(live.root / "m.hmat");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string expected = original;
  expected.replace(expected.find("period 3"), 8, "period 4.5");
  EXPECT_EQ(ss.str(), expected);
  for (const auto& e : fs::directory_iterator(live.root))  // no temporary left beside it
    EXPECT_TRUE(e.path().filename() == "m.hmat" || e.path().filename() == ".previews") << e.path();
}

// The material a preview.json is of.
std::string preview_of(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in).at("material").get<std::string>();
}

TEST(StudioSession, APreviewNotYetDrawnIsNeverAnOlderLoads) {
  LiveSession live;
  std::ofstream(live.root / "a.hmat") << "material \"a\" {\n  grating period 3 mm\n  roughness 0.4\n}\n";
  std::ofstream(live.root / "b.hmat") << "material \"b\" {\n  grating period 4 mm\n  roughness 0.6\n}\n";
  const auto va = live.session->open("a.hmat")["version"].get<std::uint64_t>();
  const auto pa = live.session->preview_file("preview.json", va);
  ASSERT_TRUE(pa) << "no preview of a";
  EXPECT_EQ(preview_of(*pa), "a");

  // Asked at once, with no wait: either b's preview or "not yet" (503), never a's under b's load.
  const auto vb = live.session->open("b.hmat")["version"].get<std::uint64_t>();
  ASSERT_GT(vb, va);
  try {
    const auto early = live.session->preview_file("preview.json", vb, std::chrono::milliseconds(0));
    ASSERT_TRUE(early);
    EXPECT_EQ(preview_of(*early), "b");
  } catch (const studio::RequestError& e) {
    EXPECT_EQ(e.status, 503) << e.what();
    EXPECT_NE(std::string(e.what()).find("ask again"), std::string::npos) << e.what();
  }
  const auto pb = live.session->preview_file("preview.json", vb);
  ASSERT_TRUE(pb);
  EXPECT_EQ(preview_of(*pb), "b");
}

// A held device gone at its first read, whose port check waits until `release` is ready.
class UnpluggedDevice final : public runtime::HeldDevice {
 public:
  UnpluggedDevice() { limits_ = runtime::sim_device_limits(); }
  const runtime::DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double, glm::dvec2& p) noexcept override {
    p = {0, 0};
    return false;
  }
  bool write_force_rt(glm::dvec2) noexcept override { return true; }
  runtime::DeviceFault last_fault_rt() const noexcept override { return runtime::DeviceFault::Unplugged; }
  void close_nonrt() noexcept override {}
  std::string fault_detail_nonrt() const override { return "no device"; }

 private:
  runtime::DeviceLimits limits_;
};

TEST(StudioSession, AFileOpensWhileTheLoopWaitsToSeeIfItsDeviceComesBack) {
  // After an unplug the loop waits up to runtime::kResetGraceS for the device at its port; a file
  // opened meanwhile must not wait for that. The check here waits until the open has returned.
  const fs::path root = test::temp_dir("studio-unplugged");
  std::ofstream(root / "m.hmat") << "grating period 3 mm\nroughness 0.5\n";
  auto device = std::make_unique<UnpluggedDevice>();
  std::promise<void> checking, opened;
  auto opened_done = opened.get_future();
  bool opened_in_time = false;
  device->watch_for_return_nonrt([&](double) {
    checking.set_value();
    opened_in_time = opened_done.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
    return false;
  });
  studio::LoopOptions options;
  options.restart_after_fault = false;
  studio::LiveLoop loop(std::move(device), nullptr, options);
  studio::Session session(test::shipped_compiler(), loop, root, root / ".previews");
  loop.start_nonrt();
  checking.get_future().wait();
  EXPECT_TRUE(session.open("m.hmat")["ok"].get<bool>());
  opened.set_value();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (loop.state_nonrt().stop_cause.empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(loop.state_nonrt().stop_cause, "device_unplugged");  // not found back at its port
  loop.stop_nonrt();
  EXPECT_TRUE(opened_in_time);
}

TEST(StudioSession, RefusesFilesOutsideItsFolder) {
  LiveSession live;
  try {
    live.session->open("../../etc/passwd");
    ADD_FAILURE() << "opened a file outside the folder";
  } catch (const studio::RequestError& e) {
    EXPECT_EQ(e.status, 403);
  }
  try {
    live.session->open("missing.hmat");
    ADD_FAILURE() << "opened a missing file";
  } catch (const studio::RequestError& e) {
    EXPECT_EQ(e.status, 404);
  }
}

TEST(StudioSession, TheDummyHandFeelsTheMaterial) {
  LiveSession live;
  std::ofstream(live.root / "m.hmat") << "roughness 0.6\ngrating period 2.5 mm\n";
  const auto v = live.session->open("m.hmat")["version"].get<std::uint64_t>();
  live.wait_for(v, 10);
  // Stroke across the ribs: the felt maximum reaches most of the compiled force.
  for (int i = 0; i <= 40; ++i) {
    live.loop->set_hand_nonrt(-10 + 0.5 * i, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  studio::LoopState s;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  do {  // the supervisor publishes the hand every 10 ms, later on a loaded machine
    s = live.loop->state_nonrt();
  } while (std::abs(s.hand_mm.x - 10) > 1e-6 && std::chrono::steady_clock::now() < deadline);
  EXPECT_NEAR(s.hand_mm.x, 10, 1e-6);
  EXPECT_GT(s.felt_max_lateral_force_N, 0.5 * s.compiled_max_lateral_force_N);
  EXPECT_LE(s.felt_max_lateral_force_N, s.compiled_max_lateral_force_N * (1 + 1e-9));
}

}  // namespace
}  // namespace sandpaper
