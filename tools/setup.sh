# Sourced by tools/serve.sh and tools/test.sh: installs what is missing, skips what is
# there in the right version (trunk and wasm-bindgen-cli are compiled: about 3 min each on
# 2 cores). Everything comes from crates.io, npm or Debian; nothing else is downloaded.

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# tools/cached first: its wasm-opt keeps results by input and flags (a warm build skips the
# minute of -Oz passes), and calls npm binaryen's wasm-opt in web/node_modules/.bin.
export PATH="$HOME/.cargo/bin:$ROOT/tools/cached:$ROOT/web/node_modules/.bin:$PATH"
TRUNK_VERSION="0.21.14"
# Build output outside the clone, so that CI's fresh clones on a warm machine reuse
# compiled dependencies (a brand-new machine starts cold either way).
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/armlab/target}"
mkdir -p "$CARGO_TARGET_DIR"

say() { printf '\n\033[1m== %s\033[0m\n' "$*"; }

ensure_wasm_target() {
  rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown \
    || { say "adding the wasm32 target"; rustup target add wasm32-unknown-unknown; }
}

# wasm-bindgen-cli must equal the wasm-bindgen version in Cargo.lock.
wasm_bindgen_version() {
  awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' "$ROOT/Cargo.lock"
}

# `install_tool OPT_LEVEL CRATE ARGS...`: cargo install with a quick release profile. Both
# tools spend their time in the programs they start or in reading a few files, not in their
# own code, so compiling them fast beats compiling them well. Trunk's own profile asks for
# fat LTO and one codegen unit; without them it took 700 s of CPU at opt-level 1 and 300 s
# at opt-level 0, and the opt-level 0 trunk builds the same page in the same 16 s.
# The build runs in cargo's own temporary folder, not in CARGO_TARGET_DIR (which cargo
# install would use): the tests' builds there would wait on its lock while it runs in the
# background.
install_tool() {
  local opt="$1"; shift
  env -u CARGO_TARGET_DIR CARGO_PROFILE_RELEASE_OPT_LEVEL="$opt" CARGO_PROFILE_RELEASE_LTO=false \
    CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 CARGO_PROFILE_RELEASE_DEBUG=false cargo install "$@"
}

# `optimised LEVEL PACKAGE...`: the --config arguments that give those packages of a tool
# opt-level LEVEL over install_tool's.
optimised() {
  local level="$1" pkg; shift
  for pkg in "$@"; do printf -- '--config\nprofile.release.package.%s.opt-level=%s\n' "$pkg" "$level"; done
}

ensure_wasm_bindgen() {
  local want; want="$(wasm_bindgen_version)"
  if ! wasm-bindgen --version 2>/dev/null | grep -q " $want\$"; then
    say "installing wasm-bindgen-cli $want (about 3 minutes)"
    # Without its default TLS (rustls and ring, for downloading a browser's WebDriver):
    # the wasm tests run in Node. wasm-bindgen parses and rewrites every wasm the tests and
    # the page make (several MB each): the crates that do that (walrus and the wasm
    # parser, encoder and the bindings' generator) are optimised a little, the rest not.
    # All at opt-level 1 took 325 s of CPU, this 230 s; it handles the page's wasm in 1.4 s
    # instead of 1.0 s, a test's in 0.6 s instead of 0.5 s.
    local hot; mapfile -t hot < <(optimised 1 walrus wasmparser wasm-encoder wasm-bindgen-cli-support id-arena)
    install_tool 0 wasm-bindgen-cli --version "$want" --no-default-features "${hot[@]}"
  fi
}

ensure_trunk() {
  if ! trunk --version 2>/dev/null | grep -q " $TRUNK_VERSION\$"; then
    say "installing trunk $TRUNK_VERSION (about 3 minutes)"
    install_tool 0 trunk --version "$TRUNK_VERSION" --locked
  fi
}

# binaryen's wasm-opt (v132, from npm: Debian's v108 breaks eframe pages), esbuild (minifies
# the page's JS glue: web/build/minify-build.mjs), xzwasm (the page's xz decoder:
# web/build/pack-wasm.mjs) and playwright-core, pinned by web/package-lock.json.
ensure_npm() {
  if [ ! -x "$ROOT/web/node_modules/.bin/wasm-opt" ] || [ ! -d "$ROOT/web/node_modules/playwright-core" ] \
    || [ ! -d "$ROOT/web/node_modules/esbuild" ] || [ ! -d "$ROOT/web/node_modules/xzwasm" ]; then
    say "installing web/ npm packages"
    (cd "$ROOT/web" && npm ci --no-audit --no-fund)
  fi
}

