# shellcheck shell=dash disable=SC2015,SC2034
# (dash: busybox sh's dialect, with `local`. SC2015: `a && b || fail` reports a failure of any
# step. SC2034: LAB_USB_DEV, LAB_HIDRAW and LAB_INPUT are the waits' results, for the caller.)
# Sourced by the USB lab's scenario scripts in the guest (busybox sh): `. "$LAB_GADGET"`.
#
# The device side: configfs gadgets on dummy_hcd's UDCs (dummy_udc.0, dummy_udc.1), with a
# FunctionFS function (a userspace program plays the device) or the kernel's HID function (a device
# that needs no program). The host side: waits until the kernel enumerated a device and a driver
# bound it. Every wait is a bounded poll of a sysfs or /dev condition; on timeout it says what it was
# waiting for and returns 1. Functions return non-zero on failure and never exit the caller.
#
#   gadget_create NAME VID PID [bcd=0x0100] [manufacturer=..] [product=..] [serial=..]
#                 [speed=full-speed] [power=100] [bcdusb=0x0200] [class=0] [subclass=0] [protocol=0]
#   gadget_add_ffs NAME FUNC          FunctionFS function, mounted at /dev/ffs-FUNC
#   gadget_wait_ffs FUNC [EP] [SECS]  until the program wrote its descriptors (EP file, default ep1)
#   gadget_add_hid NAME FUNC HEX [report_length=8] [subclass=0] [protocol=0]
#                                     kernel HID function with report descriptor HEX; /dev/hidgN
#   gadget_bind NAME UDC              plug in: the host starts enumerating
#   gadget_unbind NAME                unplug
#   gadget_remove NAME                unplug and take the gadget apart (stop FunctionFS programs first)
#   lab_wait_usb_device VID PID [SECS]  sets LAB_USB_DEV (its /sys/bus/usb/devices path)
#   lab_wait_usb_gone VID PID [SECS]
#   lab_wait_hidraw DEV [SECS]          sets LAB_HIDRAW (hidrawN) for a device's interfaces
#   lab_wait_input DEV [SECS]           sets LAB_INPUT (eventN)
#   lab_wait_file PATH [SECS]
#   lab_wait_line FILE PATTERN [SECS]   until a line of FILE matches (grep -E) PATTERN: a program's
#                                       readiness line in its log
#   lab_poll SECS WHAT COMMAND...       the bounded poll the others are made of

GADGET_CONFIGFS=/sys/kernel/config/usb_gadget
LAB_POLL_INTERVAL=${LAB_POLL_INTERVAL:-0.02}
LAB_DEFAULT_TIMEOUT=${LAB_DEFAULT_TIMEOUT:-30}

lab_fail() { echo "lab: $*" >&2; return 1; }

