# Run by `cmake --install` (and cpack) after everything else is installed (install(CODE) at the end
# of the top-level CMakeLists.txt): the installed programs, the Python module and the static
# libraries lose their debug information as Debian's dh_strip takes it off, so that an install is
# tens of MB, not 465. For programs and shared objects the debug information is kept apart, where
# gdb looks for it by build id: <prefix>/lib/debug/.build-id/xx/yyyy.debug (compressed), named by a
# .gnu_debuglink in the stripped file. Static archives keep their symbols and lose only their debug
# sections (strip --strip-debug), which nothing can link back. A Debian package made by cpack gets
# no debug files: Debian ships them in a -dbgsym package of their own.
#
# Set by the install(CODE) that includes this: SANDPAPER_STRIP, SANDPAPER_OBJCOPY, SANDPAPER_READELF
# (the toolchain's), SANDPAPER_INSTALL_DEBUG_DIR (relative to the prefix: lib/debug).

if(NOT SANDPAPER_STRIP OR NOT SANDPAPER_OBJCOPY OR NOT SANDPAPER_READELF OR CMAKE_INSTALL_DO_STRIP)
  return()  # no toolchain tools, or `cmake --install --strip` already stripped without keeping debug
endif()

set(_sandpaper_packaging FALSE)
if("$ENV{DESTDIR}" MATCHES "/_CPack_Packages/")
  set(_sandpaper_packaging TRUE)
endif()
# The manifest names files as installed under the prefix; with DESTDIR (a staged install) they are
# under DESTDIR, and the manifest gets the debug files' names in the same form.
set(_sandpaper_destdir "$ENV{DESTDIR}")
set(_sandpaper_debug_root "${CMAKE_INSTALL_PREFIX}/${SANDPAPER_INSTALL_DEBUG_DIR}/.build-id")
set(_sandpaper_debug_files "")

function(_sandpaper_run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_VARIABLE _err)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "cmake/install_strip.cmake: `${ARGN}` failed: ${_err}")
  endif()
endfunction()

foreach(_listed IN LISTS CMAKE_INSTALL_MANIFEST_FILES)
  set(_file "${_listed}")
  if(_sandpaper_destdir AND NOT _listed MATCHES "^${_sandpaper_destdir}")
    set(_file "${_sandpaper_destdir}${_listed}")
  endif()
  if(IS_SYMLINK "${_file}" OR IS_DIRECTORY "${_file}" OR NOT EXISTS "${_file}")
    continue()
  endif()
  file(READ "${_file}" _magic LIMIT 8 HEX)
  if(_magic MATCHES "^213c617263683e0a")  # "!<arch>\n": a static library
    _sandpaper_run("${SANDPAPER_STRIP}" --strip-debug --enable-deterministic-archives "${_file}")
  elseif(_magic MATCHES "^7f454c46")  # ELF: a program or a shared object
    execute_process(COMMAND "${SANDPAPER_READELF}" -n "${_file}" OUTPUT_VARIABLE _notes ERROR_QUIET)
    set(_debug "")
    if(NOT _sandpaper_packaging AND _notes MATCHES "Build ID: ([0-9a-f][0-9a-f])([0-9a-f]+)")
      set(_listed_debug "${_sandpaper_debug_root}/${CMAKE_MATCH_1}/${CMAKE_MATCH_2}.debug")
      set(_debug "${_sandpaper_destdir}${_listed_debug}")
      get_filename_component(_debug_dir "${_debug}" DIRECTORY)
      file(MAKE_DIRECTORY "${_debug_dir}")
      _sandpaper_run("${SANDPAPER_OBJCOPY}" --only-keep-debug --compress-debug-sections "${_file}" "${_debug}")
      list(APPEND _sandpaper_debug_files "${_listed_debug}")
    endif()
    _sandpaper_run("${SANDPAPER_STRIP}" --strip-unneeded --remove-section=.comment --remove-section=.note "${_file}")
    if(_debug)
      _sandpaper_run("${SANDPAPER_OBJCOPY}" "--add-gnu-debuglink=${_debug}" "${_file}")
    endif()
  endif()
endforeach()
list(APPEND CMAKE_INSTALL_MANIFEST_FILES ${_sandpaper_debug_files})
