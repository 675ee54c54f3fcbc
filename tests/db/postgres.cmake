# Tests against a real PostgreSQL: the throwaway cluster of scripts/pg.
#
# The fixture test pg.start starts a private cluster in <build>/pg on port 25432 before
# any test that needs it (ctest adds it by itself, also for `ctest -R ...`), pg.destroy
# stops it and removes <build>/pg after them. The database tests hold RESOURCE_LOCK pg,
# so they never share the cluster at once: some stop the server to act out an outage
# (`$DTMF_PG_SCRIPT stop $DTMF_PG_DIR`, then `$DTMF_PG_SCRIPT start $DTMF_PG_DIR`, which
# keeps the data). They get DTMF_DB_URL, DTMF_PG_DIR and DTMF_PG_SCRIPT in ENVIRONMENT.
# Include from tests/CMakeLists.txt after include(GoogleTest); register a gtest
# executable's tests with dtmf_pg_test(<target>).

set(DTMF_PG_DIR ${PROJECT_BINARY_DIR}/pg)
# Below Linux's ephemeral ports (32768-60999): the outage tests stop the server and start it
# again, and on 55432 a client socket of a test running beside them once took the port in
# between ("could not bind ... Address already in use"), failing every later database test.
set(DTMF_PG_PORT 25432 CACHE STRING "port of the test cluster (another build tree testing at once needs another)")
set(DTMF_PG_SCRIPT ${PROJECT_SOURCE_DIR}/scripts/pg)
set(DTMF_PG_URL postgresql://postgres@127.0.0.1:${DTMF_PG_PORT}/postgres)
set(DTMF_PG_ENV DTMF_DB_URL=${DTMF_PG_URL} DTMF_PG_DIR=${DTMF_PG_DIR}
                DTMF_PG_SCRIPT=${DTMF_PG_SCRIPT})

add_test(NAME pg.start COMMAND ${DTMF_PG_SCRIPT} start ${DTMF_PG_DIR} ${DTMF_PG_PORT})
add_test(NAME pg.destroy COMMAND ${DTMF_PG_SCRIPT} destroy ${DTMF_PG_DIR})
set_tests_properties(pg.start PROPERTIES FIXTURES_SETUP pg RESOURCE_LOCK pg TIMEOUT 90)
set_tests_properties(pg.destroy PROPERTIES FIXTURES_CLEANUP pg RESOURCE_LOCK pg TIMEOUT 90)

# gtest_add_tests (not gtest_discover_tests) because CMake 3.25's discovery splits every
# PROPERTIES list, so an ENVIRONMENT of several variables cannot get through it. It finds
# the tests by reading the target's sources, so add the executable with add_executable,
# not dtmf_test (which discovers). The tests are named db.<Suite>.<Test>.
function(dtmf_pg_test target)
  gtest_add_tests(TARGET ${target} TEST_PREFIX db. TEST_LIST pg_tests)
  set_tests_properties(${pg_tests} PROPERTIES
    FIXTURES_REQUIRED pg RESOURCE_LOCK pg TIMEOUT 300 ENVIRONMENT "${DTMF_PG_ENV}")
endfunction()
