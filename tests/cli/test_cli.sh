#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The smi-lua command line: options as lua's, exit statuses, messages, arg, stdin, -i.
source "$(dirname "$0")/lib.sh"

# --help lists every option, exits 0
run help 0 "$SMI" --help
for o in " -e chunk" " -l mod" " -i " " -v " " -W " " -E " " -- " " - " --allow-read --allow-write --allow-exec \
         --lib --stdlib-dir --out --seed --quiet --max-memory --timeout --store --dry-run --help; do
  has_out "$o"
done
run version 0 "$SMI" -v
has_out "smi-lua 0.1.0 (Lua 5.4"

# usage errors: status 2, message and the usage line on stderr
for args in "--bogus" "-x" "-e" "-l" "--seed abc" "--seed -1" "--timeout 0" "--timeout x" "--max-memory 0" \
            "--lib" "--out"; do
  # shellcheck disable=SC2086
  run "usage $args" 2 "$SMI" $args
  has_err "usage: smi-lua [options] [script [args]]"
done
run "usage names the option" 2 "$SMI" --seed abc
has_err "--seed needs a non-negative integer, got 'abc'"

# a script error: status 1, file:line and a traceback on stderr
printf 'local x = 1\nerror("boom")\n' > err.lua
run "script error" 1 "$SMI" err.lua
has_err "smi-lua: err.lua:2: boom"
has_err "stack traceback:"
has_err "err.lua:2: in main chunk"
printf 'local x = \n' > syntax.lua
run "syntax error" 1 "$SMI" syntax.lua
has_err "syntax.lua:2: unexpected symbol near <eof>"
run "missing script" 1 "$SMI" nosuch.lua
has_err "cannot open nosuch.lua"
run "-e error" 1 "$SMI" -e "local t = nil; print(t.x)"
has_err "(command line):1: attempt to index a nil value (local 't')"

# arg and ...: script at 0, arguments at 1..n, interpreter and options below 0
printf 'print(arg[0], arg[1], arg[2], #arg, arg[-1], arg[-2], select("#", ...), ...)\n' > args.lua
run "arg table" 0 "$SMI" --seed 5 args.lua a "b c"
out_is "$(printf 'args.lua\ta\tb c\t2\t5\t--seed\t2\ta\tb c')"
printf 'print(arg[0], ...)' > -dash.lua
run "-- ends the options" 0 "$SMI" -- -dash.lua x
out_is "$(printf -- '-dash.lua\tx')"

# -e and -l run in order before the script; -l g=mod names the global
mkdir -p lib && printf 'return {name = "greeter", hello = function(w) return "hello " .. w end}\n' > lib/greeter.lua
run "-e -l order" 0 "$SMI" --lib lib -e "x = 1" -l greeter -l g=greeter -e "print(x, greeter.hello('a'), g.name)" args.lua
has_out "$(printf '1\thello a\tgreeter')"
has_out "args.lua"

# stdin: "-" as the script, or piped with no script at all
run_in "stdin -" 0 'print("from stdin", ...)' "$SMI" - p q
out_is "$(printf 'from stdin\tp\tq')"
run_in "piped stdin" 0 'print(6 * 7)' "$SMI"
out_is "42"

# -i with piped stdin: the REPL without readline or prompts
run_in "repl piped" 0 $'x = 20\nx + 1\nfunction f(a)\n  return a * 2\nend\nf(21)\n{1, "s", k = {1}}\nerror("oops")\n"after the error"\n' "$SMI" -i
out_is "$(printf '21\n42\n{1, "s", k = {1}}\nafter the error')"
has_err "stdin:1: oops"
run_in "repl vec summary" 0 $'smi.vec.linspace(0, 1, 1000000)\n' "$SMI" -i
has_out "vec(1000000)"
if [ "$(wc -c < .out)" -lt 300 ]; then ok; else bad "a million-element vec prints more than 300 characters"; fi
run_in "repl after script" 0 $'y\n' "$SMI" -e "y = 'set by -e'" -i
out_is "set by -e"
run_in "repl unfinished chunk" 0 $'for i = 1,\n' "$SMI" -i
has_err "stdin:1: unexpected symbol near <eof>"

# os.exit: the code, uncatchable, and the state is closed (finalizers run) before exiting
run "os.exit(3)" 3 "$SMI" -e "os.exit(3)"
run "os.exit in pcall" 4 "$SMI" -e "pcall(os.exit, 4); print('not reached')"
lacks_out "not reached"
run "os.exit(true)" 0 "$SMI" -e "os.exit(true)"
run "os.exit(false)" 1 "$SMI" -e "os.exit(false)"
run "os.exit closes the state" 5 "$SMI" -e "x = setmetatable({}, {__gc = function() print('finalized') end}); os.exit(5)"
out_is "finalized"
run "os.exit stops -e chain" 0 "$SMI" -e "os.exit(0)" -e "print('not reached')"
lacks_out "not reached"

# --seed: smi.seed and math.random
run "seed default" 0 "$SMI" -e "print(smi.seed)"
out_is "20200214"
run "seed 7 a" 0 "$SMI" --seed 7 -e "print(smi.seed, math.random(1, 1000000), smi.rng(smi.seed):uniform(1)[1])"
cp .out seed7
run "seed 7 b" 0 "$SMI" --seed=7 -e "print(smi.seed, math.random(1, 1000000), smi.rng(smi.seed):uniform(1)[1])"
if cmp -s .out seed7; then ok; else bad "same seed, different numbers"; fi
run "seed 8" 0 "$SMI" --seed 8 -e "print(smi.seed, math.random(1, 1000000))"
if cmp -s .out seed7; then bad "different seeds, same numbers"; else ok; fi

# --quiet is automatic when stdout is not a terminal
run "quiet auto" 0 "$SMI" -e "print(smi.quiet)"
out_is "true"

# --store and --dry-run are accepted (the evaluation area reads them from the policy)
run "store dry-run" 0 "$SMI" --store runs.sqlite --dry-run -e ""
run "warnings" 0 "$SMI" -W -e "warn('careful')"
has_err "warning: careful"

finish
