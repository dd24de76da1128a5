// The CDC serial port as a sink (class/cdc/cdc_device.h says why): nothing connected, nothing
// received, everything written accepted and dropped; a flush completes at once.
#include <cstdint>

#include "tusb.h"

extern "C" {

bool tud_cdc_n_connected(uint8_t) { return false; }
uint32_t tud_cdc_n_available(uint8_t) { return 0; }
uint32_t tud_cdc_n_read(uint8_t, void*, uint32_t) { return 0; }
uint32_t tud_cdc_n_write(uint8_t, void const*, uint32_t bufsize) { return bufsize; }
uint32_t tud_cdc_n_write_available(uint8_t) { return CFG_TUD_CDC_TX_BUFSIZE; }

// The "host" took the data: the class driver's transfer-complete callback, as cdcd_xfer_cb makes it.
uint32_t tud_cdc_n_write_flush(uint8_t itf) {
  tud_cdc_tx_complete_cb(itf);
  return 0;
}

}  // extern "C"
