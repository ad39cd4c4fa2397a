#!/usr/bin/env bash
# Regenerates include/topoplex.h from crates/topoplex-ffi/src with the pinned cbindgen (a dev-dependency).
set -euo pipefail
cd "$(dirname "$0")/.."
TOPOPLEX_REGENERATE_HEADER=1 cargo test --quiet -p topoplex-ffi --test header
echo "include/topoplex.h regenerated"
