#!/usr/bin/env bash
# The air container's main process: scripts/air's PulseAudio null sink `air`, but in the
# foreground, so that the container lives and dies with it.
#   dtmf-air           run the air (socket DTMF_AIR_DIR/native, default /run/dtmf-air/native)
#   dtmf-air health    exit 0 when the sink `air` answers (the image's HEALTHCHECK)
# Keep the pulseaudio and pacat arguments in step with scripts/air.
set -euo pipefail

dir=${DTMF_AIR_DIR:-/run/dtmf-air}
socket=$dir/native
pactl_air() { LC_ALL=C PULSE_SERVER=unix:$socket timeout 5 pactl "$@"; }
healthy() { pactl_air list short sinks 2>/dev/null | grep -q $'\tair\t'; }

if [[ ${1:-} == health ]]; then healthy; exit; fi

# Cookie, pid file and runtime state stay private to this container; only the socket is shared.
export HOME=${HOME:-/home/dtmf} XDG_RUNTIME_DIR=/tmp/air-runtime XDG_CONFIG_HOME=/tmp/air-config
install -d -m 700 "$XDG_RUNTIME_DIR" "$XDG_CONFIG_HOME"
rm -f "$socket"  # left by a container that was killed; nothing else serves it

# --disable-shm: clients in other containers do not share our /dev/shm, so all audio goes
# through the socket. auth-anonymous: the socket's volume is the access control.
pulseaudio -n --daemonize=no --exit-idle-time=-1 --disallow-exit=true --disable-shm=yes \
  --log-target=stderr \
  --load="module-native-protocol-unix socket=$socket auth-anonymous=1" \
  --load="module-null-sink sink_name=air rate=48000 channels=1" &
pulse=$!
for _ in $(seq 100); do healthy && break; kill -0 "$pulse" 2>/dev/null || exit 1; sleep 0.1; done
healthy || { echo "air: sink 'air' did not appear within 10 s" >&2; exit 1; }
pactl_air set-default-sink air >/dev/null
pactl_air set-default-source air.monitor >/dev/null

# A low-latency silent stream makes the null sink render in small blocks instead of 2 s
# ones, which would delay every sound by up to 2 s (see scripts/air).
pacat --playback --server="unix:$socket" --device=air --raw --format=float32le \
  --rate=48000 --channels=1 --latency-msec=20 --client-name=air-silence </dev/zero &
silence=$!
echo "air: serving unix:$socket (sink air, source air.monitor)" >&2

trap 'kill "$silence" "$pulse" 2>/dev/null; wait; exit 0' TERM INT
wait -n
echo "air: pulseaudio or the silent stream ended" >&2
kill "$silence" "$pulse" 2>/dev/null || true
exit 1
