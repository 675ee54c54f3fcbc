# PortAudio against a real sound server: the PulseAudio "air" of scripts/air.
#
# The fixture test air.start starts a private air in <build>/air before any test that
# needs it (ctest adds it by itself, also for `ctest -R ...`), air.stop removes it after
# them. The air tests get the PULSE_* variables that `scripts/air start` would print, and
# hold RESOURCE_LOCK air so that parallel runs never play into the same air at once.
# The no-device tests run against a server that does not exist.
# Include from tests/CMakeLists.txt after include(GoogleTest).

set(DTMF_AIR_DIR ${PROJECT_BINARY_DIR}/air)
set(DTMF_AIR_SCRIPT ${PROJECT_SOURCE_DIR}/scripts/air)

add_test(NAME air.start COMMAND ${DTMF_AIR_SCRIPT} start ${DTMF_AIR_DIR})
add_test(NAME air.stop COMMAND ${DTMF_AIR_SCRIPT} stop ${DTMF_AIR_DIR})
set_tests_properties(air.start PROPERTIES FIXTURES_SETUP air RESOURCE_LOCK air TIMEOUT 30)
set_tests_properties(air.stop PROPERTIES FIXTURES_CLEANUP air RESOURCE_LOCK air TIMEOUT 30)

foreach(test portaudio_air_test portaudio_no_device_test)
  add_executable(${test} ${CMAKE_CURRENT_LIST_DIR}/${test}.cpp)
  target_link_libraries(${test} PRIVATE GTest::gtest_main dtmf_sim dtmf_signal dtmf_link
                                        Threads::Threads)
endforeach()

# gtest_add_tests (not gtest_discover_tests) because CMake 3.25's discovery splits every
# PROPERTIES list, so an ENVIRONMENT of several variables cannot get through it.
set(DTMF_AIR_ENV PULSE_SERVER=unix:${DTMF_AIR_DIR}/native PULSE_SINK=air PULSE_SOURCE=air.monitor)
function(dtmf_air_test target)
  gtest_add_tests(TARGET ${target} TEST_PREFIX air. TEST_LIST air_tests)
  set_tests_properties(${air_tests} PROPERTIES
    FIXTURES_REQUIRED air RESOURCE_LOCK air TIMEOUT 120 ENVIRONMENT "${DTMF_AIR_ENV}")
endfunction()
dtmf_air_test(portaudio_air_test)
gtest_add_tests(TARGET portaudio_no_device_test TEST_PREFIX no_air. TEST_LIST no_air_tests)
set_tests_properties(${no_air_tests} PROPERTIES
  TIMEOUT 60 ENVIRONMENT PULSE_SERVER=unix:/nonexistent)
