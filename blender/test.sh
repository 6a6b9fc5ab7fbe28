#!/usr/bin/env bash
# The Blender extension's headless test (issue 32): builds its zip (blender/build.sh), installs
# Blender as a Python module (`bpy` from PyPI, for this CPython) in a virtual environment,
# installs the wheel the zip bundles, and runs blender/tests against the zip's contents. Where
# bpy cannot be installed, it says so and skips; it never passes without running.
set -euo pipefail
cd "$(dirname "$0")/.."
zip=$(bash blender/build.sh | tail -1)
venv=target/bpy-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "bpy>=4.2,<5" pytest numpy \
        > target/bpy-install.log 2>&1; then
    echo "blender/test.sh: SKIPPED — bpy could not be installed for $("$venv/bin/python" --version) (target/bpy-install.log):" >&2
    tail -3 target/bpy-install.log >&2
    exit 0
fi
unpacked=$(mktemp -d)
trap 'rm -rf "$unpacked"' EXIT
python3 -m zipfile -e "$zip" "$unpacked"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps "$unpacked"/wheels/*.whl
echo "blender/test.sh: bpy $("$venv/bin/python" -c 'import bpy; print(bpy.app.version_string)'), extension $zip"
CURVENET_BLENDER_EXTENSION="$unpacked" "$venv/bin/python" -m pytest -q -p no:cacheprovider blender/tests
