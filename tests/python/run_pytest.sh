#!/usr/bin/env bash
# The Python package's test (CTest label python): a virtual environment of Debian's
# /usr/bin/python3 with --system-site-packages (numpy, scipy, matplotlib, pytest from Debian;
# no package index), the package from python/ built against BUILD's libgeomint.a (pip,
# without build isolation, from a copy so the source tree stays clean), then pytest.
# usage: run_pytest.sh BUILD_DIR SOURCE_DIR [pytest arguments]
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
shift 2
python=/usr/bin/python3
for module in numpy scipy matplotlib pytest; do
  if ! "$python" -c "import $module" 2>/dev/null; then
    echo "run_pytest: $python cannot import $module (run scripts/install-deps as root)" >&2
    exit 1
  fi
done
venv="$build/python-venv"
[[ -x "$venv/bin/python" ]] || "$python" -m venv --system-site-packages "$venv"
copy="$build/python-src"
rm -rf "$copy"
mkdir -p "$copy"
cp -r "$source/python/pyproject.toml" "$source/python/setup.py" "$source/python/src" "$copy/"
GEOMINT_BUILD_DIR="$build" GEOMINT_SOURCE_DIR="$source" \
  PIP_DISABLE_PIP_VERSION_CHECK=1 "$venv/bin/pip" install --quiet --no-cache-dir \
  --no-build-isolation --no-index --no-deps "$copy"
cd "$build"
export GEOMINT_CLI="$build/geomint" GEOMINT_BUILD_DIR="$build" GEOMINT_SOURCE_DIR="$source"
export MPLBACKEND=Agg
exec "$venv/bin/python" -m pytest -p no:cacheprovider -q "$source/tests/python" "$@"
