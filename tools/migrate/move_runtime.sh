#!/usr/bin/env bash
# Moves the Runtime (the one place that assembles vm, sandbox and the bindings into a run) and
# the doc installer (which reads the bindings' texts) out of host/vm into host/app, so vm no
# longer includes bindings. Idempotent: a file already moved is skipped. If both paths exist
# (a merge re-created the old path), it stops and names the pair to resolve by hand.
set -euo pipefail
cd "$(git -C "$(dirname "$0")" rev-parse --show-toplevel)"
mkdir -p host/app
for f in runtime.hpp runtime.cpp docs.hpp docs.cpp; do
  old=host/vm/$f new=host/app/$f
  if [[ -e $old && ! -e $new ]]; then
    git mv "$old" "$new"
    echo "moved $old -> $new"
  elif [[ -e $old && -e $new ]]; then
    echo "both $old and $new exist: merge the edits of $old into $new by hand, then git rm $old" >&2
    exit 1
  fi
done
