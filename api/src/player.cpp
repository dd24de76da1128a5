// sandpaper::Player: a device, a hot-swappable force source and a servo thread, started and
// stopped from the application's thread.
#include <atomic>

#include "sandpaper/runtime/owning_source.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/swappable_source.hpp"
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {
namespace {

// A patch evaluator that owns its program, so that a material swapped out on the servo thread
// keeps its program until the application thread frees both together (collect_retired_nonrt).
using ProgramSource = runtime::OwningSource<schema::PatchProgram, runtime::PatchEvaluator>;

}  // namespace

struct Player::Impl {
  std::unique_ptr<runtime::Device> device;
  std::unique_ptr<runtime::SwappableSource> source;  // null until the first load
  std::atomic<bool> stop_request{false};
  runtime::ServoConfig config;
  std::unique_ptr<runtime::ServoThread> thread;  // from start until joined
  std::string device_calibration;                // usb(): the calibration the joystick takes forces in

  // Stops a run still going (also when a moved-to Player drops this one), rather than wait for
  // its whole duration as ServoThread's own destructor would.
  ~Impl() {
    if (!thread) return;
    stop_request.store(true, std::memory_order_release);
    try {
      join();
    } catch (...) {  // a destructor must not throw; the run is over either way
    }
  }

  runtime::ServoReport join() {
    runtime::ServoReport report = thread->join_nonrt();
    thread.reset();
    source->collect_retired_nonrt();
    return report;
  }
};

Player Player::simulated(runtime::HandScript hand) {
  // Records no ticks (capacity 0): the report carries what an application needs.
  return Player(std::make_unique<runtime::SimJoystick>(runtime::sim_device_limits(), hand, 0));
}

Player::Player(std::unique_ptr<runtime::Device> device) : impl_(std::make_unique<Impl>()) {
  if (!device) throw Error("Player needs a device");
  impl_->device = std::move(device);
}

Player::~Player() = default;

Player::Player(Player&&) noexcept = default;
Player& Player::operator=(Player&&) noexcept = default;

void Player::load(const Material& material) {
  // Forces are compiled against a device's command scale (thesis 7.6.3): another device's program
  // would push with the wrong strength.
  if (!impl_->device_calibration.empty() && material.program().device != impl_->device_calibration)
    throw DeviceError("the material '" + material.name() + "' was compiled for device '" + material.program().device +
                "', but this player's joystick is '" + impl_->device_calibration +
                "'; open the library for device '" + impl_->device_calibration + "' and compile it there");
  auto next = std::make_unique<ProgramSource>(material.shared_program());
  if (impl_->thread) {
    impl_->source->offer_nonrt(std::move(next));
    impl_->source->collect_retired_nonrt();
  } else {
    impl_->source = std::make_unique<runtime::SwappableSource>(std::move(next));
  }
}

void Player::start(PlayOptions options) {
  if (impl_->thread && !impl_->thread->finished()) throw Error("already playing; stop() first");
  if (impl_->thread) impl_->join();  // a run that ended on its own and was not waited for
  if (!impl_->source) throw Error("nothing to play; load() a material first");
  impl_->config = runtime::ServoConfig{};
  impl_->config.rate_hz = options.rate_hz;
  impl_->config.duration_s = options.duration_s;  // 0: until stop(); the loop's memory is the same either way
  impl_->stop_request.store(false, std::memory_order_release);
  impl_->config.stop_request = &impl_->stop_request;
  auto thread = std::make_unique<runtime::ServoThread>();
  thread->start_nonrt(*impl_->device, *impl_->source, impl_->config);  // validates: may throw
  impl_->thread = std::move(thread);
}

runtime::ServoReport Player::stop() {
  if (!impl_->thread) throw Error("not playing; start() first");
  impl_->stop_request.store(true, std::memory_order_release);
  return impl_->join();
}

runtime::ServoReport Player::wait() {
  if (!impl_->thread) throw Error("not playing; start() first");
  return impl_->join();
}

bool Player::playing() const noexcept { return impl_->thread && !impl_->thread->finished(); }

runtime::Device& Player::device() noexcept { return *impl_->device; }

const std::string& Player::device_calibration() const noexcept { return impl_->device_calibration; }

void Player::set_device_calibration_nonrt(std::string name) { impl_->device_calibration = std::move(name); }

}  // namespace sandpaper
