#!/usr/bin/env bash
# Runs every test (installing what is missing): fmt, clippy (native and wasm32, every
# crate), the libraries' tests natively and as wasm in Node (same count), the UI tests
# (egui_kittest on lavapipe), the JS API in Node, and the built page in headless Chromium.
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

# The library crates (everything but the app): they build without the GUI, natively and as
# wasm; their tests run both ways in equal numbers.
LIBS=(-p armlab-core -p armlab-text -p armlab-session -p armlab-api -p armlab-urdf -p armlab-bench)

run fmt cargo fmt --all --check
run clippy-native cargo clippy --workspace --all-targets --features armlab-js/urdf,armlab-bench/frame -- -D warnings
run clippy-wasm-app cargo clippy --target wasm32-unknown-unknown -p armlab --lib --bins --tests -- -D warnings
run clippy-wasm-libs cargo clippy --target wasm32-unknown-unknown "${LIBS[@]}" -p armlab-js --features armlab-js/urdf --lib --tests -- -D warnings

# The manifests keep the boundaries (crates/armlab-core/Cargo.toml names no GUI, web or
# text crate); this checks it a second time, on what cargo resolves and on the sources.
say "the core has no GUI, web or text dependency; no library has a GUI one"
for lib in armlab-core armlab-text armlab-session armlab-api armlab-urdf armlab-bench; do
  if cargo tree -p "$lib" -e normal --prefix none | grep -E '^(egui|eframe|wgpu|web-sys|wasm-bindgen|js-sys)[ -]'; then
    echo "FAILED: $lib pulls in GUI or web crates (above)"; exit 1
  fi
done
if cargo tree -p armlab-core -e normal --prefix none | grep -E '^armlab-text '; then
  echo "FAILED: the core depends on the text catalogue"; exit 1
fi
if grep -rnE '\b(egui|eframe|wgpu|web_sys|wasm_bindgen|js_sys|armlab_text)::' crates/armlab-core/src; then
  echo "FAILED: crates/armlab-core imports GUI, web or text crates (above)"; exit 1
fi

say "the docs build without warnings"
run doc env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --workspace --features armlab-js/urdf -q

say "every test file is built: a test binary of its crate or a module of one"
for dir in . crates/*; do
  [ -d "$dir/tests" ] || continue
  test_paths="$(awk '/^\[\[test\]\]/ { t = 1; next } /^\[/ { t = 0 } t && /^path = / { gsub(/"/, "", $3); print $3 }' "$dir/Cargo.toml")"
  test_names="$(awk '/^\[\[test\]\]/ { t = 1; next } /^\[/ { t = 0 } t && /^name = / { gsub(/"/, "", $3); print $3 }' "$dir/Cargo.toml")"
  for f in "$dir"/tests/*.rs; do
    name="$(basename "$f" .rs)"
    if grep -qx "tests/$name.rs" <<<"$test_paths" || grep -qx "$name" <<<"$test_names" \
      || cat "$dir"/tests/*.rs | grep -qx "mod $name;"; then
      continue
    fi
    echo "FAILED: $f is in no test binary (add 'mod $name;' to its crate's test binary, or a [[test]])"; exit 1
  done
done

run libs-native cargo test "${LIBS[@]}" --tests
run libs-doc cargo test "${LIBS[@]}" --doc
add libs-native; add libs-doc

await_background apt
run ui cargo test -p armlab --lib --test ui --test ui_finnish
add ui

await_background wasm-bindgen
run libs-wasm cargo test --profile wasm-test "${LIBS[@]}" --tests --target wasm32-unknown-unknown
read -r native _ < <(count "$LOG/libs-native.log")
read -r wasm _ < <(count "$LOG/libs-wasm.log")
say "library tests: $native passed natively, $wasm passed as wasm in Node"
if [ "$native" -eq 0 ] || [ "$native" != "$wasm" ]; then
  echo "FAILED: the libraries' tests must pass in the same number natively and as wasm"; exit 1
fi
add libs-wasm

say "the JS API in Node"
cargo rustc -p armlab-js --lib --crate-type cdylib --release --target wasm32-unknown-unknown
wasm-bindgen --target nodejs --out-dir "$CARGO_TARGET_DIR/armlab-node" --out-name armlab \
  "$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/armlab_js.wasm"
export ARMLAB_NODE_PKG="$CARGO_TARGET_DIR/armlab-node/armlab.js"
run js-api node --test web/api.test.mjs
add js-api

await_background trunk
build_web
run e2e node --test --test-concurrency=1 web/e2e.test.mjs web/offline.test.mjs web/urdf.test.mjs web/motion.test.mjs web/collision.test.mjs web/exercise.test.mjs
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
# The libraries' tests run twice (natively and as wasm): the distinct tests count them once.
echo "distinct tests: $((passed - wasm)) (the $wasm library tests run natively and as wasm)"
echo "$passed passed, $failed failed"
