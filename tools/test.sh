#!/usr/bin/env bash
# Runs every test (installing what is missing): fmt, clippy (native, core-only, wasm32),
# the core's tests natively and as wasm in Node (same count), the UI tests (egui_kittest on
# lavapipe), the JS API in Node, and the built page in headless Chromium.
set -euo pipefail
# egui_kittest overwrites a mismatching snapshot and passes when this is set (and the
# browser test compares against the same image): never in a test run.
unset UPDATE_SNAPSHOTS
source "$(dirname "$0")/setup.sh"
cd "$ROOT"
START=$SECONDS
ensure_wasm_target
ensure_npm
# On a fresh machine the installs take about ten minutes of compiling and the Debian
# packages a download: they run beside the lints and the core's tests, which need none of
# them, and are awaited where first needed (apt: the UI tests; wasm-bindgen: the core's
# wasm tests; trunk: the page).
trap stop_background EXIT
in_background wasm-bindgen ensure_wasm_bindgen
in_background trunk ensure_trunk
if apt_unattended; then
  in_background apt ensure_apt mesa-vulkan-drivers chromium
else
  ensure_apt mesa-vulkan-drivers chromium
fi

LOG="$(mktemp -d)"
passed=0
failed=0
count() { # sums cargo's "test result: ... N passed; M failed" and node's "# pass N" / "# fail M"
  local p f
  p=$(grep -Eo 'test result: [a-zA-Z]+\. [0-9]+ passed|^# pass [0-9]+' "$1" | grep -Eo '[0-9]+' | awk '{s+=$1} END {print s+0}')
  f=$(grep -Eo '[0-9]+ passed; [0-9]+ failed|^# fail [0-9]+' "$1" | grep -Eo '[0-9]+$|[0-9]+ failed' | grep -Eo '[0-9]+' | awk '{s+=$1} END {print s+0}')
  echo "$p $f"
}
not_run() { # ignored + filtered out (cargo), skipped + todo (node): tests that exist but did not run
  { grep -Eo '[0-9]+ ignored;( [0-9]+ measured;)? [0-9]+ filtered out|^# (skipped|todo) [0-9]+' "$1" || true; } \
    | { grep -Eo '[0-9]+ ignored|[0-9]+ filtered|(skipped|todo) [0-9]+' || true; } \
    | awk '{ for (i = 1; i <= NF; i++) if ($i ~ /^[0-9]+$/) s += $i } END {print s+0}'
}
run() { # run NAME CMD...: runs, keeps the log, adds its counts
  local name="$1"; shift
  say "$name"
  local log="$LOG/$name.log"
  if "$@" 2>&1 | tee "$log"; then :; else
    read -r p f < <(count "$log")
    echo "FAILED: $name"
    echo "$((passed + p)) passed, $((failed + f + 1)) failed"
    exit 1
  fi
}
SUITES=""
add() { # adds a test suite's counts; a suite that ran no test fails the run
  read -r p f < <(count "$LOG/$1.log")
  local skipped; skipped=$(not_run "$LOG/$1.log")
  if [ "$p" -eq 0 ]; then
    echo "FAILED: the suite $1 ran no test"
    echo "$passed passed, $((failed + f + 1)) failed"
    exit 1
  fi
  passed=$((passed + p)); failed=$((failed + f))
  SUITES="$SUITES
  $1: $p passed, $f failed, $skipped ignored, skipped or filtered out"
}
snapshots_hash() { # the snapshot images and their contents (new files count too)
  (cd "$ROOT" && find tests/snapshots -name '*.png' ! -name '*.diff.png' ! -name '*.old.png' ! -name '*.new.png' -print0 \
    | sort -z | xargs -0 sha256sum)
}
SNAPSHOTS_BEFORE="$(snapshots_hash)"

