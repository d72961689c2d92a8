# Sourced by tools/test.sh (after tools/setup.sh, for `say` and `stop_background`): the
# test command as named steps, and the totals of the test suites among them. Whatever ends
# the run early — a step's command, a check, an install awaited, a build — ends it through
# the EXIT trap set here, which names the step that was running and prints the totals line
# `N passed, M failed`. Under `set -e` a failing command would otherwise end the script
# without a word about what failed. The caller sets LOG, a folder for the steps' logs.

STEP="start"  # the step running now
STEP_LOG=""   # its log, while its counts are not yet in the totals
passed=0
failed=0
SUITES=""
TIMES=""      # each finished step's wall and CPU time, printed when the run ends
STEP_START=$SECONDS
STEP_CPU=0    # the CPU time of this shell's finished children when the step began (s)

# One awk, which prints "0 0" for a log without counts (a lint's, a build's): a grep that
# matches nothing fails, and in a pipeline under pipefail and errexit that ended the script
# before it said which step had failed.
count() { # "P F": the sums of cargo's "test result: ... P passed; F failed" and node's "# pass P" / "# fail F"
  awk '
    match($0, /test result: [a-zA-Z]+\. [0-9]+ passed; [0-9]+ failed/) {
      split(substr($0, RSTART, RLENGTH), w, " "); p += w[4]; f += w[6]
    }
    /^# pass [0-9]+/ { p += $3 }
    /^# fail [0-9]+/ { f += $3 }
    END { print p + 0, f + 0 }' "$1"
}

not_run() { # ignored + filtered out (cargo), skipped + todo (node): tests that exist but did not run
  { grep -Eo '[0-9]+ ignored;( [0-9]+ measured;)? [0-9]+ filtered out|^# (skipped|todo) [0-9]+' "$1" || true; } \
    | { grep -Eo '[0-9]+ ignored|[0-9]+ filtered|(skipped|todo) [0-9]+' || true; } \
    | awk '{ for (i = 1; i <= NF; i++) if ($i ~ /^[0-9]+$/) s += $i } END {print s+0}'
}

at() { # at NAME: what runs from here on is the step NAME, without a heading
  step_time
  STEP="$1"
  STEP_LOG=""
}

step() { # step NAME: what runs from here on is the step NAME, under a heading
  at "$1"
  say "$1"
}

run() { # run NAME CMD...: the step NAME runs CMD, its output kept in $LOG/NAME.log
  step "$1"
  shift
  STEP_LOG="$LOG/$STEP.log"
  "$@" 2>&1 | tee "$STEP_LOG"
}

add() { # add NAME: the counts of the step NAME's log go into the totals; a suite that ran no test fails
  local p f skipped
  read -r p f < <(count "$LOG/$1.log")
  skipped=$(not_run "$LOG/$1.log")
  [ "$p" -gt 0 ] || fail "the suite $1 ran no test"
  passed=$((passed + p))
  failed=$((failed + f))
  [ "$STEP_LOG" != "$LOG/$1.log" ] || STEP_LOG=""
  SUITES="$SUITES
  $1: $p passed, $f failed, $skipped ignored, skipped or filtered out"
}

step_time() { # the step running now ends: its wall time (and its processes' CPU time) goes into TIMES
  local cpu
  # `times` gives the shell's and then its finished children's user and system time; in
  # this shell, not in a pipeline's or a substitution's subshell, whose children these are not.
  times > "$LOG/times"
  cpu=$(awk 'NR == 2 { gsub(/[ms]/, " "); print int(($1 * 60 + $2 + $3 * 60 + $4) + 0.5) }' "$LOG/times")
  [ "$STEP" = start ] || TIMES="$TIMES
  $STEP: $((SECONDS - STEP_START)) s (CPU $((cpu - STEP_CPU)) s)"
  STEP_START=$SECONDS
  STEP_CPU=$cpu
}

print_times() { # the wall time of every step so far, the one running now last
  step_time
  printf '\nwall time per step:%s\n' "$TIMES"
}

fail() { # fail MESSAGE: ends the run here, as a failure of the step running now
  echo "FAILED: $*"
  exit 1
}

# The EXIT trap. On a failure the totals take in the failed step's own counts (a test
# suite's passes and failures, from its log) and the step as one failure when its log has
# none (a build, a lint, a check), so that M is never 0 on a failed run.
end_steps() {
  local status=$? p=0 f=0
  set +e
  stop_background
  if [ "$status" -ne 0 ]; then
    print_times
    if [ -n "$STEP_LOG" ] && [ -f "$STEP_LOG" ]; then read -r p f < <(count "$STEP_LOG"); fi
    [ "$f" -gt 0 ] || f=1
    echo
    echo "FAILED at the step: $STEP (exit status $status)"
    echo "$((passed + p)) passed, $((failed + f)) failed"
  fi
  exit "$status"
}
trap end_steps EXIT
