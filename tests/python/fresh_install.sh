#!/usr/bin/env bash
# The Python package installed from a fresh clone, with no build/ directory: pip must configure
# and build libgeomint itself (python/setup.py) before the extension links it. Takes minutes
# (the whole library is compiled); ctest runs it as python_fresh_install, or by hand:
#   tests/python/fresh_install.sh [REPOSITORY [REVISION]]    (default: this checkout, its HEAD)
# Clones into a temporary directory, makes a venv of Debian's /usr/bin/python3 with
# --system-site-packages, runs `pip install --no-build-isolation --no-index ./python`, then the
# five-line start from a directory outside the clone. Removes the directory at the end.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
repo=${1:-$here}
# default: the commit checked out here (works on a detached HEAD, as in CI)
rev=${2:-$(git -C "$here" rev-parse HEAD)}
tmp=$(mktemp -d /tmp/geomint-fresh.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
git clone --quiet --no-checkout "$repo" "$tmp/clone"
git -C "$tmp/clone" checkout --quiet "$rev"
if [[ -e "$tmp/clone/build" ]]; then
  echo "fresh_install: the clone has a build/ directory" >&2
  exit 1
fi
start=$(date +%s)
/usr/bin/python3 -m venv --system-site-packages "$tmp/venv"
(cd "$tmp" && PIP_DISABLE_PIP_VERSION_CHECK=1 "$tmp/venv/bin/pip" install --quiet \
  --no-build-isolation --no-index ./clone/python)
[[ -f "$tmp/clone/python/build-lib/libgeomint.a" ]] || {
  echo "fresh_install: setup.py did not build python/build-lib/libgeomint.a" >&2
  exit 1
}
cd /
"$tmp/venv/bin/python" - <<'PY'
import geomint
r = geomint.run("kepler", method="verlet", dt=0.01, steps=1000)
assert r.q.shape == (1001, 2) and r.stats["force_evals"] > 0
from geomint import dec, fields, pde, yee  # noqa: F401
print("fresh_install: ok,", geomint.__file__)
PY
echo "fresh_install: pip install took $(( $(date +%s) - start )) s"
