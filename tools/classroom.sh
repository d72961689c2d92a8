#!/usr/bin/env bash
# Runs a lecture: builds the page when dist/ is missing or older than its sources, builds
# the classroom server, and serves page and relay on http://127.0.0.1:PORT (8080 unless
# --port P). Other arguments go to the server (--listen ADDR, --redis redis://HOST:PORT;
# docs/deploying.md).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
PORT=8080
ARGS=()
while [ $# -gt 0 ]; do
  case "$1" in
    --port) PORT="${2:?--port needs a number}"; shift 2 ;;
    *) ARGS+=("$1"); shift ;;
  esac
done
cd "$ROOT"
page_is_stale() { # dist/ missing, or a source of the page newer than its index.html
  [ -f dist/index.html ] || return 0
  [ -n "$(find src crates assets web/page index.html Trunk.toml Cargo.toml Cargo.lock \
    -newer dist/index.html -not -path 'crates/armlab-classroom/*' -print -quit 2>/dev/null)" ]
}
if page_is_stale; then
  ensure_wasm_target
  ensure_wasm_bindgen
  ensure_trunk
  ensure_npm
  build_web
fi
say "building the classroom server (release)"
cargo build --release -p armlab-classroom
# The key the lecturers' tokens are derived from, kept across restarts: after one, only a
# class's own lecturer can re-create it.
SECRET="${XDG_STATE_HOME:-$HOME/.local/state}/armlab/classroom.secret"
say "serving page and relay on http://127.0.0.1:$PORT (Ctrl-C stops)"
exec "$CARGO_TARGET_DIR/release/armlab-classroom" --port "$PORT" --dist "$ROOT/dist" --secret-file "$SECRET" "${ARGS[@]}"
