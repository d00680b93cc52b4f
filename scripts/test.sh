#!/usr/bin/env sh
# Install vgxsim with its test extra and run the checks: ruff, then pytest.
# Mesa's OSMesa (the independent OpenGL peer of the conformance tests) comes from
# Debian's libosmesa6; it is installed here when we are root and it is missing.
set -eu
cd "$(dirname "$0")/.."
if ! ldconfig -p 2>/dev/null | grep -q libOSMesa; then
  if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
    (apt-get install -y -q libosmesa6 >/dev/null 2>&1 ||
      (apt-get update -q >/dev/null 2>&1 && apt-get install -y -q libosmesa6 >/dev/null 2>&1)) ||
      echo "note: could not install libosmesa6; Mesa conformance tests will be skipped"
  else
    echo "note: libOSMesa not found; Mesa conformance tests will be skipped"
  fi
fi
python -m pip install -q -e ".[test]"
python -m ruff check .
python -m pytest -q -p no:cacheprovider
