// The firmware's EEPROM emulation (eeprom.h: EE_Init, EE_ReadVariable, EE_WriteVariable,
// EE_Format) as an in-memory map from virtual address to 16-bit value, in place of eeprom.c,
// which programs flash sectors 1 and 2 of the STM32F407 through absolute addresses.
// flash_helpers.cpp (Flash_Read, Flash_Write, ...) is the firmware's own, on top of this.
// The map starts empty, as a freshly erased board's flash.
#include <cstdint>
#include <map>
#include <mutex>

extern "C" {
#include "eeprom.h"  // declared with C linkage, as flash_helpers.h includes it
}

namespace {

struct Store {
  std::mutex mutex;
  std::map<uint16_t, uint16_t> values;
};

Store& store() {
  static auto* s = new Store();  // never destroyed: firmware threads outlive statics
  return *s;
}

}  // namespace

uint16_t EE_Init(void) { return EE_OK; }

// 0 when found (and *Data set), 1 when the variable was never written, as eeprom.c returns.
uint16_t EE_ReadVariable(uint16_t VirtAddress, uint16_t* Data) {
  std::lock_guard lock(store().mutex);
  const auto it = store().values.find(VirtAddress);
  if (it == store().values.end()) return 1;
  *Data = it->second;
  return 0;
}

uint16_t EE_WriteVariable(uint16_t VirtAddress, uint16_t Data) {
  std::lock_guard lock(store().mutex);
  store().values[VirtAddress] = Data;
  return HAL_OK;
}

HAL_StatusTypeDef EE_Format() {
  std::lock_guard lock(store().mutex);
  store().values.clear();
  return HAL_OK;
}
