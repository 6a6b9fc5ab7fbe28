#!/usr/bin/env bash
# Builds the viewer and serves it on http://localhost:${PORT:-8000}/ (Ctrl-C to stop).
set -euo pipefail
cd "$(dirname "$0")"
bash build.sh
echo "open http://localhost:${PORT:-8000}/"
exec python3 -m http.server "${PORT:-8000}" --bind 127.0.0.1
