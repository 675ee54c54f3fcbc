#!/bin/sh
# The Python package's tests (ctest: python.package): installs clients/python with Debian's
# Python into a throwaway virtual environment, exactly as the README says, then runs pytest
# against a live system (conftest.py) from outside the source tree.
#   run_tests.sh BIN_DIR [pytest arguments...]
set -eu
bin_dir=$1; shift
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/dtmf-python-XXXXXX")
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
"$work/venv/bin/pip" install --no-index --quiet --disable-pip-version-check "$repo/clients/python"
cd "$work"
DTMF_BIN_DIR=$bin_dir exec "$work/venv/bin/python" -m pytest -p no:cacheprovider -v \
  --rootdir "$repo/tests/python" "$repo/tests/python" "$@"
