#!/usr/bin/env bash
# Builds the Blender extension zip (Blender 4.2 and later): blender/curvenet_blender with the
# curvenet wheel in wheels/, as `blender --command extension build` lays it out. Install it in
# Blender with Edit › Preferences › Get Extensions › Install from Disk, or
# `blender --command extension install-file -r user_default target/blender/curvenet-0.1.0.zip`.
#
#   bash blender/build.sh            # builds the wheel too (python/build-wheel.sh) if missing
set -euo pipefail
cd "$(dirname "$0")/.."
wheel=$(ls target/wheels/curvenet-*-cp39-abi3-manylinux_2_28_x86_64.whl 2>/dev/null | head -1 || true)
if [ -z "$wheel" ]; then
    bash python/build-wheel.sh
    wheel=$(ls target/wheels/curvenet-*-cp39-abi3-manylinux_2_28_x86_64.whl | head -1)
fi
# The manifest names the wheel it bundles: they must agree.
grep -q "\"./wheels/$(basename "$wheel")\"" blender/curvenet_blender/blender_manifest.toml || {
    echo "blender/build.sh: blender_manifest.toml does not name $(basename "$wheel")" >&2
    exit 1
}
version=$(sed -n 's/^version = "\(.*\)"/\1/p' blender/curvenet_blender/blender_manifest.toml)
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
cp blender/curvenet_blender/__init__.py blender/curvenet_blender/blender_manifest.toml "$stage/"
mkdir "$stage/wheels"
cp "$wheel" "$stage/wheels/"
mkdir -p target/blender
out="$PWD/target/blender/curvenet-$version.zip"
rm -f "$out"
(cd "$stage" && python3 -m zipfile -c "$out" __init__.py blender_manifest.toml wheels)
echo "$out"
