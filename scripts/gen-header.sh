#!/usr/bin/env bash
# Regenerates include/topoplex.h from src/ffi/ with the pinned cbindgen (a dev-dependency).
set -euo pipefail
cd "$(dirname "$0")/.."
TOPOPLEX_REGENERATE_HEADER=1 cargo test --quiet --test header
echo "include/topoplex.h regenerated"
