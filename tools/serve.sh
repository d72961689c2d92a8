#!/usr/bin/env bash
# Builds the page and serves it on http://127.0.0.1:8080 (installing what is missing).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
ensure_wasm_target
ensure_wasm_bindgen
ensure_trunk
ensure_npm
build_web
say "serving http://127.0.0.1:8080 (Ctrl-C stops)"
cd "$ROOT" && exec python3 -m http.server 8080 --bind 127.0.0.1 --directory dist
