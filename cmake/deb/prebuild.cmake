# CPACK_PRE_BUILD_SCRIPTS of cmake/Packaging.cmake: run by cpack on the staged install (under
# CPACK_TEMPORARY_DIRECTORY), before the package is made from it.
set(_staged "${CPACK_TEMPORARY_DIRECTORY}${CPACK_PACKAGING_INSTALL_PREFIX}")
if(NOT IS_DIRECTORY "${_staged}/bin")
  message(FATAL_ERROR "cmake/deb/prebuild.cmake: no staged install at ${_staged}")
endif()

# 1. Debian's python3 imports packaged modules from /usr/lib/python3/dist-packages; move the module
# there from lib/python3.X/dist-packages, where a build configured for /usr/local puts it. Only that
# exact layout is moved: the module carries its path to share/sandpaper relative to itself
# (bindings/python, SANDPAPER_MODULE_DIR_TO_DATA), and lib/python3.X/dist-packages and
# lib/python3/dist-packages lie equally deep below the prefix.
set(_from "${CPACK_SANDPAPER_PYTHON_INSTALL_DIR}")
if(_from MATCHES "^lib/python3\\.[0-9]+/dist-packages$")
  file(GLOB _modules "${_staged}/${_from}/sandpaper*.so")
  if(NOT _modules)
    message(FATAL_ERROR "cmake/deb/prebuild.cmake: no Python module under ${_staged}/${_from}")
  endif()
  file(MAKE_DIRECTORY "${_staged}/lib/python3/dist-packages")
  foreach(_module IN LISTS _modules)
    get_filename_component(_name "${_module}" NAME)
    file(RENAME "${_module}" "${_staged}/lib/python3/dist-packages/${_name}")
  endforeach()
  # Remove lib/python3.X/dist-packages and lib/python3.X if the module was all they held.
  foreach(_dir "${_staged}/${_from}" "${_staged}/${_from}/..")
    get_filename_component(_dir "${_dir}" ABSOLUTE)
    file(GLOB _left "${_dir}/*")
    if(NOT _left)
      file(REMOVE_RECURSE "${_dir}")
    endif()
  endforeach()
endif()

# 2. CPACK_STRIP_FILES strips the programs and the module but not static archives (their symbol
# table is all they have); drop their debug information as Debian's dh_strip does (--strip-debug),
# which is most of their size in a RelWithDebInfo build.
if(CPACK_STRIP_FILES AND CPACK_SANDPAPER_STRIP)
  file(GLOB _archives "${_staged}/${CPACK_SANDPAPER_LIBDIR}/libsandpaper_*.a")
  foreach(_archive IN LISTS _archives)
    execute_process(COMMAND "${CPACK_SANDPAPER_STRIP}" --strip-debug --enable-deterministic-archives "${_archive}"
      RESULT_VARIABLE _rc)
    if(NOT _rc EQUAL 0)
      message(FATAL_ERROR "cmake/deb/prebuild.cmake: ${CPACK_SANDPAPER_STRIP} --strip-debug ${_archive} failed")
    endif()
  endforeach()
endif()
