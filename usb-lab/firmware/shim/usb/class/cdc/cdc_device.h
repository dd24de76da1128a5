/*
 * TinyUSB's CDC device API as the OpenFFBoard firmware calls it, for the lab (cdc_sink.cpp).
 *
 * The firmware's source copy has no CDC class driver, and the lab's USB function is the HID
 * interface alone, so the CDC (serial command) port is a sink: no terminal is connected, nothing
 * is ever received, and what the firmware writes is accepted, dropped and reported complete at
 * once (so CDCcomm's send semaphore is given back as a reading host would). The descriptor
 * constants are the USB CDC 1.20 values TinyUSB's class/cdc/cdc.h gives them, for the
 * TUD_CDC_DESCRIPTOR template in usbd.h that usb_descriptors.cpp expands.
 */
#ifndef SANDPAPER_LAB_CDC_DEVICE_H
#define SANDPAPER_LAB_CDC_DEVICE_H

#include <stdbool.h>
#include <stdint.h>

#include "device/usbd.h"  // as TinyUSB's cdc_device.h: the firmware gets tusb_option.h through it

#ifdef __cplusplus
extern "C" {
#endif

// USB CDC 1.20: communications interface subclass, protocol and functional descriptor subtypes.
enum {
  CDC_COMM_SUBCLASS_ABSTRACT_CONTROL_MODEL = 0x02,
  CDC_COMM_PROTOCOL_NONE = 0x00,
  CDC_FUNC_DESC_HEADER = 0x00,
  CDC_FUNC_DESC_CALL_MANAGEMENT = 0x01,
  CDC_FUNC_DESC_ABSTRACT_CONTROL_MANAGEMENT = 0x02,
  CDC_FUNC_DESC_UNION = 0x06,
};

bool tud_cdc_n_connected(uint8_t itf);
uint32_t tud_cdc_n_available(uint8_t itf);
uint32_t tud_cdc_n_read(uint8_t itf, void* buffer, uint32_t bufsize);
uint32_t tud_cdc_n_write(uint8_t itf, void const* buffer, uint32_t bufsize);
uint32_t tud_cdc_n_write_flush(uint8_t itf);
uint32_t tud_cdc_n_write_available(uint8_t itf);
static inline bool tud_cdc_connected(void) { return tud_cdc_n_connected(0); }

// Application callbacks (the firmware's global_callbacks.cpp defines them).
void tud_cdc_rx_cb(uint8_t itf);
void tud_cdc_tx_complete_cb(uint8_t itf);

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_CDC_DEVICE_H
