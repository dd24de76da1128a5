# How often the lab's bus carries interrupt OUT transactions: WRITES blocking writes of an output
# report to a device's hidraw node, back to back (sandpaper-lab-writes). Each write returns once
# usbhid's OUT transfer is done, so their rate is the bus's (or the device's, if it is slower).
#   BUS_DEVICE=hid      the kernel's HID function (usb_f_hid; its OUT endpoint has bInterval 1 as the
#                       host sees it); `cat` drains /dev/hidg0.
#   BUS_DEVICE=ffboard  the emulated OpenFFBoard (bInterval 1): a no-op Device Control report (no bit
#                       set), taken by the firmware's program through FunctionFS; its log has each arrival.
# Writes /out/busrate.json: the writes, the time they took (CLOCK_MONOTONIC), the longest and shortest
# time between two, the endpoint's bInterval as the host saw it, the bus the lab gave the guest
# (/lab/bus), and on the lab's own bus the frames it ran around the writes (and over how many cs) and
# the shortest time it has had between two frames' starts.
# tools/usb-lab/run --bus-rate.
# shellcheck shell=dash disable=SC2015 source-path=SCRIPTDIR
read -r bus < /lab/bus
case ${BUS_DEVICE:-ffboard} in
  ffboard)
    . /lab/ffboard.sh
    ffboard_plug --hand scan --speed 10 --extent 10 || exit 1
    dev=$FFB_USB_DEV report=0c00 ;;
  hid)
    . "$LAB_GADGET"
    # Vendor page, one 8-byte output report without an ID (hidraw's writes then lead with a 0).
    desc="06 00 ff 09 01 a1 01 09 02 15 00 26 ff 00 75 08 95 08 91 02 c0"
    gadget_create busrate 0x1d6b 0x0104 product="USB lab bus rate" &&
      gadget_add_hid busrate out "$desc" report_length=8 &&
      gadget_bind busrate dummy_udc.1 || exit 1
    lab_wait_usb_device 0x1d6b 0x0104 30 && lab_wait_hidraw "$LAB_USB_DEV" 30 || exit 1
    dev=$LAB_USB_DEV
    f=/sys/kernel/config/usb_gadget/busrate/functions/hid.out
    [ -e /dev/hidg0 ] || { IFS=: read -r major minor < "$f/dev" && mknod /dev/hidg0 c "$major" "$minor"; }
    cat /dev/hidg0 > /dev/null &
    reader=$!
    report=000102030405060708 ;;
  *) echo "busrate: BUS_DEVICE is hid or ffboard" >&2; exit 2 ;;
esac
node=/dev/$LAB_HIDRAW
# The OUT endpoint's bInterval as the host's USB core read it (its sysfs directory may come a moment
# after the hidraw node).
_out_interval() {
  local ep
  for ep in "$dev"/*:1.0/ep_0[1-9]*; do
    [ "$(cat "$ep/direction" 2>/dev/null)" = out ] && read -r interval < "$ep/bInterval" && return 0
  done
  return 1
}
interval=
lab_poll 5 "the OUT endpoint of $dev in sysfs" _out_interval
lab_step "bus $bus: writing $WRITES reports to $node (OUT bInterval $interval)"
# The lab's own dummy_hcd counts the frames it runs (usb-lab/bus/); the stock one has no counter.
frames_file=/sys/module/dummy_hcd/parameters/usb_lab_frames
f0=$(cat "$frames_file" 2>/dev/null)
lab_now
t0=$LAB_NOW
result=$("$LAB_WRITES" "$node" "$WRITES" "$report")
status=$?
lab_now
t1=$LAB_NOW
f1=$(cat "$frames_file" 2>/dev/null)
frames=null
[ -n "$f0" ] && [ -n "$f1" ] && frames=$((f1 - f0))
lab_step "sandpaper-lab-writes (status $status): $result"
# "writes N seconds S max_gap_ms G min_gap_ms M"
# shellcheck disable=SC2086  # (split on purpose: the words of the line above)
set -- $result
writes=${2:-0} seconds=${4:-0} max_gap=${6:-0} min_gap=${8:-0}
if [ "${BUS_DEVICE:-ffboard}" = ffboard ]; then
  ffboard_stop
else
  kill "$reader" 2>/dev/null
  gadget_remove busrate
fi
echo "{\"device\": \"${BUS_DEVICE:-ffboard}\", \"bus\": \"$bus\", \"out_binterval\": \"$interval\", \"status\": $status," \
  "\"writes\": $writes, \"seconds\": $seconds, \"max_gap_ms\": $max_gap, \"min_gap_ms\": $min_gap," \
  "\"frames\": $frames, \"frames_window_cs\": $((t1 - t0)), \"dummy_hcd_taint\": \"$(cat /sys/module/dummy_hcd/taint)\"," \
  "\"min_frame_gap_ns\": $(cat /sys/module/dummy_hcd/parameters/usb_lab_min_frame_gap_ns 2>/dev/null || echo null)}" \
  > /out/busrate.json
