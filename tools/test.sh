#!/usr/bin/env bash
# Runs every test (installing what is missing): fmt, clippy (native, core-only, wasm32),
# the core's and the URDF tests natively and as wasm in Node (same counts), the UI tests
# (egui_kittest on lavapipe), the JS API in Node, and the built page in headless Chromium.
# Each part is a named step (tools/steps.sh): when one fails, the run ends naming it, with
# the totals line `N passed, M failed`.
set -euo pipefail
# egui_kittest overwrites a mismatching snapshot and passes when this is set (and the
# browser test compares against the same image): never in a test run.
unset UPDATE_SNAPSHOTS
source "$(dirname "$0")/setup.sh"
cd "$ROOT"
LOG="$(mktemp -d)"
source "$ROOT/tools/steps.sh"
START=$SECONDS
at "install the wasm32 target and web/'s npm packages"
ensure_wasm_target
ensure_npm
# On a fresh machine the installs take about ten minutes of compiling and the Debian
# packages a download: they run beside the lints and the core's tests, which need none of
# them, and are awaited where first needed (apt: the UI tests; wasm-bindgen: the core's
# wasm tests; trunk: the page). The EXIT trap stops the unfinished ones.
in_background wasm-bindgen ensure_wasm_bindgen
in_background trunk ensure_trunk
if apt_unattended; then
  in_background apt ensure_apt mesa-vulkan-drivers chromium
else
  at "install Debian packages (mesa-vulkan-drivers, chromium)"
  ensure_apt mesa-vulkan-drivers chromium
fi

snapshots_hash() { # the snapshot images and their contents (new files count too)
  (cd "$ROOT" && find tests/snapshots -name '*.png' ! -name '*.diff.png' ! -name '*.old.png' ! -name '*.new.png' -print0 \
    | sort -z | xargs -0 sha256sum)
}
SNAPSHOTS_BEFORE="$(snapshots_hash)"
WASM_PASSED=0
same_count() { # same_count NATIVE WASM WHAT: the wasm run of a suite passed as many tests as its native run
  local native wasm
  read -r native _ < <(count "$LOG/$1.log")
  read -r wasm _ < <(count "$LOG/$2.log")
  say "$3: $native passed natively, $wasm passed as wasm in Node"
  if [ "$native" -eq 0 ] || [ "$native" != "$wasm" ]; then
    fail "$3 must pass in the same number natively and as wasm"
  fi
  WASM_PASSED=$((WASM_PASSED + wasm))
}

run fmt cargo fmt --check
run clippy-native cargo clippy --all-targets -- -D warnings
run clippy-core cargo clippy --no-default-features --all-targets -- -D warnings
run clippy-wasm-app cargo clippy --target wasm32-unknown-unknown --lib --bins --tests -- -D warnings
run clippy-wasm-core cargo clippy --target wasm32-unknown-unknown --no-default-features --features js --lib --tests -- -D warnings
# URDF support is an opt-in feature (it doubles the JS API's wasm): lint and test it on its own.
run clippy-urdf cargo clippy --no-default-features --features js,urdf --all-targets -- -D warnings

step "the core has no GUI or web dependency"
# The tree first, so that a failing cargo tree fails here instead of matching nothing.
core_tree="$(cargo tree --no-default-features -e normal --prefix none)"
if grep -E '^(egui|eframe|wgpu|web-sys|wasm-bindgen|js-sys)[ -]' <<<"$core_tree"; then
  fail "the core build pulls in GUI or web crates (above)"
fi
if grep -rnE '\b(egui|eframe|wgpu|web_sys|wasm_bindgen|js_sys)::' src/kinematics; then
  fail "src/kinematics imports GUI or web crates (above)"
fi

say "the docs build without warnings (core and app)"
run doc-core env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --no-default-features --lib -q
run doc-app env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib -q

step "every test file runs: a test binary of Cargo.toml or a module of tests/core.rs; a JS test in a suite's folder"
test_targets="$(awk '/^\[\[test\]\]/ { t = 1; next } /^\[/ { t = 0 } t && /^name = / { gsub(/"/, "", $3); print $3 }' Cargo.toml)"
for f in tests/*.rs; do
  name="$(basename "$f" .rs)"
  if ! grep -qx "mod $name;" tests/core.rs && ! grep -qx "$name" <<<"$test_targets"; then
    fail "$f is in no test binary (add 'mod $name;' to tests/core.rs, or a [[test]] to Cargo.toml)"
  fi
done
# The JS suites are folders, not lists of names, so a new test file runs without an edit
# here: web/tests/*.test.mjs drive the built page in Chromium; web/tests/api/*.test.mjs
# load the JS API's Node build (ARMLAB_NODE_PKG), no page and no browser.
shopt -s nullglob
BROWSER_TESTS=(web/tests/*.test.mjs)
API_TESTS=(web/tests/api/*.test.mjs)
shopt -u nullglob
[ ${#BROWSER_TESTS[@]} -gt 0 ] || fail "no browser test in web/tests/ (*.test.mjs)"
[ ${#API_TESTS[@]} -gt 0 ] || fail "no JS API test in web/tests/api/ (*.test.mjs)"
while IFS= read -r f; do
  case " ${BROWSER_TESTS[*]} ${API_TESTS[*]} " in
    *" $f "*) ;;
    *) fail "$f is in no suite (browser tests go in web/tests/, tests of the JS API in Node in web/tests/api/)" ;;
  esac
done < <(find web -path web/node_modules -prune -o -name '*.test.mjs' -print)

run core-native cargo test --no-default-features --tests
add core-native
run core-doc cargo test --no-default-features --doc
add core-doc
run urdf-native cargo test --no-default-features --features urdf --test urdf
add urdf-native

at "install Debian packages (mesa-vulkan-drivers, chromium; in the background)"
await_background apt
run ui cargo test --lib --test ui --test ui_finnish
add ui

at "install wasm-bindgen-cli (in the background)"
await_background wasm-bindgen
run core-wasm cargo test --profile wasm-test --no-default-features --tests --target wasm32-unknown-unknown
same_count core-native core-wasm "the core's tests"
add core-wasm
run urdf-wasm cargo test --profile wasm-test --no-default-features --features urdf --test urdf --target wasm32-unknown-unknown
same_count urdf-native urdf-wasm "the URDF tests"
add urdf-wasm

say "the JS API in Node"
run js-api-build cargo rustc --lib --crate-type cdylib --release --target wasm32-unknown-unknown --no-default-features --features js
run js-api-bindgen wasm-bindgen --target nodejs --out-dir "$CARGO_TARGET_DIR/armlab-node" \
  "$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/armlab.wasm"
export ARMLAB_NODE_PKG="$CARGO_TARGET_DIR/armlab-node/armlab.js"
run js-api node --test "${API_TESTS[@]}"
add js-api

at "install trunk (in the background)"
await_background trunk
run page-build build_web
run e2e node --test --test-concurrency=1 "${BROWSER_TESTS[@]}"
add e2e

step "the snapshots are unchanged"
if [ "$(snapshots_hash)" != "$SNAPSHOTS_BEFORE" ]; then
  diff <(echo "$SNAPSHOTS_BEFORE") <(snapshots_hash) || true
  fail "a snapshot image in tests/snapshots changed during the run (a test must not write its reference)"
fi

say "all tests passed in $((SECONDS - START)) s"
printf 'suites:%s\n' "$SUITES"
# The core's and the URDF tests run twice (natively and as wasm): the distinct tests count them once.
echo "distinct tests: $((passed - WASM_PASSED)) (the $WASM_PASSED core and URDF tests run natively and as wasm)"
echo "$passed passed, $failed failed"
