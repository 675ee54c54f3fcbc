#!/usr/bin/env bash
# A robot's build (the options scripts/robot-build-check uses) compiles no file of the
# simulator (protocol/sim), no dtmfctl simulate and no dtmf-room, but keeps dtmf-agent and
# dtmfctl with encode and decode. Configures only (seconds): the build itself, in a bare
# Debian root, is scripts/robot-build-check's. Prints PASS when every check holds.
#   robot_build_test.sh SOURCE_DIR
set -euo pipefail
src=$1
build=$(mktemp -d)
trap 'rm -rf "$build"' EXIT
source "$src/scripts/lib/common.sh"
cmake -S "$src" -B "$build" -G Ninja "${DTMF_ROBOT_CMAKE_OPTIONS[@]}" >"$build/configure.log" 2>&1 ||
  { tail -n 20 "$build/configure.log"; echo "FAIL: the robot build does not configure"; exit 1; }
# Captured first: `ninja ... | grep -q` under pipefail fails when grep stops reading early.
targets=$(ninja -C "$build" -t targets all)
compiled=$(grep -oE '[^ ]+\.(cpp|c)\.o' <<<"$targets" | sort -u)
failed=0
check() { if ! eval "$1"; then echo "FAIL: $2"; failed=1; fi; }
check '! grep -q "/sim/" <<<"$compiled"' "it compiles the simulator: $(grep /sim/ <<<"$compiled" | head -3 | tr '\n' ' ')"
check '! grep -q "simulate_command" <<<"$compiled"' "dtmfctl simulate is built"
check '! grep -q "^bin/dtmf-room:" <<<"$targets"' "dtmf-room is built"
check 'grep -q "^bin/dtmf-agent:" <<<"$targets"' "dtmf-agent is not built"
check 'grep -q "^bin/dtmfctl:" <<<"$targets"' "dtmfctl is not built"
check 'grep -q "encode_command" <<<"$compiled" && grep -q "decode_command" <<<"$compiled"' \
  "dtmfctl lost encode or decode"
check '! grep -q "server/" <<<"$compiled"' "the sender is built"
[ $failed -eq 0 ] && echo "PASS: a robot's build compiles $(wc -l <<<"$compiled") files, none of the simulator"
