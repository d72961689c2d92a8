#!/usr/bin/env bash
# Runs every test (installing what is missing): fmt, clippy (every crate, native and
# wasm32; natively within the test build), the docs, the libraries' tests natively and as
# wasm in Node (same counts), the UI tests (egui_kittest on lavapipe), the JS API in Node,
# and the built page in headless Chromium.
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
# On a fresh machine the installs take about ten minutes of one core's compiling and the Debian
# packages a download: they run beside the lints and the core's tests, which need none of
# them, and are awaited where first needed (apt: the classroom server's Redis test;
# wasm-bindgen: the core's wasm tests). The page's release build follows trunk's install
# there, once wasm-bindgen is there too, and is awaited by the browser tests, so that it
# takes whatever CPU the tests leave. On a fresh machine that is little: the builds before
# keep both cores busy, and the installs and the page finish mostly after the JS API's
# tests (docs/benchmarks.md).
# The EXIT trap stops the unfinished ones.
wasm_bindgen_marked() { # ensure_wasm_bindgen, and a file in $LOG that says how it ended
  if ensure_wasm_bindgen; then touch "$LOG/wasm-bindgen.ok"; else touch "$LOG/wasm-bindgen.failed"; return 1; fi
}
in_background wasm-bindgen wasm_bindgen_marked
page_after_tools() {
  ensure_trunk || return 1
  until [ -e "$LOG/wasm-bindgen.ok" ]; do
    [ ! -e "$LOG/wasm-bindgen.failed" ] || { echo "the page waits for wasm-bindgen-cli, whose install failed"; return 1; }
    sleep 1
  done
  build_web
}
in_background page page_after_tools
if apt_unattended; then
  in_background apt ensure_apt "${DEBIAN_TEST_PACKAGES[@]}"
else
  at "install Debian packages (${DEBIAN_TEST_PACKAGES[*]})"
  ensure_apt "${DEBIAN_TEST_PACKAGES[@]}"
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

# The library crates (everything but the app and the JS package): they build without the
# GUI, natively and as wasm; their tests run both ways in equal numbers.
LIB_NAMES=(armlab-core armlab-text armlab-session armlab-api armlab-urdf armlab-bench armlab-room)
LIBS=()
for lib in "${LIB_NAMES[@]}"; do LIBS+=(-p "$lib"); done

run fmt cargo fmt --all --check
# Every feature of the workspace's crates.
FEATURES=armlab-js/urdf,armlab-bench/frame,armlab-bench/classroom
# The app, the libraries and the JS package in one check, so that the dependencies they
# share are checked once, with their features joined. The native lint is part of the native
# test build below.
run clippy-wasm cargo clippy --target wasm32-unknown-unknown -p armlab "${LIBS[@]}" -p armlab-js --features armlab-js/urdf \
  --lib --bin armlab --tests -- -D warnings

# The manifests keep the boundaries (crates/armlab-core/Cargo.toml names no GUI, web or
# text crate); this checks it a second time, on what cargo resolves and on the sources.
step "the core has no GUI, web or text dependency; no library has a GUI or web one"
for lib in "${LIB_NAMES[@]}"; do
  # The tree first, so that a failing cargo tree fails here instead of matching nothing.
  tree="$(cargo tree -p "$lib" -e normal --prefix none)"
  if grep -E '^(egui|eframe|wgpu|web-sys|wasm-bindgen|js-sys)[ -]' <<<"$tree"; then
    fail "$lib pulls in GUI or web crates (above)"
  fi
done
if grep -E '^armlab-text ' <<<"$(cargo tree -p armlab-core -e normal --prefix none)"; then
  fail "the core depends on the text catalogue"
fi
# Code lines only: the core's docs may name the crate that words its errors.
if grep -rnE '\b(egui|eframe|wgpu|web_sys|wasm_bindgen|js_sys|armlab_text)::' crates/armlab-core/src \
  | grep -vE '^[^:]+:[0-9]+:[[:space:]]*//'; then
  fail "crates/armlab-core imports GUI, web or text crates (above)"
fi