run fmt cargo fmt --check
run clippy-native cargo clippy --all-targets -- -D warnings
run clippy-core cargo clippy --no-default-features --all-targets -- -D warnings
run clippy-wasm-app cargo clippy --target wasm32-unknown-unknown --lib --bins --tests -- -D warnings
run clippy-wasm-core cargo clippy --target wasm32-unknown-unknown --no-default-features --features js --lib --tests -- -D warnings
# URDF support is an opt-in feature (it doubles the JS API's wasm): lint and test it on its own.
run clippy-urdf cargo clippy --no-default-features --features js,urdf --all-targets -- -D warnings

say "the core has no GUI or web dependency"
if cargo tree --no-default-features -e normal --prefix none | grep -E '^(egui|eframe|wgpu|web-sys|wasm-bindgen|js-sys)[ -]'; then
  echo "FAILED: the core build pulls in GUI or web crates (above)"; exit 1
fi
if grep -rnE '\b(egui|eframe|wgpu|web_sys|wasm_bindgen|js_sys)::' src/kinematics; then
  echo "FAILED: src/kinematics imports GUI or web crates (above)"; exit 1
fi

say "the docs build without warnings (core and app)"
run doc-core env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --no-default-features --lib -q
run doc-app env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib -q

say "every test file is built: a test binary of Cargo.toml or a module of tests/core.rs"
test_targets="$(awk '/^\[\[test\]\]/ { t = 1; next } /^\[/ { t = 0 } t && /^name = / { gsub(/"/, "", $3); print $3 }' Cargo.toml)"
for f in tests/*.rs; do
  name="$(basename "$f" .rs)"
  if ! grep -qx "mod $name;" tests/core.rs && ! grep -qx "$name" <<<"$test_targets"; then
    echo "FAILED: $f is in no test binary (add 'mod $name;' to tests/core.rs, or a [[test]] to Cargo.toml)"; exit 1
  fi
done

run core-native cargo test --no-default-features --tests
run core-doc cargo test --no-default-features --doc
add core-native; add core-doc
run core-urdf cargo test --no-default-features --features urdf --test urdf
add core-urdf

await_background apt
run ui cargo test --lib --test ui --test ui_finnish
add ui

await_background wasm-bindgen
run core-wasm cargo test --profile wasm-test --no-default-features --tests --target wasm32-unknown-unknown
read -r native _ < <(count "$LOG/core-native.log")
read -r wasm _ < <(count "$LOG/core-wasm.log")
say "core tests: $native passed natively, $wasm passed as wasm in Node"
if [ "$native" -eq 0 ] || [ "$native" != "$wasm" ]; then
  echo "FAILED: the core's tests must pass in the same number natively and as wasm"; exit 1
fi
add core-wasm

say "the JS API in Node"
cargo rustc --lib --crate-type cdylib --release --target wasm32-unknown-unknown --no-default-features --features js
wasm-bindgen --target nodejs --out-dir "$CARGO_TARGET_DIR/armlab-node" \
  "$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/armlab.wasm"
export ARMLAB_NODE_PKG="$CARGO_TARGET_DIR/armlab-node/armlab.js"
run js-api node --test web/tests/api/api.test.mjs
add js-api

await_background trunk
build_web
run e2e node --test --test-concurrency=1 web/tests/e2e.test.mjs web/tests/offline.test.mjs web/tests/urdf.test.mjs web/tests/motion.test.mjs web/tests/collision.test.mjs web/tests/exercise.test.mjs
add e2e

say "the snapshots are unchanged"
if [ "$(snapshots_hash)" != "$SNAPSHOTS_BEFORE" ]; then
  echo "FAILED: a snapshot image in tests/snapshots changed during the run (a test must not write its reference)"
  diff <(echo "$SNAPSHOTS_BEFORE") <(snapshots_hash) || true
  echo "$passed passed, $((failed + 1)) failed"
  exit 1
fi

say "all tests passed in $((SECONDS - START)) s"
printf 'suites:%s\n' "$SUITES"
# The core's tests run twice (natively and as wasm): the distinct tests count them once.
echo "distinct tests: $((passed - wasm)) (the $wasm core tests run natively and as wasm)"
echo "$passed passed, $failed failed"
