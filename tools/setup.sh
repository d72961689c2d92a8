# Sourced by tools/serve.sh and tools/test.sh: installs what is missing, skips what is
# there in the right version (installing trunk or wasm-bindgen-cli costs ~10 min each on
# 2 cores). Everything comes from crates.io, npm or Debian; nothing else is downloaded.

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="$HOME/.cargo/bin:$ROOT/web/node_modules/.bin:$PATH"
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

ensure_wasm_bindgen() {
  local want; want="$(wasm_bindgen_version)"
  if ! wasm-bindgen --version 2>/dev/null | grep -q " $want\$"; then
    say "installing wasm-bindgen-cli $want (about 10 minutes)"
    cargo install wasm-bindgen-cli --version "$want"
  fi
}

ensure_trunk() {
  if ! trunk --version 2>/dev/null | grep -q " $TRUNK_VERSION\$"; then
    say "installing trunk $TRUNK_VERSION (about 10 minutes)"
    cargo install trunk --version "$TRUNK_VERSION" --locked
  fi
}

# binaryen's wasm-opt (v132, from npm: Debian's v108 breaks eframe pages) and
# playwright-core, pinned by web/package-lock.json.
ensure_npm() {
  if [ ! -x "$ROOT/web/node_modules/.bin/wasm-opt" ] || [ ! -d "$ROOT/web/node_modules/playwright-core" ]; then
    say "installing web/ npm packages"
    (cd "$ROOT/web" && npm ci --no-audit --no-fund)
  fi
}

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
build_web() {
  say "building the page (trunk build --release)"
  (cd "$ROOT" && cargo fetch --target wasm32-unknown-unknown -q \
    && CARGO_TARGET_DIR="$CARGO_TARGET_DIR/web" CARGO_PROFILE_RELEASE_OPT_LEVEL=z CARGO_PROFILE_RELEASE_PANIC=abort \
       CARGO_PROFILE_RELEASE_LTO=fat \
       CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1 \
       trunk build --release --offline "$@")
}