say "the docs build without warnings"
# For wasm32, where rustdoc reads the dependencies as the wasm lint above checked them; a
# native doc would check every native dependency first, which nothing else does natively
# (the native lint is a build): about 5 min of CPU on a new machine. The classroom server,
# which has no wasm build, natively. The app's desktop-only code (platform/native) is then
# not in the docs; the native lint reads it.
run doc env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --target wasm32-unknown-unknown \
  -p armlab "${LIBS[@]}" -p armlab-js --features armlab-js/urdf -q
run doc-server env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps -p armlab-classroom -q

step "every test file runs: a test binary of its crate or a module of one; a JS test in a suite's folder"
for dir in . crates/*; do
  [ -d "$dir/tests" ] || continue
  test_paths="$(awk '/^\[\[test\]\]/ { t = 1; next } /^\[/ { t = 0 } t && /^path = / { gsub(/"/, "", $3); print $3 }' "$dir/Cargo.toml")"
  test_names="$(awk '/^\[\[test\]\]/ { t = 1; next } /^\[/ { t = 0 } t && /^name = / { gsub(/"/, "", $3); print $3 }' "$dir/Cargo.toml")"
  for f in "$dir"/tests/*.rs; do
    name="$(basename "$f" .rs)"
    if grep -qx "tests/$name.rs" <<<"$test_paths" || grep -qx "$name" <<<"$test_names" \
      || grep -qx "mod $name;" "$dir"/tests/*.rs; then
      continue
    fi
    fail "$f is in no test binary (add 'mod $name;' to its crate's test binary, or a [[test]] to its Cargo.toml)"
  done
  # A folder with a main.rs is a test binary of its own; each file beside it is a module.
  for main in "$dir"/tests/*/main.rs; do
    [ -f "$main" ] || continue
    for f in "$(dirname "$main")"/*.rs; do
      name="$(basename "$f" .rs)"
      [ "$name" = main ] || grep -qx "mod $name;" "$main" \
        || fail "$f is in no test binary (add 'mod $name;' to $main)"
    done
  done
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

# Every native test program comes from one build: cargo gives a dependency the features
# that the packages built together ask for, so the libraries, the classroom server and the
# app, each built alone, compiled nalgebra, parry3d, serde and some 30 more crates two or
# three times. Each suite then runs its packages' programs from that build.
# The same build is the native lint: cargo hands the workspace's own crates to
# tools/lint-rustc (clippy-driver, with -D warnings) in place of rustc, as `cargo clippy`
# does, and clippy-driver compiles each crate once it has linted it. `cargo clippy` itself
# checks every dependency without compiling it, work no build can reuse (on a new machine
# about 5 min of CPU). Hence every target of every crate, with every feature: the
# benchmarks and the binaries are linted too, though only the test programs run.
NATIVE=(--workspace --features "$FEATURES")
native_cargo() { RUSTC_WORKSPACE_WRAPPER="$ROOT/tools/lint-rustc" cargo "$@"; }
native_build() { # the JSON lists the test programs (native_tests); the words go to the log
  native_cargo test "${NATIVE[@]}" --all-targets --no-run --message-format=json-render-diagnostics >"$LOG/native-tests.json"
}
native_tests() { # native_tests PACKAGE...: as cargo test runs them, in the package's folder, until one fails
  local pkg dir exe
  while IFS=$'\t' read -r pkg dir exe; do
    case " $* " in *" $pkg "*) ;; *) continue ;; esac
    echo "     Running ${exe#"$CARGO_TARGET_DIR"/} ($pkg)"
    (cd "$dir" && CARGO_MANIFEST_DIR="$dir" CARGO_PKG_NAME="$pkg" "$exe") || return 1
  done < <(node -e '
    for (const line of require("fs").readFileSync(process.argv[1], "utf8").split("\n")) {
      if (!line.startsWith("{")) continue;
      const m = JSON.parse(line);
      // The targets cargo test runs: not the benchmarks, nor the binaries without tests.
      if (m.reason !== "compiler-artifact" || !m.profile.test || !m.target.test || !m.executable) continue;
      // "path+file:///dir#name@version", or "…/name#version" where the folder is named so.
      const [url, tail] = m.package_id.split("#");
      const name = tail.includes("@") ? tail.split("@")[0] : url.split("/").pop();
      console.log([name, require("path").dirname(m.manifest_path), m.executable].join("\t"));
    }' "$LOG/native-tests.json")
}
run native-clippy-build native_build
run libs-native native_tests "${LIB_NAMES[@]}"
add libs-native
run libs-doc native_cargo test "${NATIVE[@]}" --doc
add libs-doc

at "install Debian packages (${DEBIAN_TEST_PACKAGES[*]}; in the background)"
await_background apt
# The classroom server (not a library: tokio and axum, natively only): its relay, rules
# and Redis tests on in-process servers (redis-server from Debian), and the fuzz of its
# message decoding (1,000,000 messages).
run classroom native_tests armlab-classroom
add classroom
# The JS package's own tests (its feature urdf, which the native build has).
run js-native native_tests armlab-js
add js-native

at "install wasm-bindgen-cli (in the background)"
await_background wasm-bindgen
# With the QR encoder, as in the native build (where the app asks for it).
# With the JS package (whose own tests need its feature urdf: they run natively, above),
# so that the JS API's Node module below comes from this call's dependencies: in a cargo
# call of its own, without the libraries' test dependencies, serde, approx, wasm-bindgen
# and js-sys resolve to other features, and cargo compiles them, nalgebra, parry3d and the
# workspace's crates a second time (about 80 s of CPU on a fresh machine).
WASM_TESTS=(--profile wasm-test "${LIBS[@]}" -p armlab-js --features armlab-room/qr --target wasm32-unknown-unknown)
run libs-wasm cargo test "${WASM_TESTS[@]}" --tests
same_count libs-native libs-wasm "the libraries' tests (core, text, session, JSON API, URDF, benchmarks, lecture-room protocol)"
add libs-wasm

say "the JS API in Node"
# The package's module from the libraries' wasm test build above (the same call, with its
# libraries: --lib links armlab-js's cdylib, and cargo finds every other crate built), in
# their profile (a release build compiled every crate again); debug assertions stay on. Its
# own output folder: web/scripts/' benchmarks load the release build.
run js-api-build cargo build "${WASM_TESTS[@]}" --tests --lib
run js-api-bindgen wasm-bindgen --target nodejs --out-dir "$CARGO_TARGET_DIR/armlab-node-test" --out-name armlab \
  "$CARGO_TARGET_DIR/wasm32-unknown-unknown/wasm-test/armlab_js.wasm"
export ARMLAB_NODE_PKG="$CARGO_TARGET_DIR/armlab-node-test/armlab.js"
run js-api node --test "${API_TESTS[@]}"
add js-api

# The UI tests (egui_kittest) run beside the page's release build, in the idle scheduling
# class, so that they take no CPU the build wants: on a fresh machine the build ends on one
# core (the page's link-time optimisation, then wasm-opt: about 3 min), and they take the
# other (docs/benchmarks.md, the test command). Awaited before the browser tests, which
# would draw beside them.
ui_tests() { native_tests armlab 2>&1 | tee "$LOG/ui.log"; }
in_background --idle ui ui_tests
at "page-build (trunk's install and the page's build, in the background)"
await_background page
step "ui (begun in the background beside the page's build)"
STEP_LOG="$LOG/ui.log"
await_background ui
add ui
# Two test files at a time: a file's page often waits (a lecture room's student offline for
# 30 s, the live region's once a second) while the other draws; 355 s against 452 s one at a
# time. The frame times the tests print are then taken beside another page: the scripts in
# web/scripts/ measure alone.
run e2e node --test --test-concurrency=2 "${BROWSER_TESTS[@]}"
add e2e

step "the snapshots are unchanged"
if [ "$(snapshots_hash)" != "$SNAPSHOTS_BEFORE" ]; then
  diff <(echo "$SNAPSHOTS_BEFORE") <(snapshots_hash) || true
  fail "a snapshot image in tests/snapshots changed during the run (a test must not write its reference)"
fi

print_times
say "all tests passed in $((SECONDS - START)) s"
printf 'suites:%s\n' "$SUITES"
# The libraries' tests run twice (natively and as wasm): the distinct tests count them once.
echo "distinct tests: $((passed - WASM_PASSED)) (the $WASM_PASSED library tests run natively and as wasm)"
echo "$passed passed, $failed failed"
