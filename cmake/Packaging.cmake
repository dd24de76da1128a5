# A Debian package of the install (cpack -G DEB; docs/API.md, "A Debian package"):
#   cmake --build build && (cd build && cpack -G DEB)    # -> build/sandpaper_<version>_<arch>.deb
#   sudo apt-get install ./build/sandpaper_*.deb
# One package, `sandpaper`, holding everything `cmake --install` installs, under /usr: the CLI and the
# player, the data (share/sandpaper/{library,calibration}), the Python module, and what an application
# builds against (headers, the static libraries, the CMake package and sandpaper.pc). The developer
# part is small (static archives and headers, no shared library), so it is not split off; what an
# application needs beyond it (nlohmann-json, toml++, glm, OpenImageIO headers) is Suggested.
# Depends comes from dpkg-shlibdeps (dpkg-dev) on the installed programs and the Python module, plus
# the Python the module was built for. tests/consumer/deb_package_test.sh (ctest install.deb) checks it.
# The programs and the module find the data from where they lie, so nothing here is prefix-specific;
# only the Python module moves, to the place Debian's python3 looks in for /usr (see below).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME sandpaper)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "Sandpaper maintainers")
set(CPACK_PACKAGE_CONTACT "Sandpaper maintainers <maintainers@users.noreply.h-seed-a7aea37b.example>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "haptic materials compiled from text and played on force-feedback joysticks")
# The extended description (CPackDeb puts the summary above it and indents its lines).
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "Sandpaper compiles a material described in text, or named from its world
haptics library, into a patch program and plays it on a force-feedback
joystick or a simulated one. This package holds the sandpaper command line
tool and the sandpaper-play player, the library and calibration data, the
Python module, and the headers, static libraries, CMake package
(find_package(Sandpaper)) and pkg-config file for applications.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)  # the RelWithDebInfo programs are ~200 MB with their debug information
set(CPACK_INSTALL_DEFAULT_DIRECTORY_PERMISSIONS
  OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # sandpaper_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)   # runtime libraries (OpenImageIO, libusb, sqlite, ...) by dpkg-shlibdeps
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(_sandpaper_deb_depends)
if(SANDPAPER_PYTHON AND SANDPAPER_PYTHON_VERSION)
  # The module is built for one Python (its file name says cpython-3XY) and uses numpy for its arrays.
  string(REPLACE "." ";" _py_version "${SANDPAPER_PYTHON_VERSION}")
  list(GET _py_version 0 _py_major)
  list(GET _py_version 1 _py_minor)
  math(EXPR _py_next_minor "${_py_minor} + 1")
  list(APPEND _sandpaper_deb_depends "python3 (>= ${_py_major}.${_py_minor})" "python3 (<< ${_py_major}.${_py_next_minor})"
    python3-numpy)
endif()
list(JOIN _sandpaper_deb_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)  # dpkg-shlibdeps' list is added to it
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
  "cmake, pkg-config, nlohmann-json3-dev, libtomlplusplus-dev, libglm-dev, zlib1g-dev, libopenimageio-dev, libusb-1.0-0-dev, libevdev-dev")

# The library index `sandpaper library search` reads is built where the library lies, which only
# root may write under /usr: the postinst builds it, the prerm removes it (cmake/deb/).
if(SANDPAPER_CURATION)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_LIST_DIR}/deb/postinst ${CMAKE_CURRENT_LIST_DIR}/deb/prerm)
endif()

# On the staged install, before the package is made (cmake/deb/prebuild.cmake): the Python module
# moves from lib/python3.X/dist-packages (a build configured for /usr/local) to
# lib/python3/dist-packages, where Debian's /usr/bin/python3 imports packaged modules from; the static
# archives lose their debug information.
set(CPACK_PRE_BUILD_SCRIPTS ${CMAKE_CURRENT_LIST_DIR}/deb/prebuild.cmake)
set(CPACK_SANDPAPER_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
set(CPACK_SANDPAPER_STRIP "${CMAKE_STRIP}")
if(SANDPAPER_PYTHON)
  set(CPACK_SANDPAPER_PYTHON_INSTALL_DIR "${SANDPAPER_PYTHON_INSTALL_DIR}")
endif()

include(CPack)
