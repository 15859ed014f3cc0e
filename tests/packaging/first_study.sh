#!/bin/bash
# SPDX-License-Identifier: MIT
# Prints the README's first study: the first ```lua block after the heading "## A first study";
# with --output, the output the README shows for it (the next ``` block of that section).
# Used by test_install.sh and packaging/test-deb-chroot.sh, so both run what the README shows.
#   first_study.sh README.md [--output] > first.lua
block=1
[ "${2:-}" = --output ] && block=2
awk -v want="$block" '
  /^## / { sec = /^## A first study/ }
  sec && /^```/ && !on { n++; on = 1; next }
  on && /^```/ { on = 0; if (n == want) exit; next }
  on && n == want { print }
' "$1"
