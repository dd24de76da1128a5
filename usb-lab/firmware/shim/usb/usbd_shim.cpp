// The parts of TinyUSB's device core (device/usbd.c) and of a device controller driver (dcd_*)
// that the firmware's HID class driver (class/hid/hid_device.c) and control transfer code
// (device/usbd_control.c), both compiled as they are, call into; with the lab's entry points
// (lab_usbd.hpp). Endpoint bookkeeping (busy, claimed, stalled), the SETUP dispatch to the class
// driver and the SET_CONFIGURATION / suspend callbacks follow usbd.c at the firmware's commit
// (process_control_request, usbd_edpt_*, tud_task's event cases); the "controller" completes
// transfers when the lab says the host did.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <mutex>

#include "lab_core.hpp"
#include "lab_usbd.hpp"
#include "tusb.h"
#include "device/dcd.h"
#include "device/usbd_pvt.h"

// From usbd_control.c (declared there, not in a header).
extern "C" {
void usbd_control_reset(void);
void usbd_control_set_request(tusb_control_request_t const* request);
void usbd_control_set_complete_callback(usbd_control_xfer_cb_t fp);
bool usbd_control_xfer_cb(uint8_t rhport, uint8_t ep_addr, xfer_result_t event, uint32_t xferred_bytes);
}

