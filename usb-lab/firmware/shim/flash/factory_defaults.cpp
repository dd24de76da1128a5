// The lab board's factory defaults: what Flash_Write_Defaults() (flash_helpers.cpp) writes at the
// first start, in the form the firmware asks a target to give them (FLASH_FACTORY_DEFAULTS_OVERRIDE).
// Only the motor drivers: axis X uses driver 11 and axis Y driver 12, the simulated drivers
// (shim/drivers/RmdMotorCAN.h), no separate encoder (they have one). Everything else keeps the
// firmware's own defaults. Axis config word: bits 0-5 encoder type, bits 6-11 driver type
// (Axis::decodeConfFromInt).
#include <array>
#include <cstdint>
#include <span>
#include <utility>

#include "eeprom_addresses.h"
#include "flash_helpers.h"

namespace {

constexpr uint16_t axis_config(uint16_t driver, uint16_t encoder) {
  return static_cast<uint16_t>((encoder & 0x3f) | ((driver & 0x3f) << 6));
}

const auto lab_flash_defaults = std::to_array<const std::pair<uint16_t, uint16_t>>({
    {ADR_AXIS1_CONFIG, axis_config(11, 0)},
    {ADR_AXIS2_CONFIG, axis_config(12, 0)},
});

}  // namespace

const std::span<const std::pair<uint16_t, uint16_t>> flash_factory_defaults = lab_flash_defaults;