# A slow install in the background at the lowest CPU priority, so that it takes the time the
# foreground leaves idle (a single-threaded compile of the crate, a test run, a download)
# instead of running before everything: `in_background NAME CMD...` starts CMD with its
# output kept in a log, `await_background NAME` waits for it and shows that log (and fails
# with it when CMD failed; a NAME never started is nothing to wait for). On exit, unfinished
# ones are stopped (`stop_background`). `in_background --idle NAME CMD...` runs CMD in the
# idle scheduling class instead (chrt; no privilege needed): it gets only the CPU that no
# other process, a niced one included, wants.
declare -A BG_PID=() BG_LOG=()
in_background() {
  local class=(renice -n 19 -p)
  if [ "$1" = --idle ]; then class=(chrt --idle -p 0); shift; fi
  local name="$1"; shift
  BG_LOG[$name]="$(mktemp)"
  ("${class[@]}" "$BASHPID" >/dev/null 2>&1 || true; "$@") >"${BG_LOG[$name]}" 2>&1 &
  BG_PID[$name]=$!
}
await_background() {
  local name="$1" status=0
  [ -n "${BG_PID[$name]:-}" ] || return 0
  kill -0 "${BG_PID[$name]}" 2>/dev/null && say "waiting for $name (in the background)"
  wait "${BG_PID[$name]}" || status=$?
  unset "BG_PID[$name]"
  cat "${BG_LOG[$name]}" && rm -f "${BG_LOG[$name]}"
  [ $status -eq 0 ] || { echo "FAILED: $name (in the background) ended with status $status"; return 1; }
}
stop_background() {
  local name
  for name in "${!BG_PID[@]}"; do
    kill_tree "${BG_PID[$name]}"
    rm -f "${BG_LOG[$name]}"
  done
}
kill_tree() { # a process and everything it started (cargo's rustc processes too)
  local child
  for child in $(pgrep -P "$1" 2>/dev/null); do kill_tree "$child"; done
  kill "$1" 2>/dev/null || true
}

# Whether ensure_apt can install without asking for a password (as root, or sudo -n).
apt_unattended() {
  [ "$(id -u)" = 0 ] || sudo -n true 2>/dev/null
}

# The Debian packages the tests need: Vulkan on the CPU (lavapipe) for the UI tests, the
# browser for the page's tests, Redis for the classroom server's two-instance test.
DEBIAN_TEST_PACKAGES=(mesa-vulkan-drivers chromium redis-server)

APT_UPDATED=0
ensure_apt() {
  local missing=()
  for pkg in "$@"; do
    dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    say "installing Debian packages: ${missing[*]}"
    local sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
    [ $APT_UPDATED = 1 ] || { $sudo apt-get update -qq; APT_UPDATED=1; }
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
  fi
}