namespace sandpaper::usb_lab::usbd {
namespace {

constexpr unsigned endpoint_count = 16;
constexpr std::uint8_t hid_interface = 0;  // the function's only interface (renumbered to 0)

struct Endpoint {
  bool opened = false;
  bool busy = false;
  bool claimed = false;
  bool stalled = false;
  std::uint8_t* buffer = nullptr;  // the queued transfer (dcd_edpt_xfer)
  std::uint16_t length = 0;
};

struct Device {
  std::atomic<bool> initialized{false};  // tusb_init ran (read by the lab without the core)
  bool connected = false;    // a SETUP was seen (usbd.c sets it on the first one)
  bool suspended = false;
  std::uint8_t cfg_num = 0;
  bool ep0_stalled = false;  // dcd_edpt_stall on EP0 during the current control transfer
  Endpoint ep[endpoint_count][2];
  std::vector<std::uint8_t> function_descriptors;  // hidd_open keeps pointers into it
};

Device& device() {
  static auto* d = new Device();  // never destroyed: firmware threads outlive statics
  return *d;
}

Endpoint& endpoint(std::uint8_t ep_addr) {
  return device().ep[tu_edpt_number(ep_addr) % endpoint_count][tu_edpt_dir(ep_addr)];
}

// IN transfers queued by the driver, for the front end that waits without the core.
struct InQueue {
  std::mutex mutex;
  std::condition_variable queued;
  bool pending[endpoint_count] = {};  // queued and not yet taken
  std::uint16_t taken_length[endpoint_count] = {};
  std::vector<std::uint8_t> data[endpoint_count];
};

InQueue& in_queue() {
  static auto* q = new InQueue();
  return *q;
}

// usbd.c configuration_reset: every class driver's reset, then all endpoint and device state.
void configuration_reset() {
  hidd_reset(0);
  Device& d = device();
  for (auto& pair : d.ep) {
    for (auto& e : pair) e = Endpoint{};
  }
  const bool connected = d.connected;
  d.cfg_num = 0;
  d.suspended = false;
  d.connected = connected;
  std::lock_guard lock(in_queue().mutex);
  for (bool& p : in_queue().pending) p = false;
}

}  // namespace

bool configure(std::span<const std::uint8_t> hid_function_descriptors) {
  Device& d = device();
  d.connected = true;
  if (d.cfg_num != 0) configuration_reset();
  d.cfg_num = 1;
  d.function_descriptors.assign(hid_function_descriptors.begin(), hid_function_descriptors.end());
  auto const* itf = reinterpret_cast<tusb_desc_interface_t const*>(d.function_descriptors.data());
  const auto len = static_cast<std::uint16_t>(d.function_descriptors.size());
  if (hidd_open(0, itf, len) == 0) {
    d.cfg_num = 0;
    return false;
  }
  tud_mount_cb();
  return true;
}

void deconfigure() {
  Device& d = device();
  if (d.cfg_num == 0) return;
  configuration_reset();
  tud_umount_cb();
}

void suspend(bool suspended) {
  Device& d = device();
  if (!d.connected) return;  // usbd.c skips suspend/resume while not connected
  d.suspended = suspended;
  if (suspended) {
    tud_suspend_cb(false);  // remote wakeup never enabled by the host here
  } else {
    tud_resume_cb();
  }
}

ControlResult control(std::uint8_t bmRequestType, std::uint8_t bRequest, std::uint16_t wValue, std::uint16_t wIndex,
                      std::uint16_t wLength, std::span<const std::uint8_t> out_data) {
  Device& d = device();
  tusb_control_request_t request{};
  request.bmRequestType = bmRequestType;
  request.bRequest = bRequest;
  request.wValue = wValue;
  request.wIndex = wIndex;
  request.wLength = wLength;

  // usbd.c, DCD_EVENT_SETUP_RECEIVED: control endpoints free, then process_control_request.
  d.connected = true;
  d.ep0_stalled = false;
  for (std::uint8_t ep : {std::uint8_t{0x00}, std::uint8_t{0x80}}) {
    endpoint(ep).busy = false;
    endpoint(ep).claimed = false;
  }
  usbd_control_set_complete_callback(nullptr);

  bool ok = false;
  const auto type = request.bmRequestType_bit.type;
  if (type == TUSB_REQ_TYPE_VENDOR) {
    usbd_control_set_complete_callback(tud_vendor_control_xfer_cb);
    ok = tud_vendor_control_xfer_cb(0, CONTROL_STAGE_SETUP, &request);
  } else if (request.bmRequestType_bit.recipient == TUSB_REQ_RCPT_INTERFACE) {
    if (d.cfg_num != 0 && tu_u16_low(wIndex) == hid_interface) {
      usbd_control_set_complete_callback(hidd_control_xfer_cb);
      ok = hidd_control_xfer_cb(0, CONTROL_STAGE_SETUP, &request);
      // GET_INTERFACE and SET_INTERFACE must be answered even if the class driver does not.
      if (!ok && type == TUSB_REQ_TYPE_STANDARD &&
          (bRequest == TUSB_REQ_GET_INTERFACE || bRequest == TUSB_REQ_SET_INTERFACE)) {
        usbd_control_set_complete_callback(nullptr);
        static std::uint8_t alternate = 0;
        ok = bRequest == TUSB_REQ_GET_INTERFACE ? tud_control_xfer(0, &request, &alternate, 1)
                                                : tud_control_status(0, &request);
      }
    }
  } else if (request.bmRequestType_bit.recipient == TUSB_REQ_RCPT_ENDPOINT) {
    const std::uint8_t ep_addr = tu_u16_low(wIndex);
    const bool ours = d.cfg_num != 0 && endpoint(ep_addr).opened;
    if (type != TUSB_REQ_TYPE_STANDARD) {
      if (ours) {
        usbd_control_set_complete_callback(hidd_control_xfer_cb);
        ok = hidd_control_xfer_cb(0, CONTROL_STAGE_SETUP, &request);
      }
    } else if (bRequest == TUSB_REQ_GET_STATUS) {
      static std::uint16_t status = 0;
      status = usbd_edpt_stalled(0, ep_addr) ? 0x0001 : 0x0000;
      ok = tud_control_xfer(0, &request, &status, 2);
    } else if (bRequest == TUSB_REQ_CLEAR_FEATURE || bRequest == TUSB_REQ_SET_FEATURE) {
      if (wValue == TUSB_REQ_FEATURE_EDPT_HALT) {
        if (bRequest == TUSB_REQ_CLEAR_FEATURE) {
          usbd_edpt_clear_stall(0, ep_addr);
        } else {
          usbd_edpt_stall(0, ep_addr);
        }
      }
      if (ours) {  // forwarded to the driver, which cannot refuse; then the status stage
        usbd_control_set_complete_callback(hidd_control_xfer_cb);
        (void)hidd_control_xfer_cb(0, CONTROL_STAGE_SETUP, &request);
        usbd_control_set_complete_callback(nullptr);
        if (!endpoint(0x80).busy) tud_control_status(0, &request);
      }
      ok = true;
    }
  }

  ControlResult result;
  if (!ok) {
    result.stall = true;  // usbd.c stalls both control endpoints
    return result;
  }

  // The controller's side of EP0: complete whatever usbd_control.c queued until it queues nothing
  // more (after the status stage) or stalls. IN data goes to the reply, OUT data comes from the host.
  std::size_t out_offset = 0;
  const bool out_request = request.bmRequestType_bit.direction == TUSB_DIR_OUT;
  for (int step = 0; step < 4096 && !d.ep0_stalled; ++step) {
    std::uint8_t ep_addr = 0;
    if (endpoint(0x80).busy) {
      ep_addr = 0x80;
    } else if (endpoint(0x00).busy) {
      ep_addr = 0x00;
    } else {
      break;
    }
    Endpoint& e = endpoint(ep_addr);
    std::uint32_t transferred = 0;
    if (ep_addr == 0x80) {
      if (e.length > 0 && e.buffer) result.data.insert(result.data.end(), e.buffer, e.buffer + e.length);
      transferred = e.length;
    } else if (out_request) {
      const std::size_t remaining = out_data.size() > out_offset ? out_data.size() - out_offset : 0;
      transferred = static_cast<std::uint32_t>(std::min<std::size_t>(e.length, remaining));
      if (transferred > 0 && e.buffer) std::memcpy(e.buffer, out_data.data() + out_offset, transferred);
      out_offset += transferred;
    }
    e.busy = false;  // usbd.c, DCD_EVENT_XFER_COMPLETE
    e.claimed = false;
    usbd_control_xfer_cb(0, ep_addr, XFER_RESULT_SUCCESS, transferred);
  }
  if (d.ep0_stalled) {
    result.stall = true;
    result.data.clear();
  }
  return result;
}

bool out_transfer(std::uint8_t ep_addr, std::span<const std::uint8_t> data) {
  Endpoint& e = endpoint(ep_addr);
  if (device().cfg_num == 0 || !e.busy || e.stalled) return false;
  const auto n = static_cast<std::uint32_t>(std::min<std::size_t>(data.size(), e.length));
  if (n > 0 && e.buffer) std::memcpy(e.buffer, data.data(), n);
  e.busy = false;
  e.claimed = false;
  hidd_xfer_cb(0, ep_addr, XFER_RESULT_SUCCESS, n);
  return true;
}

bool wait_in_transfer(std::uint8_t ep_addr, std::vector<std::uint8_t>& data, std::chrono::microseconds wait) {
  InQueue& q = in_queue();
  const unsigned n = tu_edpt_number(ep_addr) % endpoint_count;
  std::unique_lock lock(q.mutex);
  if (!q.queued.wait_for(lock, wait, [&] { return q.pending[n]; })) return false;
  q.pending[n] = false;
  data = q.data[n];
  q.taken_length[n] = static_cast<std::uint16_t>(data.size());
  return true;
}

void complete_in_transfer(std::uint8_t ep_addr, bool delivered) {
  Endpoint& e = endpoint(ep_addr);
  if (!e.busy) return;
  std::uint16_t length = 0;
  {
    std::lock_guard lock(in_queue().mutex);
    length = in_queue().taken_length[tu_edpt_number(ep_addr) % endpoint_count];
  }
  e.busy = false;
  e.claimed = false;
  hidd_xfer_cb(0, ep_addr, delivered ? XFER_RESULT_SUCCESS : XFER_RESULT_FAILED, delivered ? length : 0);
}

bool stack_initialized() { return device().initialized; }

}  // namespace sandpaper::usb_lab::usbd

