# limn_library(NAME SOURCES... DEPS ...): one layer of lib/, with limn's warnings.
function(limn_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/lib)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE limn_warnings ${ARG_PRIVATE_DEPS})
endfunction()

# limn_tool(NAME SOURCES... DEPS ...): a thin command-line program built into bin/.
function(limn_tool name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE limn_warnings ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY LIMN_TOOL_TARGETS ${name})
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# limn_gtest(NAME SOURCES... DEPS ...): a GoogleTest executable registered with CTest.
function(limn_gtest name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE limn_warnings GTest::gtest_main limn_test_support limn_test_watchdog
    ${ARG_DEPS})
  # Test sources at -O1 -g1 (after the build type's -O2 -g on the command line, so they win):
  # GoogleTest's macros make them the heaviest files to compile (a CLI test file 11.2 s of CPU at
  # -O2 -g, 5.2 s at -O1 -g1), while the work they test runs in limn's libraries and tools, which
  # keep -O2, and the OpenSubdiv oracles in tests/support, which do too.
  target_compile_options(${name} PRIVATE $<$<CONFIG:RelWithDebInfo>:-O1 -g1>)
  target_compile_definitions(${name} PRIVATE
    LIMN_TEST_DATA_DIR="${LIMN_TEST_DATA_DIR}"
    LIMN_BIN_DIR="${CMAKE_BINARY_DIR}/bin"
    LIMN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  # One label per executable: CMake 3.25's gtest_discover_tests flattens a list of them.
  # A test that hangs fails at 600 s instead of holding CTest (and CI) forever; the watchdog
  # (tests/support/test_watchdog.cpp) has printed where it hangs by then.
  # (An empty LABELS would swallow the next property's name: it is left out when empty.)
  set(properties TIMEOUT 600)
  if(ARG_LABELS)
    list(APPEND properties LABELS "${ARG_LABELS}")
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
  if(NOT ARG_LABELS MATCHES "^(render|heavy)$")
    set_property(GLOBAL APPEND PROPERTY LIMN_SANITIZED_TESTS ${name}) # limn_sanitizer_suite
  endif()
endfunction()
include(GoogleTest)
