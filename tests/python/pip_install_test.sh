#!/usr/bin/env bash
# `pip install --no-build-isolation .` with Debian's packages only, as docs/python.md says: a venv
# that sees Debian's NumPy and pybind11, pip from Debian, the module linked in this build directory.
#   pip_install_test.sh SOURCE_DIR BUILD_DIR PYTHON
set -euo pipefail
source_dir=$1 build_dir=$2 python=$3
venv="$build_dir/pip-test-venv"
rm -rf "$venv"
"$python" -m venv --system-site-packages "$venv"
# A copy of what pip reads (the module is built in BUILD_DIR, whose sources are the checkout), so that
# pip's in-tree build leaves nothing in the checkout.
work="$build_dir/pip-test-src"
rm -rf "$work"
mkdir -p "$work"
cp -r "$source_dir"/setup.py "$source_dir"/pyproject.toml "$source_dir"/python "$work"/
TUMBLE_CMAKE_BUILD_DIR="$build_dir" "$venv/bin/pip" install --no-build-isolation --no-deps --quiet "$work"
cd "$build_dir"
"$venv/bin/python" - <<'PY'
import tumble, numpy as np
assert "pip-test-venv" in tumble.__file__, tumble.__file__
b = tumble.box([1.0, 2.0, 3.0], mass=6.0)
np.testing.assert_allclose(b.principal_moments, [2.5, 5.0, 6.5], rtol=1e-15)  # m(b²+c²)/12, ...
print("pip install: tumble imported from", tumble.__file__)
PY
rm -rf "$venv" "$work"
