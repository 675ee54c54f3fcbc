# Shared by scripts/test, scripts/quickstart and scripts/experiments: the Debian packages
# this project needs, installing the missing ones, and configuring + building into build/.
# Source it; it defines functions only.

# Everything the build, the tests and the demo use (Debian 12 names).
DTMF_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libfftw3-dev libsndfile1-dev libutfcpp-dev libsamplerate0-dev portaudio19-dev libasound2-dev libjack-jackd2-dev
  libspdlog-dev libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  pulseaudio pulseaudio-utils libasound2-plugins alsa-utils
  postgresql libpqxx-dev cyclonedds-dev cyclonedds-tools
  libfec-dev  # Reed-Solomon codecs (protocol/reliability/reed_solomon.h)
  libsodium-dev  # keys, MACs and random numbers of authenticated frames (protocol/security/)
  libfastrtps-dev fastddsgen  # tests/interop/fastdds: ROS 2 Jazzy's default middleware as the subscriber
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler grpc-proto
  espeak-ng sox openssl
  time  # scripts/bench: /usr/bin/time, the CPU time of a start-up
  libncurses-dev  # dtmfctl teleop: the full-screen terminal view
  tmux  # tests/e2e: drives dtmfctl teleop in a real terminal (send-keys, capture-pane)
  systemd  # systemd-analyze verify checks the units (tests/install)
  clang-format  # tests/format: the code follows .clang-format
  dpkg-dev lintian help2man file  # scripts/package: dpkg-shlibdeps, the package check, manual pages
  docker-compose  # tests/docker: validates docker/compose.yaml offline (no engine needed)
  python3 python3-pip python3-venv python3-grpcio python3-protobuf python3-pytest python3-matplotlib
  libcivetweb-dev  # dtmf-console: its HTTP and WebSocket server
  chromium chromium-driver python3-selenium  # tests/console: the console's page in a real, headless browser
)

# A robot's build: dtmf-agent and dtmfctl's offline commands (encode, decode, keygen); no
# sender, no live commands, no simulator (tests/install/robot_build_test.sh checks it).
DTMF_ROBOT_CMAKE_OPTIONS=(-DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF -DDTMF_BUILD_SERVER=OFF -DDTMF_CLI_LIVE=OFF
  -DDTMF_BUILD_SIMULATOR=OFF)
# What a robot needs to build it: no gRPC, Protocol Buffers or GoogleTest.
# scripts/robot-build-check proves it in a fresh Debian root; docs/robot.md lists the same.
DTMF_ROBOT_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libfftw3-dev libsndfile1-dev libsamplerate0-dev portaudio19-dev libasound2-dev libjack-jackd2-dev
  libspdlog-dev libcli11-dev nlohmann-json3-dev libpqxx-dev cyclonedds-dev cyclonedds-tools libfec-dev libsodium-dev
)

# Installs what is missing (as root), or says exactly what to run and fails.
ensure_packages() {
  local missing=() p
  for p in "${DTMF_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "missing Debian packages: ${missing[*]}" >&2
    echo "install them with:" >&2
    echo "  sudo apt-get install -y ${missing[*]}" >&2
    return 1
  fi
  echo "installing ${#missing[@]} Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# Configures (once) and builds into build/: everything, or with arguments
# `build_all DIR [TARGET...]` into DIR only the targets named (scripts/experiments).
build_all() {
  local dir=${1:-build}
  if [ $# -gt 0 ]; then shift; fi
  # DTMF_CMAKE_OPTIONS: more options for the configure step (scripts/test: warnings are errors).
  if [ ! -f "$dir/build.ninja" ] || [ -n "${DTMF_CMAKE_OPTIONS:-}" ]; then
    # shellcheck disable=SC2086  # a list of options
    cmake -G Ninja -B "$dir" -S . -DCMAKE_BUILD_TYPE=RelWithDebInfo ${DTMF_CMAKE_OPTIONS:-} >/dev/null
  fi
  if [ $# -gt 0 ]; then cmake --build "$dir" --target "$@"; else cmake --build "$dir"; fi
}

# Third-party clients from npm for the interop tests, into DIR/npm (default build/npm):
# buf (@bufbuild/buf, pinned), a reflection-driven gRPC client like grpcurl, and its linter.
# Node and npm come from Debian when the machine has none.
DTMF_BUF_VERSION=1.75.0
ensure_npm_tools() {
  local dir=${1:-build}/npm
  if ! command -v npm >/dev/null; then
    if [ "$(id -u)" -ne 0 ]; then
      echo "npm is missing: sudo apt-get install -y nodejs npm" >&2
      return 1
    fi
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
  fi
  local buf=$dir/node_modules/.bin/buf
  [ -x "$buf" ] && [ "$("$buf" --version 2>/dev/null)" = "$DTMF_BUF_VERSION" ] && return 0
  echo "installing @bufbuild/buf@$DTMF_BUF_VERSION into $dir"
  mkdir -p "$dir"
  npm install --prefix "$dir" --no-save --no-audit --no-fund --loglevel=error "@bufbuild/buf@$DTMF_BUF_VERSION" >/dev/null
}