# LAB_NOW: the guest's uptime in hundredths of a second, without forking (polls run often).
lab_now() {
  local up
  read -r up _ < /proc/uptime
  # "1" in front keeps a fraction such as "08" from reading as octal.
  LAB_NOW=$(( ${up%.*} * 100 + 1${up#*.} - 100 ))
}

# A line on the console with the guest's uptime: where a scenario stood when it stopped speaking.
lab_step() {
  lab_now
  printf 'lab: [%d.%02d s] %s\n' $(( LAB_NOW / 100 )) $(( LAB_NOW % 100 )) "$*"
}

lab_poll() {
  local secs="$1" what="$2" deadline
  shift 2
  lab_now
  deadline=$(( LAB_NOW + secs * 100 ))
  while ! "$@"; do
    lab_now
    if [ "$LAB_NOW" -ge "$deadline" ]; then
      lab_fail "timed out after ${secs} s waiting for $what"
      return 1
    fi
    sleep "$LAB_POLL_INTERVAL"
  done
}

# "0x1D6B" -> "1d6b", as sysfs writes idVendor and idProduct.
lab_hex4() { printf '%04x' $(( $1 )); }

_lab_exists() { [ -e "$1" ]; }

lab_wait_file() { lab_poll "${2:-$LAB_DEFAULT_TIMEOUT}" "$1" _lab_exists "$1"; }

_lab_has_line() { [ -f "$1" ] && grep -Eq "$2" "$1"; }

lab_wait_line() {
  lab_poll "${3:-$LAB_DEFAULT_TIMEOUT}" "a line matching '$2' in $1" _lab_has_line "$1" "$2"
}

_lab_find_usb() {
  local d v p
  for d in /sys/bus/usb/devices/*; do
    [ -f "$d/idVendor" ] || continue
    read -r v < "$d/idVendor"
    read -r p < "$d/idProduct"
    if [ "$v" = "$1" ] && [ "$p" = "$2" ]; then
      LAB_USB_DEV=$d
      return 0
    fi
  done
  return 1
}

_lab_no_usb() { ! _lab_find_usb "$1" "$2"; }

lab_wait_usb_device() {
  local v p
  v=$(lab_hex4 "$1") p=$(lab_hex4 "$2")
  LAB_USB_DEV=
  lab_poll "${3:-$LAB_DEFAULT_TIMEOUT}" "USB device $v:$p under /sys/bus/usb/devices" \
    _lab_find_usb "$v" "$p"
}

lab_wait_usb_gone() {
  local v p
  v=$(lab_hex4 "$1") p=$(lab_hex4 "$2")
  lab_poll "${3:-$LAB_DEFAULT_TIMEOUT}" "USB device $v:$p to go away" _lab_no_usb "$v" "$p"
}

# A class device (hidraw, input event) under one of DEV's interfaces, with its /dev node made.
_lab_find_class() {
  local n
  for n in $1; do
    if [ -e "$n" ] && [ -e "/dev/$3${n##*/}" ]; then
      eval "$2=\${n##*/}"
      return 0
    fi
  done
  return 1
}

lab_wait_hidraw() {
  LAB_HIDRAW=
  lab_poll "${2:-$LAB_DEFAULT_TIMEOUT}" "a hidraw node for $1 (usbhid, hid-generic)" \
    _lab_find_class "$1/*:*/*:*/hidraw/hidraw*" LAB_HIDRAW ""
}

lab_wait_input() {
  LAB_INPUT=
  lab_poll "${2:-$LAB_DEFAULT_TIMEOUT}" "an input event node for $1" \
    _lab_find_class "$1/*:*/*:*/input/input*/event*" LAB_INPUT "input/"
}

gadget_create() {
  local name="$1" vid="$2" pid="$3" g kv
  local bcd=0x0100 manufacturer="Sandpaper USB lab" product="USB lab gadget" serial="$1"
  local speed=full-speed power=100 bcdusb=0x0200 class=0 subclass=0 protocol=0
  shift 3 || { lab_fail "gadget_create NAME VID PID [key=value...]"; return 1; }
  for kv; do
    case $kv in
      bcd=*) bcd=${kv#*=} ;;
      manufacturer=*) manufacturer=${kv#*=} ;;
      product=*) product=${kv#*=} ;;
      serial=*) serial=${kv#*=} ;;
      speed=*) speed=${kv#*=} ;;
      power=*) power=${kv#*=} ;;
      bcdusb=*) bcdusb=${kv#*=} ;;
      class=*) class=${kv#*=} ;;
      subclass=*) subclass=${kv#*=} ;;
      protocol=*) protocol=${kv#*=} ;;
      *) lab_fail "gadget_create: unknown option '$kv'"; return 1 ;;
    esac
  done
  [ -d "$GADGET_CONFIGFS" ] || { lab_fail "$GADGET_CONFIGFS is missing (libcomposite, configfs)"; return 1; }
  g=$GADGET_CONFIGFS/$name
  mkdir "$g" || { lab_fail "gadget $name: mkdir $g failed"; return 1; }
  echo "$vid" > "$g/idVendor" &&
  echo "$pid" > "$g/idProduct" &&
  echo "$bcd" > "$g/bcdDevice" &&
  echo "$bcdusb" > "$g/bcdUSB" &&
  echo "$class" > "$g/bDeviceClass" &&
  echo "$subclass" > "$g/bDeviceSubClass" &&
  echo "$protocol" > "$g/bDeviceProtocol" &&
  echo "$speed" > "$g/max_speed" &&
  mkdir "$g/strings/0x409" &&
  echo "$manufacturer" > "$g/strings/0x409/manufacturer" &&
  echo "$product" > "$g/strings/0x409/product" &&
  echo "$serial" > "$g/strings/0x409/serialnumber" &&
  mkdir "$g/configs/c.1" &&
  echo "$power" > "$g/configs/c.1/MaxPower" &&
  mkdir "$g/configs/c.1/strings/0x409" &&
  echo "$product" > "$g/configs/c.1/strings/0x409/configuration" ||
    { lab_fail "gadget $name: configfs refused a setting"; return 1; }
}

gadget_add_ffs() {
  local g="$GADGET_CONFIGFS/$1" func="$2"
  mkdir "$g/functions/ffs.$func" &&
  ln -s "$g/functions/ffs.$func" "$g/configs/c.1/" &&
  mkdir -p "/dev/ffs-$func" &&
  mount -t functionfs "$func" "/dev/ffs-$func" ||
    { lab_fail "gadget $1: FunctionFS function $func failed"; return 1; }
}

# FunctionFS creates the endpoint files once the program wrote its descriptors and strings to
# ep0; binding before that fails.
gadget_wait_ffs() {
  lab_poll "${3:-$LAB_DEFAULT_TIMEOUT}" "the FunctionFS program's descriptors (/dev/ffs-$1/${2:-ep1})" \
    _lab_exists "/dev/ffs-$1/${2:-ep1}"
}

gadget_add_hid() {
  local g="$GADGET_CONFIGFS/$1" func="$2" hex="$3" kv f size
  local report_length=8 subclass=0 protocol=0
  shift 3 || { lab_fail "gadget_add_hid NAME FUNC HEX [key=value...]"; return 1; }
  for kv; do
    case $kv in
      report_length=*) report_length=${kv#*=} ;;
      subclass=*) subclass=${kv#*=} ;;
      protocol=*) protocol=${kv#*=} ;;
      *) lab_fail "gadget_add_hid: unknown option '$kv'"; return 1 ;;
    esac
  done
  f=$g/functions/hid.$func
  hex=$(echo "$hex" | tr -d ' \n')
  mkdir "$f" &&
  echo "$protocol" > "$f/protocol" &&
  echo "$subclass" > "$f/subclass" &&
  echo "$report_length" > "$f/report_length" &&
  # One write: each write to report_desc replaces the descriptor.
  echo "$hex" | xxd -r -p > "$f/report_desc" &&
  ln -s "$f" "$g/configs/c.1/" ||
    { lab_fail "gadget $1: HID function $func failed"; return 1; }
  size=$(wc -c < "$f/report_desc")
  [ "$size" -eq $(( ${#hex} / 2 )) ] ||
    { lab_fail "gadget $1: report descriptor is $size bytes, not $(( ${#hex} / 2 ))"; return 1; }
}

gadget_bind() {
  local g="$GADGET_CONFIGFS/$1" udc="$2" have="" u
  if [ ! -e "/sys/class/udc/$udc" ]; then
    for u in /sys/class/udc/*; do have="$have ${u##*/}"; done
    lab_fail "no UDC $udc (there are:$have)"
    return 1
  fi
  echo "$udc" > "$g/UDC" || { lab_fail "gadget $1: binding to $udc failed"; return 1; }
}

gadget_unbind() {
  local g="$GADGET_CONFIGFS/$1" udc
  read -r udc < "$g/UDC" 2>/dev/null
  [ -z "$udc" ] || echo "" > "$g/UDC" || { lab_fail "gadget $1: unbinding failed"; return 1; }
}

gadget_remove() {
  local g="$GADGET_CONFIGFS/$1" c f ok=0
  [ -d "$g" ] || return 0
  gadget_unbind "$1" || ok=1
  for c in "$g"/configs/*; do
    for f in "$c"/*; do [ -L "$f" ] && { rm "$f" || ok=1; }; done
    for f in "$c"/strings/*; do rmdir "$f" || ok=1; done
    rmdir "$c" || ok=1
  done
  for f in "$g"/functions/*; do
    [ -e "$f" ] || continue
    case ${f##*/} in
      ffs.*) umount "/dev/ffs-${f##*/ffs.}" && rmdir "/dev/ffs-${f##*/ffs.}" || ok=1 ;;
    esac
    rmdir "$f" || ok=1
  done
  for f in "$g"/strings/*; do rmdir "$f" || ok=1; done
  rmdir "$g" || ok=1
  [ "$ok" -eq 0 ] || lab_fail "gadget $1: not all of it could be removed"
}
