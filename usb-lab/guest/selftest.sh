# The USB lab's selftest scenario (lab.py selftest): plugs a kernel usb_f_hid joystick into
# dummy_udc.1 and checks from sysfs that the host side enumerated it at full speed and that usbhid
# and hid-generic bound it; runs each binary listed in /lab/binaries to show its libraries load.
# Writes /out/selftest.json; exits 0 only when everything held.
# shellcheck shell=dash disable=SC2015 source-path=SCRIPTDIR source=gadget.sh
. "$LAB_GADGET"

vid=0x1d6b pid=0x0104
# A 2-axis joystick: Generic Desktop / Joystick, X and Y, 8 bits each, in one 2-byte input report.
desc="05 01 09 04 a1 01 09 01 a1 00 09 30 09 31 15 81 25 7f 75 08 95 02 81 02 c0 c0"
failures=""
fail() { echo "selftest: FAIL: $*"; failures="$failures $1"; }

lab_now; t_bind=$LAB_NOW
gadget_create selftest $vid $pid product="USB lab selftest joystick" &&
gadget_add_hid selftest js "$desc" report_length=2 &&
gadget_bind selftest dummy_udc.1 || fail gadget "the gadget could not be made and plugged"

speed="" driver="" hid_driver=""
if lab_wait_usb_device $vid $pid 30; then
  lab_now; t_enum=$LAB_NOW
  read -r speed < "$LAB_USB_DEV/speed"
  [ "$speed" = 12 ] || fail speed "$LAB_USB_DEV enumerated at $speed Mb/s, not 12 (full speed)"
  if lab_wait_hidraw "$LAB_USB_DEV" 30; then
    lab_now; t_hidraw=$LAB_NOW
    intf=$LAB_USB_DEV/${LAB_USB_DEV##*/}:1.0
    driver=$(basename "$(readlink "$intf/driver")")
    for hid in "$intf"/*:*:*.*; do
      hid_driver=$(basename "$(readlink "$hid/driver")")
    done
    [ "$driver" = usbhid ] || fail driver "interface driver is '$driver', not usbhid"
    [ "$hid_driver" = hid-generic ] || fail hid_driver "HID driver is '$hid_driver', not hid-generic"
  else
    fail hidraw "no hidraw node"
  fi
else
  fail enumerate "the host side never saw $vid:$pid"
fi

# The unplug: the device goes away and the gadget comes apart.
gadget_unbind selftest && lab_wait_usb_gone $vid $pid 30 || fail unplug "the device did not go away"
gadget_remove selftest || fail remove "the gadget did not come apart"

binaries_json=""
if [ -f /lab/binaries ]; then
  while read -r b; do
    out=$("$b" --version 2>&1 </dev/null)
    rc=$?
    case $out in *"error while loading shared libraries"*) rc=127 ;; esac
    [ "$rc" -ne 127 ] || fail binary "$b did not load: $out"
    binaries_json="$binaries_json${binaries_json:+,}{\"path\":\"$b\",\"status\":$rc}"
  done < /lab/binaries
fi

read -r uptime _ < /proc/uptime
cat > /out/selftest.json <<EOF
{"vid":"$vid","pid":"$pid","udc":"dummy_udc.1","device":"${LAB_USB_DEV##*/}","speed":"$speed",
 "interface_driver":"$driver","hid_driver":"$hid_driver","hidraw":"$LAB_HIDRAW",
 "enumerate_cs":$(( ${t_enum:-0} - t_bind )),"hidraw_cs":$(( ${t_hidraw:-0} - t_bind )),
 "binaries":[$binaries_json],"failures":"${failures# }","uptime":"$uptime"}
EOF
cat /out/selftest.json
if [ -n "$failures" ]; then
  echo "selftest: FAIL:$failures"
  exit 1
fi
echo "selftest: PASS"