# The release web build: small over fast (opt-level z, fat LTO, one codegen unit, abort on
# panic), then wasm-opt -Oz through trunk (index.html's data-wasm-opt), which also strips
# names (stripping in cargo would hide the wasm feature section from wasm-bindgen). Its own
# target folder, so that these profile settings do not rebuild the JS API's release build.
#
# A panic in the page aborts into the crash screen, which says what to do in words: the
# file, line and column of every place that can panic (a bounds check, an `expect`) are
# bytes no visitor reads. `-Zlocation-detail=none` leaves them out, `-Zfmt-debug=shallow`
# makes a derived `Debug` print its type's or variant's name without the fields, and
# tools/page-rustc (the build's RUSTC_WRAPPER) makes `{:?}` print nothing in every crate
# but the few whose `{:?}` is read (the page writes no `{:?}` a person reads: its sentences
# come from the catalogue, and its logs are compiled out); the crates' paths that remain
# are written without the folder cargo unpacks them into. Stable rustc takes these -Z
# flags with RUSTC_BOOTSTRAP, set for the page's build alone. They replace
# .cargo/config.toml's for wasm32, so they repeat its SIMD flag.
build_web() {
  say "building the page (trunk build --release)"
  # xz packs the page's wasm (web/build/pack-wasm.mjs): Debian's xz-utils, in most installs.
  command -v xz >/dev/null || ensure_apt xz-utils || return 1
  (cd "$ROOT" && cargo fetch --target wasm32-unknown-unknown -q) || return 1
  # Cargo does not see what a RUSTC_WRAPPER adds to a crate's flags: page-rustc's code (not
  # its comments) keys the build's cache (its checksum as a -C metadata, which only mixes
  # into the crates' hashes), so that a change to it compiles every crate again.
  local key; key="$(grep -v '^#' "$ROOT/tools/page-rustc" | cksum | cut -d' ' -f1)"
  local flags="-Ctarget-feature=+simd128 -Zlocation-detail=none -Zfmt-debug=shallow -Cmetadata=page-rustc-$key" registry
  for registry in "${CARGO_HOME:-$HOME/.cargo}"/registry/src/*/; do
    flags="$flags --remap-path-prefix=$registry="
  done
  (cd "$ROOT" && CARGO_TARGET_DIR="$CARGO_TARGET_DIR/web" CARGO_PROFILE_RELEASE_OPT_LEVEL=z CARGO_PROFILE_RELEASE_PANIC=abort \
       CARGO_PROFILE_RELEASE_LTO=fat \
       CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1 \
       CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="$flags" RUSTC_BOOTSTRAP=1 \
       RUSTC_WRAPPER="$ROOT/tools/page-rustc" trunk build --release --offline "$@")
}

# The URDF module: the JS package (armlab-js) built with its feature urdf (no GUI) as a second wasm module
# in dist/urdf/, which the page imports only when a URDF file is opened or saved, collisions
# are checked or the symbolic matrices are shown (the module is ~300 kB gzip, urdf-rs and its
# XML crates, the collision library and the symbolic algebra included: more than the first
# load's budget leaves). Trunk runs this as a build hook (Trunk.toml), so `trunk build` and `trunk serve`
# make it too, beside the page and with its settings: build_web's profile variables, and in
# release wasm-opt with index.html's data-wasm-opt level and data-wasm-opt-params. Its own
# target folder inside the page's, so that the two builds' settings do not rebuild each
# other. Writes $TRUNK_STAGING_DIR/urdf/armlab_urdf.js and
# armlab_urdf-HASH_bg.wasm (HASH from cargo's wasm, so a new build never pairs with an old
# cached wasm); the bindgen'd and optimised result is kept per HASH, so a build that changes
# nothing here costs cargo's freshness check and a copy.
build_urdf_module() {
  local out="${TRUNK_STAGING_DIR:?set by trunk: build_urdf_module is its build hook (Trunk.toml)}/urdf"
  local target="$CARGO_TARGET_DIR/urdf-module" profile=release
  local flags=(-p armlab-js --lib --crate-type cdylib --target wasm32-unknown-unknown --features urdf --locked)
  if [ "${TRUNK_PROFILE:-release}" = release ]; then flags+=(--release); else profile=debug; fi
  # Without build_web's RUSTC_WRAPPER: the module's `{:?}` stays (a broken URDF file's
  # sentence quotes the XML parser's words).
  (cd "$ROOT" && CARGO_TARGET_DIR="$target" env -u RUSTC_WRAPPER cargo rustc -q "${flags[@]}") || return 1
  local wasm="$target/wasm32-unknown-unknown/$profile/armlab_js.wasm"
  # The page's wasm-opt settings, which the module's build is kept under too.
  local level params
  level="$(sed -n 's/.*data-wasm-opt="\([^"]*\)".*/\1/p' "$ROOT/index.html" | head -1)"
  params="$(sed -n 's/.*data-wasm-opt-params="\([^"]*\)".*/\1/p' "$ROOT/index.html" | head -1)"
  local hash; hash="$({ cat "$wasm"; echo "$profile $level $params"; } | sha256sum | cut -c1-16)"
  local kept="$target/bindgen/$hash"
  if [ ! -f "$kept/armlab_urdf.js" ]; then
    rm -rf "$target/bindgen" && mkdir -p "$kept.tmp" || return 1
    wasm-bindgen --target web --no-typescript --out-dir "$kept.tmp" --out-name "armlab_urdf-$hash" "$wasm" || return 1
    mv "$kept.tmp/armlab_urdf-$hash.js" "$kept.tmp/armlab_urdf.js"
    if [ "$profile" = release ]; then
      # shellcheck disable=SC2086 # params is a list of flags
      wasm-opt "-O${level:-z}" $params "$kept.tmp/armlab_urdf-${hash}_bg.wasm" -o "$kept.tmp/armlab_urdf-${hash}_bg.wasm" || return 1
    fi
    mv "$kept.tmp" "$kept"
  fi
  mkdir -p "$out" && cp "$kept"/* "$out/"
}
