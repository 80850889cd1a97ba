# Writes the version header of the build (config/version.cc includes it), run at configure time and again at every
# build (the sacfuse_build_version target), so `git describe` follows commits and edits without reconfiguring:
#   cmake -DSOURCE_DIR=<checkout> -DOUTPUT=<header> -DRELEASE=<project version> -DGIT_DESCRIBE=ON|OFF -P BuildVersion.cmake
# SACFUSE_GIT_DESCRIBE is `git describe --tags --always --dirty` when SOURCE_DIR is the top of a git checkout
# (not a tarball unpacked inside some other repository) and git is installed; "" otherwise. The header is
# rewritten only when its text changes, so an unchanged checkout recompiles nothing.
set(describe "")
find_program(GIT_EXECUTABLE git)
if(GIT_DESCRIBE AND GIT_EXECUTABLE AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" rev-parse --show-toplevel
    WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE top RESULT_VARIABLE top_rc
    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(top_rc EQUAL 0)
    file(REAL_PATH "${top}" top)
    file(REAL_PATH "${SOURCE_DIR}" source)
  endif()
  if(top_rc EQUAL 0 AND top STREQUAL source)
    execute_process(COMMAND "${GIT_EXECUTABLE}" describe --tags --always --dirty
      WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE describe RESULT_VARIABLE rc
      OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(NOT rc EQUAL 0)
      set(describe "")
    endif()
  endif()
endif()
set(text "// Written by cmake/BuildVersion.cmake; do not edit.
#pragma once
#define SACFUSE_RELEASE_VERSION \"${RELEASE}\"
#define SACFUSE_GIT_DESCRIBE \"${describe}\"
")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
