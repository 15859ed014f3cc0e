#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Options in any order: smi-lua's own options go before the script. After it, one the
# study did not declare is refused with the command line that works; one the study declares
# (--dry-run, --quiet) is the study's. smi.options' list of smi-lua's options matches --help.
source "$(dirname "$0")/lib.sh"

cat > study.lua <<'LUA'
local options = require "smi.options"
local opt = options.parse(arg, { name = "study",
  { name = "data", type = "path", default = "x.csv", meaning = "measurements" },
  { name = "dry-run", type = "flag", meaning = "the study's own cost plan" },
  options.study_steps })
print("data=" .. opt.data, "dry_run=" .. tostring(opt.dry_run), "quiet=" .. tostring(opt.quiet))
LUA

run "--out after the script" 2 "$SMI" study.lua --out somewhere
has_err "smi-lua's own option --out goes before the script: smi-lua --out DIR study.lua ..."
run "--seed=5 after the script" 2 "$SMI" study.lua --data y.csv --seed=5
has_err "smi-lua's own option --seed goes before the script: smi-lua --seed N study.lua ..."
run "--timeout after the script" 2 "$SMI" study.lua --timeout 10
has_err "smi-lua's own option --timeout goes before the script"
run "--out before the script" 0 "$SMI" --out o study.lua --data y.csv
has_out "data=y.csv"
run "a study's own --dry-run after the script is the study's" 0 "$SMI" study.lua --dry-run --quiet
has_out "dry_run=true"
has_out "quiet=true"

# --help of the host and of a study say the same thing
run "host help" 0 "$SMI" --help
has_out "The options below go before the script"
run "study help" 0 "$SMI" study.lua --help
has_out "go before the script: smi-lua --out DIR study.lua [options]"

# smi.options' list of smi-lua's own options is exactly the long options --help documents
"$SMI" --help | grep -oE '^  --[a-z][a-z-]+' | sed 's/^  --//' | grep -vE '^(help|version)$' | sort -u > help.txt
"$SMI" -e 'local t = {} for k in pairs(require("smi.options").host_options) do t[#t + 1] = k end
  table.sort(t) print(table.concat(t, "\n"))' > lua.txt
current="host option list"
if diff help.txt lua.txt > diff.txt; then ok; else bad "smi.options.host_options differs from --help: $(cat diff.txt)"; fi
finish
