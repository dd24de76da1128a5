# Install rules: the libraries an application links, their headers, the shipped data, a CMake
# package (find_package(Sandpaper) -> Sandpaper::sandpaper) and a pkg-config file (sandpaper.pc).
# Layout (GNUInstallDirs): lib/libsandpaper_*.a, include/sandpaper/..., share/sandpaper/library,
# share/sandpaper/calibration, lib/cmake/Sandpaper/, lib/pkgconfig/sandpaper.pc.
# tests/consumer/ checks the result from outside the source tree.
include(CMakePackageConfigHelpers)

set(SANDPAPER_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Sandpaper)
# Exported as Sandpaper::<name>: the API and what it is built from, among them the device factory
# (sandpaper_devices), the USB HID PID driver (sandpaper_usb) and the input event driver
# (sandpaper_evdev) that Player::usb opens joysticks with, so an application links libusb and libevdev.
set_target_properties(sandpaper_schema PROPERTIES EXPORT_NAME schema)
set_target_properties(sandpaper_calibration PROPERTIES EXPORT_NAME calibration)
set_target_properties(sandpaper_compiler PROPERTIES EXPORT_NAME compiler)
set_target_properties(sandpaper_runtime PROPERTIES EXPORT_NAME runtime)
set_target_properties(sandpaper_usb PROPERTIES EXPORT_NAME usb)
set_target_properties(sandpaper_evdev PROPERTIES EXPORT_NAME evdev)
set_target_properties(sandpaper_devices PROPERTIES EXPORT_NAME devices)
install(TARGETS sandpaper_api sandpaper_compiler sandpaper_image_io sandpaper_data_dirs_installed sandpaper_calibration
                sandpaper_runtime sandpaper_usb sandpaper_evdev sandpaper_devices sandpaper_schema
  EXPORT SandpaperTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# Public headers. The calibration fitting headers belong to sandpaper_calibration_fit, which
# only the CLI uses and which is not installed.
foreach(_dir schema calibration compiler runtime api)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
    PATTERN csv.hpp EXCLUDE PATTERN device_fit.hpp EXCLUDE PATTERN fit.hpp EXCLUDE
    PATTERN fit_error.hpp EXCLUDE PATTERN regression.hpp EXCLUDE)
endforeach()

# The data the installed libraries read by default (compiler/src/library/data_dirs.cpp, the "installed"
# variant): the library as it is, and calibration/ without its code.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/library/ DESTINATION ${SANDPAPER_INSTALL_DATA_DIR}/library
  PATTERN .index EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/calibration/ DESTINATION ${SANDPAPER_INSTALL_DATA_DIR}/calibration
  PATTERN include EXCLUDE PATTERN src EXCLUDE PATTERN CMakeLists.txt EXCLUDE)

# Only an install has sandpaper/package_location.h: applications including the API headers from it
# register where its data lies, from where the header lies (relocatable; compiler/data_dirs.hpp).
file(RELATIVE_PATH SANDPAPER_HEADER_DIR_TO_DATA ${CMAKE_INSTALL_FULL_INCLUDEDIR}/sandpaper ${SANDPAPER_INSTALL_FULL_DATA_DIR})
configure_file(${CMAKE_CURRENT_LIST_DIR}/package_location.h.in
  ${CMAKE_CURRENT_BINARY_DIR}/package_location/sandpaper/package_location.h @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/package_location/sandpaper/package_location.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sandpaper)

install(EXPORT SandpaperTargets NAMESPACE Sandpaper:: DESTINATION ${SANDPAPER_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/SandpaperConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/SandpaperConfig.cmake
  INSTALL_DESTINATION ${SANDPAPER_CMAKE_DIR}
  PATH_VARS SANDPAPER_INSTALL_DATA_DIR)
# 0.x: minor versions may break the API, so only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/SandpaperConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/SandpaperConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/SandpaperConfigVersion.cmake
  DESTINATION ${SANDPAPER_CMAKE_DIR})

# The .pc finds the prefix from its own place (${pcfiledir}): lib/pkgconfig/../.. or, with a
# multiarch libdir, lib/x86_64-linux-gnu/pkgconfig/../../..
file(RELATIVE_PATH SANDPAPER_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" SANDPAPER_PC_TO_PREFIX "${SANDPAPER_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/sandpaper.pc.in ${CMAKE_CURRENT_BINARY_DIR}/sandpaper.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sandpaper.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The glTF-Transform extension for MPEG_haptic_material (docs/GLTF.md), for pipelines that read and
# write Sandpaper's assets.
install(FILES ${PROJECT_SOURCE_DIR}/interop/gltf-transform/mpeg-haptic-material.js
  ${PROJECT_SOURCE_DIR}/interop/gltf-transform/gltf-transform.config.mjs
  ${PROJECT_SOURCE_DIR}/interop/gltf-transform/package.json DESTINATION ${SANDPAPER_INSTALL_DATA_DIR}/gltf-transform)
