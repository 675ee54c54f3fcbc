#!/bin/sh
# Runs a command in a private network namespace whose only interface is loopback, with
# multicast on: DDS discovery (SPDP multicast) then works with default settings, for
# CycloneDDS and Fast DDS alike, and nothing it sends can leave this machine.
#
#   in_netns.sh COMMAND [ARG...]
# Needs root (unshare -n, ip); ctest runs the Fast DDS interop tests through it.
set -eu
if [ $# -eq 0 ]; then
  echo "usage: $0 COMMAND [ARG...]" >&2
  exit 2
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "$0: a private network namespace needs root (unshare -n); run the tests as root" >&2
  exit 1
fi
# lo has no multicast by default; the route sends every multicast group out through it.
exec unshare -n sh -euc 'ip link set lo up
ip link set lo multicast on
ip route add 224.0.0.0/4 dev lo
exec "$@"' in_netns "$@"
