# Issue 54's lab test 1: `sandpaper devices` finds the emulated OpenFFBoard and names its
# calibration file; a second force-feedback gadget with an unknown VID:PID is listed as unknown
# and not opened (its kernel driver stays bound). Writes /out/devices.txt and /out/enumerate.json.
. /lab/ffboard.sh
ffboard_plug --hand still || exit 1
ffb_driver_before=$(ffboard_interface_driver)
read -r ffb_speed < "$FFB_USB_DEV/speed"

# The stranger: the kernel's HID function with a force-feedback report descriptor (STRANGER_HEX).
gadget_create stranger "$STRANGER_VID" "$STRANGER_PID" product="Unknown force feedback" &&
gadget_add_hid stranger pid "$STRANGER_HEX" report_length=64 &&
gadget_bind stranger dummy_udc.1 &&
lab_wait_usb_device "$STRANGER_VID" "$STRANGER_PID" 60 &&
stranger_dev=$LAB_USB_DEV &&
lab_wait_hidraw "$stranger_dev" 60 || exit 1
stranger_hidraw=$LAB_HIDRAW

"$SANDPAPER" devices > /out/devices.txt 2>&1
devices_status=$?
stranger_hidraw_after=
lab_wait_hidraw "$stranger_dev" 1 && stranger_hidraw_after=$LAB_HIDRAW
ffb_driver_after=$(ffboard_interface_driver)
cat /out/devices.txt
ffboard_stop
cat > /out/enumerate.json <<JSON
{"devices_status": $devices_status, "ffboard_speed": "$ffb_speed",
 "ffboard_driver_before": "$ffb_driver_before", "ffboard_driver_after": "$ffb_driver_after",
 "stranger_hidraw_before": "$stranger_hidraw", "stranger_hidraw_after": "$stranger_hidraw_after"}
JSON
cat /out/enumerate.json
