# Writes the udev rules file (`sandpaper devices --udev-rules`, docs/DEVICES.md "No root") to OUT,
# through a temporary file renamed into place, so that a failed run leaves no half a file behind.
#   cmake -DSANDPAPER=bin/sandpaper -DCALIBRATION=calibration -DOUT=udev/70-sandpaper.rules -P udev_rules.cmake
execute_process(COMMAND ${SANDPAPER} devices --udev-rules --calibration ${CALIBRATION}
  OUTPUT_FILE ${OUT}.tmp RESULT_VARIABLE _status ERROR_VARIABLE _err)
if(NOT _status EQUAL 0)
  file(REMOVE ${OUT}.tmp)
  message(FATAL_ERROR "sandpaper devices --udev-rules failed (${_status}): ${_err}")
endif()
file(RENAME ${OUT}.tmp ${OUT})
