#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Variables a model declares for its solver (smi.model.command{env = {NAME = "value"}}): a model
# sets only names the command line allows (--allow-env NAME); they reach the solver with the
# model's values, they are part of the store key (another value runs again, the same value
# reuses), and the ones that would make the solver load or run other code (the loader's LD_*,
# shells' and interpreters' start-up hooks and families, folders of start-up files, PATH) are
# refused by name when the model is declared even when allowed. smi-lua's own environment still
# reaches a solver only through --allow-env.
source "$(dirname "$0")/lib.sh"

# the solver prints the variable (0 when unset) and counts its runs in a file of the test's
printf '#!/bin/sh\necho run >> %s/runs.count\necho "y = ${SMI_TEST_THREADS:-0}"\n' "$WORK" > solver
chmod +x solver
mkdir study
cat > study/run.lua <<'LUA'
local env = load("return " .. arg[1])()
local m = smi.model.command{
  name = arg[3] or "declared", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
  command = {arg[2]}, env = env,
  parse = function(dir, h) return {y = tonumber(h.read("stdout.log"):match("y = (%S+)"))} end,
}
local r = m:evaluate(smi.mat{{1}})
print("y", r.y[1])
LUA
S=("$SMI" --quiet --allow-exec "$WORK/solver" --allow-env SMI_TEST_THREADS)

# --- a declared variable reaches the solver with the model's value
run "declared value reaches the solver" 0 "${S[@]}" --out o1 study/run.lua '{SMI_TEST_THREADS = 3}' "$WORK/solver"
has_out "y	3"
# --- the user decides: a name the command line does not allow is refused, naming the flag
run "a name not allowed" 1 "$SMI" --quiet --allow-exec "$WORK/solver" --out o2 study/run.lua '{SMI_TEST_THREADS = 3}' "$WORK/solver"
has_err "env.SMI_TEST_THREADS is set by the model, but the command line does not allow it"
has_err "--allow-env SMI_TEST_THREADS"
run "another name allowed is not this one" 1 "$SMI" --quiet --allow-exec "$WORK/solver" --allow-env OMP_NUM_THREADS \
  --out o2 study/run.lua '{SMI_TEST_THREADS = 3}' "$WORK/solver"
has_err "does not allow it"
# --- without it, nothing (smi-lua's own variable does not leak through)
export SMI_TEST_THREADS=9
run "smi-lua's variable not declared, not allowed" 0 "$SMI" --quiet --allow-exec "$WORK/solver" --out o2 study/run.lua '{}' "$WORK/solver"
has_out "y	0"
# --- the declared value wins over an allowed one of the same name
run "declared over --allow-env" 0 "$SMI" --quiet --allow-exec "$WORK/solver" --allow-env SMI_TEST_THREADS --out o3 \
  study/run.lua '{SMI_TEST_THREADS = 4}' "$WORK/solver"
has_out "y	4"
unset SMI_TEST_THREADS

# --- the store key: the same value reuses, another value runs again
runs() { wc -l < "$WORK/runs.count"; }
run "first run" 0 "${S[@]}" --out o4 study/run.lua '{SMI_TEST_THREADS = 5}' "$WORK/solver" keyed
has_out "y	5"
n1=$(runs)
run "same value: reused" 0 "${S[@]}" --out o4 study/run.lua '{SMI_TEST_THREADS = 5}' "$WORK/solver" keyed
has_out "y	5"
if [ "$(runs)" = "$n1" ]; then ok; else bad "the same declared value ran the solver again"; fi
run "other value: run again" 0 "${S[@]}" --out o4 study/run.lua '{SMI_TEST_THREADS = 6}' "$WORK/solver" keyed
has_out "y	6"
if [ "$(runs)" = "$((n1 + 1))" ]; then ok; else bad "another declared value reused the stored run"; fi

# --- refused names: the loader, shells, interpreters, PATH, smi-lua's mark, malformed names
for name in LD_PRELOAD LD_LIBRARY_PATH LD_AUDIT BASH_ENV ENV PATH PYTHONPATH PYTHONSTARTUP PERL5OPT NODE_OPTIONS \
            GCONV_PATH GLIBC_TUNABLES LUA_INIT BASH_FUNC_x%% SMI_LUA_SOLVER_OF; do
  run "env.$name refused" 1 "${S[@]}" --out o5 study/run.lua "{[\"$name\"] = \"/tmp/x\"}" "$WORK/solver"
  has_err "env.$name cannot be set by a model"
done
# --- allowed on the command line, still refused: the names a solver's interpreter reads as code
# or as where to find code (the deny-list stays as a second guard behind the allow-list)
for name in JDK_JAVA_OPTIONS JAVA_TOOL_OPTIONS PYTHONWARNINGS PYTHONUSERBASE BROWSER TCL_LIBRARY TK_LIBRARY HOME \
            XDG_CONFIG_HOME TMPDIR R_PROFILE_USER GIT_SSH PERL5OPT RUBYOPT NODE_OPTIONS OMP_TOOL_LIBRARIES SHELL; do
  run "env.$name refused even when allowed" 1 "${S[@]}" --allow-env "$name" --out o5 study/run.lua "{[\"$name\"] = \"/tmp/x\"}" "$WORK/solver"
  has_err "env.$name cannot be set by a model"
done
run "a name with '=' refused" 1 "${S[@]}" --out o5 study/run.lua '{["A=B"] = "1"}' "$WORK/solver"
has_err "cannot be set by a model"
run "a table value refused" 1 "${S[@]}" --out o5 study/run.lua '{A = {}}' "$WORK/solver"
has_err "env.A must be a string or a number"
run "env not a table" 1 "${S[@]}" --out o5 study/run.lua '"OMP=1"' "$WORK/solver"
has_err "option 'env' must be a table"
# nothing ran for a refused model
if ls o5/runs 2>/dev/null | grep -q .; then current="refused: no run"; bad "a refused model ran"; else ok; fi

finish
