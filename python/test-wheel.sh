#!/usr/bin/env bash
# Installs a built wheel (python/build-wheel.sh) into a fresh virtual environment on a PATH
# without a Rust toolchain, and runs the Python tests against it (issue 32): the wheel must
# work where nothing can compile it. The tests still compare with the CLI binary that
# `cargo test --workspace --release` built (target/release/curvenet).
#
#   bash python/test-wheel.sh [WHEEL]         # default: the newest manylinux one in target/wheels
set -euo pipefail
cd "$(dirname "$0")/.."
wheel="${1:-$(ls -t target/wheels/curvenet-*-manylinux_*.whl | head -1)}"
# The wheel is the stable ABI's and manylinux's: its name's tags and its WHEEL file say so.
case "$(basename "$wheel")" in
    *-cp39-abi3-manylinux_2_28_x86_64.whl) ;;
    *) echo "test-wheel: $wheel is not tagged cp39-abi3-manylinux_2_28_x86_64" >&2; exit 1 ;;
esac
python3 - "$wheel" <<'PY'
import sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as z:
    meta = next(n for n in z.namelist() if n.endswith(".dist-info/WHEEL"))
    tags = [l.split(": ", 1)[1] for l in z.read(meta).decode().splitlines() if l.startswith("Tag: ")]
assert tags and all(t.startswith("cp39-abi3-manylinux") for t in tags), tags
print("test-wheel: tags", ", ".join(tags))
PY
venv="$(mktemp -d)/venv"
trap 'rm -rf "$(dirname "$venv")"' EXIT
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "$wheel" \
    pytest libigl trimesh dask distributed
# No Rust on the PATH (the toolchain lives in ~/.cargo/bin): the wheel is all there is.
bare="$venv/bin:/usr/local/bin:/usr/bin:/bin"
for tool in cargo rustc maturin; do
    if PATH="$bare" command -v "$tool" >/dev/null; then
        echo "test-wheel: $tool is on the bare PATH ($(PATH="$bare" command -v "$tool"))" >&2
        exit 1
    fi
done
where=$(cd /tmp && PATH="$bare" python -c 'import curvenet, os; print(os.path.realpath(curvenet._curvenet.__file__))')
case "$where" in
    "$(realpath "$venv")"/*) echo "test-wheel: curvenet from $where" ;;
    *) echo "test-wheel: curvenet was imported from $where, not from the wheel" >&2; exit 1 ;;
esac
PATH="$bare" python -m pytest -q -p no:cacheprovider python/tests
