#!/usr/bin/env bash
# The web console in a real browser (ctest console.browser). scripts/quickstart --robots 3
# starts the whole system as a user starts it (air, database, three simulated TurtleBot3s,
# the server and the console), then pytest drives Debian's Chromium, headless, through
# Selenium against the console (test_*.py). Ports of its own, so that a user's quickstart may
# run meanwhile; screenshots are kept in WORK/screenshots.
#   run_browser_tests.sh SOURCE_DIR BIN_DIR WORK_DIR [pytest arguments...]
set -uo pipefail
src=$1
bin=$2
dir=$3
shift 3
[ -n "$dir" ] && [ "$dir" != / ] || { echo "FAIL: no work directory"; exit 1; }
export DTMF_QUICKSTART_BIN=$bin DTMF_QUICKSTART_DIR=$dir
export DTMF_QUICKSTART_PORT=25460 DTMF_QUICKSTART_PG_PORT=25461 DTMF_QUICKSTART_CONSOLE_PORT=25462
unset DTMF_AUDIO_DEVICE
quickstart() { "$src/scripts/quickstart" "$@"; }
clean() {
  quickstart down >/dev/null 2>&1
  "$src/scripts/pg" destroy "$dir/pg" >/dev/null 2>&1
}
clean
rm -rf "$dir"
trap clean EXIT
quickstart --robots 3 --no-sequence || { echo "FAIL: scripts/quickstart --robots 3 --no-sequence"; exit 1; }
DTMF_CONSOLE_URL=http://127.0.0.1:$DTMF_QUICKSTART_CONSOLE_PORT/ DTMF_SERVER=localhost:$DTMF_QUICKSTART_PORT \
  DTMF_SOURCE_DIR=$src DTMF_CONSOLE_ARTEFACTS=$dir/screenshots \
  /usr/bin/python3 -m pytest -p no:cacheprovider -v --rootdir "$src/tests/console/browser" \
  "$src/tests/console/browser" "$@"