namespace lab = sandpaper::usb_lab::usbd;

extern "C" {

// ---- tusb.c and usbd.c: stack state and endpoint API for class drivers

// tusb_init() (USBdevice::Run): usbd's init, which initializes each class driver and usbd_control.
bool tusb_rhport_init(uint8_t, const tusb_rhport_init_t*) {
  lab::Device& d = lab::device();
  if (!d.initialized) {
    hidd_init();
    usbd_control_reset();
    d.initialized = true;
  }
  return true;
}

bool tusb_inited(void) { return lab::device().initialized; }

// The firmware's USB task loops on tud_task(); the lab delivers bus events through lab_usbd.hpp
// instead of an event queue, so the task has nothing to wait for and sleeps for good.
void tud_task_ext(uint32_t, bool) {
  namespace core = sandpaper::usb_lab::core;
  core::wait_released([] { core::park_forever(); });
}

// tusb.c: endpoint descriptor check at open (full speed: interrupt packets up to 64 bytes).
bool tu_edpt_validate(tusb_desc_endpoint_t const* desc_ep, tusb_speed_t) {
  const uint16_t size = tu_edpt_packet_size(desc_ep);
  switch (desc_ep->bmAttributes.xfer) {
    case TUSB_XFER_ISOCHRONOUS:
      return size <= 1023;
    case TUSB_XFER_BULK:
    case TUSB_XFER_INTERRUPT:
      return size <= 64;
    default:
      return false;
  }
}

tusb_speed_t tud_speed_get(void) { return TUSB_SPEED_FULL; }
bool tud_connected(void) { return lab::device().connected; }
bool tud_mounted(void) { return lab::device().cfg_num != 0; }
bool tud_suspended(void) { return lab::device().suspended; }
bool tud_remote_wakeup(void) { return false; }

bool usbd_edpt_open(uint8_t, tusb_desc_endpoint_t const* desc_ep) {
  TU_ASSERT(tu_edpt_number(desc_ep->bEndpointAddress) < lab::endpoint_count);
  TU_ASSERT(tu_edpt_validate(desc_ep, TUSB_SPEED_FULL));
  lab::endpoint(desc_ep->bEndpointAddress) = lab::Endpoint{};
  lab::endpoint(desc_ep->bEndpointAddress).opened = true;
  return true;
}

void usbd_edpt_close(uint8_t, uint8_t ep_addr) { lab::endpoint(ep_addr) = lab::Endpoint{}; }

bool usbd_open_edpt_pair(uint8_t rhport, uint8_t const* p_desc, uint8_t ep_count, uint8_t xfer_type, uint8_t* ep_out,
                         uint8_t* ep_in) {
  for (int i = 0; i < ep_count; i++) {
    auto const* desc_ep = reinterpret_cast<tusb_desc_endpoint_t const*>(p_desc);
    TU_ASSERT(TUSB_DESC_ENDPOINT == desc_ep->bDescriptorType && xfer_type == desc_ep->bmAttributes.xfer);
    TU_ASSERT(usbd_edpt_open(rhport, desc_ep));
    if (tu_edpt_dir(desc_ep->bEndpointAddress) == TUSB_DIR_IN) {
      *ep_in = desc_ep->bEndpointAddress;
    } else {
      *ep_out = desc_ep->bEndpointAddress;
    }
    p_desc = tu_desc_next(p_desc);
  }
  return true;
}

bool usbd_edpt_claim(uint8_t, uint8_t ep_addr) {
  lab::Endpoint& e = lab::endpoint(ep_addr);
  if (e.busy || e.claimed) return false;
  e.claimed = true;
  return true;
}

bool usbd_edpt_release(uint8_t, uint8_t ep_addr) {
  lab::Endpoint& e = lab::endpoint(ep_addr);
  const bool ok = e.claimed && !e.busy;
  if (ok) e.claimed = false;
  return ok;
}

bool usbd_edpt_xfer(uint8_t, uint8_t ep_addr, uint8_t* buffer, uint16_t total_bytes) {
  lab::Endpoint& e = lab::endpoint(ep_addr);
  TU_ASSERT(!e.busy);  // usbd.c: a transfer on a busy endpoint is a race
  e.busy = true;
  e.buffer = buffer;
  e.length = total_bytes;
  const unsigned n = tu_edpt_number(ep_addr) % lab::endpoint_count;
  if (n != 0 && tu_edpt_dir(ep_addr) == TUSB_DIR_IN) {
    lab::InQueue& q = lab::in_queue();
    {
      std::lock_guard lock(q.mutex);
      q.data[n].assign(buffer, buffer + total_bytes);
      q.pending[n] = true;
    }
    q.queued.notify_all();
  }
  return true;
}

bool usbd_edpt_busy(uint8_t, uint8_t ep_addr) { return lab::endpoint(ep_addr).busy; }

void usbd_edpt_stall(uint8_t rhport, uint8_t ep_addr) {
  dcd_edpt_stall(rhport, ep_addr);
  lab::endpoint(ep_addr).stalled = true;
  lab::endpoint(ep_addr).busy = true;
}

void usbd_edpt_clear_stall(uint8_t rhport, uint8_t ep_addr) {
  dcd_edpt_clear_stall(rhport, ep_addr);
  lab::endpoint(ep_addr).stalled = false;
  lab::endpoint(ep_addr).busy = false;
}

bool usbd_edpt_stalled(uint8_t, uint8_t ep_addr) { return lab::endpoint(ep_addr).stalled; }

// ---- The device controller driver calls the code above makes

void dcd_edpt_stall(uint8_t, uint8_t ep_addr) {
  if (tu_edpt_number(ep_addr) == 0) lab::device().ep0_stalled = true;
}

void dcd_edpt_clear_stall(uint8_t, uint8_t) {}

// ---- usbd.c's weak application callbacks (the firmware defines the ones it uses)

TU_ATTR_WEAK void tud_mount_cb(void) {}
TU_ATTR_WEAK void tud_umount_cb(void) {}
TU_ATTR_WEAK void tud_suspend_cb(bool remote_wakeup_en) { (void)remote_wakeup_en; }
TU_ATTR_WEAK void tud_resume_cb(void) {}
TU_ATTR_WEAK bool tud_vendor_control_xfer_cb(uint8_t, uint8_t, tusb_control_request_t const*) { return false; }

}  // extern "C"
