#!/usr/bin/env bash
# The peer benchmark (docs/benchmarks.md): RTB's C++ ik_LM beside ArmLab's ikbench on the
# UR10, same protocol, same targets, same seed; prints one JSON. Not part of tools/test.sh.
#
#   bash tools/peers/run.sh [--samples N] [--rounds R]
#
# Creates tools/peers/.venv (Python's venv; Debian's python3-venv is installed if venv is
# missing) with roboticstoolbox-python from PyPI the first time, and builds ikbench
# natively in release (core only, no GUI).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$HERE/../setup.sh"
# Progress to stderr: stdout is the JSON alone.
say() { printf '== %s\n' "$*" >&2; }
RTB_VERSION="1.5.0"
VENV="$HERE/.venv"

if [ ! -x "$VENV/bin/python" ]; then
  python3 -c 'import venv, ensurepip' 2>/dev/null || ensure_apt python3-venv
  say "creating $VENV"
  python3 -m venv "$VENV" >&2
fi
if ! "$VENV/bin/python" -c "import roboticstoolbox as r; assert r.__version__ == '$RTB_VERSION'" 2>/dev/null; then
  say "installing roboticstoolbox-python $RTB_VERSION into $VENV"
  "$VENV/bin/pip" install -q "roboticstoolbox-python==$RTB_VERSION" >&2
fi

say "building ikbench (release, core only)"
(cd "$ROOT" && cargo build -q --release -p armlab-bench --bin ikbench)

say "running: RTB and ikbench alternate, a few seconds per round"
"$VENV/bin/python" "$HERE/rtb_ik.py" --ikbench "$CARGO_TARGET_DIR/release/ikbench" "$@"
