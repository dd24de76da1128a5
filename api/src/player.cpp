// sandpaper::Player: a device, a hot-swappable force source and a servo thread, started and
// stopped from the application's thread.
#include "sandpaper/runtime/devices/builtin_devices.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/live_servo.hpp"
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {

struct Player::Impl {
  std::unique_ptr<runtime::Device> device;
  std::unique_ptr<runtime::LiveServo> host;  // null until the first load
  std::string device_calibration;            // usb(): the calibration the joystick takes forces in
  std::string warning;                       // open(): what to tell a person first (Player::warning)

  runtime::ServoReport join() { return host->join_nonrt(); }
};

Player Player::simulated(runtime::HandScript hand) {
  // Through the device factory, as every caller: the simulated joystick of calibration/devices/sim.toml.
  // Records no ticks (capacity 0): the report carries what an application needs.
  runtime::DeviceSpec spec;
  spec.script = hand;
  return Player(runtime::open_device(runtime::builtin_devices(), std::move(spec)).device);
}

Player::Player(std::unique_ptr<runtime::Device> device) : impl_(std::make_unique<Impl>()) {
  if (!device) throw Error("Player needs a device");
  impl_->device = std::move(device);
}

// The host goes first (its destructor stops a run still going, rather than wait for its whole
// duration), then the device it played.
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
  if (impl_->host) {
    impl_->host->offer_nonrt(impl_->host->patch_source_nonrt(material.shared_program()));
    return;
  }
  // The first material plays from the first tick, without a blend from nothing. No telemetry: the
  // report carries what an application needs.
  runtime::LiveServo::Options options;
  options.telemetry_records = 0;
  impl_->host = std::make_unique<runtime::LiveServo>(
      *impl_->device, runtime::patch_source_for(*impl_->device, material.shared_program()), options);
}

void Player::start(PlayOptions options) {
  if (!impl_->host) throw Error("nothing to play; load() a material first");
  if (impl_->host->running() && !impl_->host->finished()) throw Error("already playing; stop() first");
  if (impl_->host->running()) impl_->join();  // a run that ended on its own and was not waited for
  runtime::ServoConfig config;
  config.rate_hz = options.rate_hz;
  config.duration_s = options.duration_s;  // 0: until stop(); the loop's memory is the same either way
  impl_->host->start_nonrt(config);        // validates: may throw
}

runtime::ServoReport Player::stop() {
  if (!impl_->host || !impl_->host->running()) throw Error("not playing; start() first");
  impl_->host->request_stop_nonrt();
  return impl_->join();
}

runtime::ServoReport Player::wait() {
  if (!impl_->host || !impl_->host->running()) throw Error("not playing; start() first");
  return impl_->join();
}

bool Player::playing() const noexcept { return impl_->host && impl_->host->running() && !impl_->host->finished(); }

runtime::Device& Player::device() noexcept { return *impl_->device; }

const std::string& Player::device_calibration() const noexcept { return impl_->device_calibration; }

const std::string& Player::warning() const noexcept { return impl_->warning; }

void Player::set_warning_nonrt(std::string text) { impl_->warning = std::move(text); }

void Player::set_device_calibration_nonrt(std::string name) { impl_->device_calibration = std::move(name); }

}  // namespace sandpaper
