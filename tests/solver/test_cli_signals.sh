#!/bin/sh
# SPDX-License-Identifier: MIT
# SIGTERM and SIGHUP (what `timeout`, Slurm and systemd send; a closed terminal) stop a study
# like Ctrl-C: exit status 128 + signal, a message naming what was kept and how to resume, every
# solver process group killed, and a solver's setsid escape (reparented to smi-lua, the child
# subreaper) killed too. Finished runs are kept: the rerun reuses them. kill -9 of smi-lua takes
# its running solver with it (PR_SET_PDEATHSIG).
# usage: test_cli_signals.sh SMI_LUA SOLVER WORKDIR
set -eu
SMI=$1 SOLVER=$2 W=$3
STUDY=$(dirname "$0")/studies/resume_study.lua
rm -rf "$W"; mkdir -p "$W"
fail() { echo "FAIL: $*" >&2; exit 1; }
lines() { if [ -f "$1" ]; then wc -l < "$1" | tr -d ' '; else echo 0; fi; }
alive() { [ -r /proc/$1/stat ] && [ "$(cut -d')' -f2 /proc/$1/stat | cut -d' ' -f2)" != Z ]; }
wait_lines() {  # FILE N: until FILE has N lines (10 s guard against a hang)
  i=0
  while [ "$(lines "$1")" -lt "$2" ]; do
    i=$((i + 1)); [ $i -lt 500 ] || fail "$1 never reached $2 lines"
    sleep 0.02
  done
}
wait_exit() {  # PID WHAT: sets st to its exit status (5 s guard; a zombie counts as exited)
  i=0
  while alive "$1"; do
    i=$((i + 1)); [ $i -lt 100 ] || { kill -9 "$1"; fail "smi-lua did not stop ($2)"; }
    sleep 0.05
  done
  st=0; wait "$1" || st=$?
}
none_alive() {  # LOG WHAT: every pid logged (solvers and escapes) is gone
  sleep 0.2
  for pid in $(cut -d' ' -f1 "$1"); do alive "$pid" && { kill -9 "$pid"; fail "process $pid still runs ($2)"; }; done
  true
}

for SIG in TERM HUP; do
  # A hanging solver whose child escapes with setsid.
  LOG=$W/$SIG.log OUT=$W/$SIG.out
  (exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/$SIG" "$STUDY" "$SOLVER" "$LOG" 0 hang_setsid > "$OUT" 2>&1) &
  PID=$!
  wait_lines "$LOG" 2  # the solver and its escape
  kill -$SIG $PID
  wait_exit $PID "SIG$SIG"
  case $SIG in TERM) want=143 ;; HUP) want=129 ;; esac
  [ "$st" = "$want" ] || fail "exit status $st after SIG$SIG, expected $want: $(cat "$OUT")"
  grep -q "interrupted by SIG$SIG" "$OUT" || fail "no 'interrupted by SIG$SIG' in: $(cat "$OUT")"
  grep -q "stopped by SIG$SIG" "$OUT" && grep -q "run the same command again" "$OUT" || fail "no resume advice in: $(cat "$OUT")"
  none_alive "$LOG" "SIG$SIG"
  echo "ok: SIG$SIG: exit $st, solver group and setsid escape killed"
done

# Finished runs survive SIGTERM: runs of 0.4 s, stop after the third launch, rerun reuses >= 2.
LOG=$W/keep.log OUT=$W/keep.out
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/keep" "$STUDY" "$SOLVER" "$LOG" 0.4 > "$OUT" 2>&1) &
PID=$!
wait_lines "$LOG" 3
kill -TERM $PID
wait_exit $PID "SIGTERM keep"
[ "$st" = 143 ] || fail "exit status $st, expected 143: $(cat "$OUT")"
none_alive "$LOG" "SIGTERM keep"
"$SMI" --quiet --allow-exec "$SOLVER" --out "$W/keep" "$STUDY" "$SOLVER" "$LOG" 0.4 > "$OUT" 2>&1 || fail "rerun: $(cat "$OUT")"
reused=$(sed -n 's/.*reused=\([0-9]*\).*/\1/p' "$OUT")
[ "${reused:-0}" -ge 2 ] || fail "the rerun reused ${reused:-0} runs, expected >= 2: $(cat "$OUT")"
echo "ok: SIGTERM kept finished runs (rerun reused $reused)"

# kill -9 of smi-lua: its solver dies with it.
LOG=$W/k9.log OUT=$W/k9.out
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/k9" "$STUDY" "$SOLVER" "$LOG" 30 > "$OUT" 2>&1) &
PID=$!
wait_lines "$LOG" 1
kill -9 $PID
wait $PID 2>/dev/null || true
none_alive "$LOG" "kill -9 of smi-lua"
echo "ok: kill -9 of smi-lua: its solver died with it"
