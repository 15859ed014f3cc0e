#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# `smi-lua verify` reads only regular files, at most the size they had when opened, and within a
# time limit: a results file is data from whoever made it, and one that names /dev/zero, a FIFO
# or a folder as an input must get an answer (a difference, exit 1), never a read that lasts for
# ever. The results file itself is held to the same rule (exit 2).
source "$(dirname "$0")/lib.sh"

# A results file recording one input `path` with a digest no file has.
results_naming() {
  printf '{"schema": 2, "provenance": {"seed": 1, "libraries": [], "files": {"%s": {"kind": "data", "hash": "sha256:%064d", "size": 1}}}}\n' "$1" 0 > "$2"
}

ln -s /dev/zero zero-link
mkfifo fifo
mkdir folder
truncate -s 900M sparse.bin   # under the 1 GB cap: hashed, 900 MB of zeros, no disk used

for input in /dev/zero "$WORK/zero-link" "$WORK/fifo" "$WORK/folder" /dev/stdin; do
  results_naming "$input" r.json
  run "verify-names-$input" 1 timeout 20 "$SMI" verify r.json
  has_out "MISSING  file (data) $input"
  has_out "only regular files are digested"
done
results_naming "$WORK/fifo" r.json
run verify-fifo-kind 1 timeout 20 "$SMI" verify r.json
has_out "it is a FIFO"
results_naming /dev/zero r.json
run verify-device-kind 1 timeout 20 "$SMI" verify r.json
has_out "it is a character device"
results_naming "$WORK/folder" r.json
run verify-folder-kind 1 timeout 20 "$SMI" verify r.json
has_out "it is a folder"

# The results file itself: a device, a FIFO, a folder, a link to a device, over the size cap.
for bad in /dev/zero "$WORK/zero-link" "$WORK/fifo" "$WORK/folder"; do
  run "verify-results-$bad" 2 timeout 20 "$SMI" verify "$bad"
  has_err "is not a regular file"
done
truncate -s 300M huge.json
run verify-results-huge 2 timeout 20 "$SMI" verify huge.json
has_err "more than a results file holds"

# The time limit: hashing 900 MB takes longer than 0.2 s; verify ends with status 2, naming
# the file, instead of running on (and a limit long enough lets it finish with a difference).
results_naming "$WORK/sparse.bin" r.json
start=$(date +%s)
run verify-time-limit 2 timeout 20 "$SMI" --timeout 0.2 verify r.json
has_err "the time limit of 0.2 s was reached while checking '$WORK/sparse.bin'"
has_err "nothing is verified"
if [ $(( $(date +%s) - start )) -le 5 ]; then ok; else bad "verify took more than 5 s under --timeout 0.2"; fi
run verify-sparse-done 1 timeout 60 "$SMI" --timeout 50 verify r.json
has_out "CHANGED  file (data) $WORK/sparse.bin"
rm -f sparse.bin huge.json

finish
