# Fails when any C++ source under libs/ apps/ tests/ differs from .clang-format.
file(GLOB_RECURSE _files
  "${SOURCE_DIR}/libs/*.cpp" "${SOURCE_DIR}/libs/*.h"
  "${SOURCE_DIR}/apps/*.cpp" "${SOURCE_DIR}/apps/*.h"
  "${SOURCE_DIR}/tests/*.cpp" "${SOURCE_DIR}/tests/*.h")
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror --style=file ${_files}
  WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE _rc ERROR_VARIABLE _err)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "clang-format: files need formatting (run clang-format -i):\n${_err}")
endif()
message(STATUS "clang-format: ${CMAKE_ARGC} checked, all formatted")
