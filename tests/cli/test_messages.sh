#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What a user sees when something is wrong: an error in the data, options or declaration is one
# line naming the culprit (no Lua traceback, no stdlib path in front; --traceback adds the
# traceback), an error in the user's own code keeps its traceback (inside a study step too), a
# misspelt option gets a "did you mean"; and what a study prints at its end: the warnings grouped
# with their counts, the results and report files named on the last lines even when piped.
source "$(dirname "$0")/lib.sh"

printf 'mode_1_Hz,mode_2_Hz\n29.6,80.1\n30.1,81.0\n' > tests.csv
cat > data_study.lua <<'LUA'
local study = require "smi.study"
local s = study.new{name = "frame", report = {title = "Frame"}}
s:step("data", function(ctx)
  local d, header = smi.csv.read("tests.csv")
  local want = "mode2_Hz"
  if d[want] == nil then
    local near = smi._closest(want, header)
    smi.fail(("tests.csv: no column '%s' (did you mean %s?); columns: %s"):format(want, near[1], table.concat(header, ", ")))
  end
end)
s:run()
LUA

# a failure: one line, the culprit and the closest column, no traceback, no internal path
run failure 1 "$SMI" data_study.lua
has_err "smi-lua: study 'frame': step 'data' failed: tests.csv: no column 'mode2_Hz' (did you mean mode_2_Hz?)"
lacks_err "stack traceback"
lacks_err "stdlib/smi"
[ "$(wc -l < "$WORK/.err")" = 1 ] && ok || bad "the failure is not one line"

run failure_traceback 1 "$SMI" --traceback data_study.lua
has_err "no column 'mode2_Hz'"
has_err "stack traceback"

# an error in the user's code inside a step: its traceback, pointing at the user's file
cat > code_study.lua <<'LUA'
local study = require "smi.study"
local s = study.new{name = "code"}
local function model(x) return x.missing.field end
s:step("fit", function(ctx) return {y = model({})} end)
s:run()
LUA
run code_error 1 "$SMI" code_study.lua
has_err "attempt to index a nil value (field 'missing')"
has_err "stack traceback"
has_err "code_study.lua:3"

# the stdlib's own error(message, 0) is a failure too: a header typo in the steering column's data
sed '1s/mode2_hz/mode_2_hz/' "$SMI_SOURCE_DIR/scripts/steering_column/data/tests.csv" > typo.csv
run stdlib_error 1 "$SMI" --allow-read . "$SMI_SOURCE_DIR/scripts/steering_column.lua" --data typo.csv --quick
has_err "step 'data' failed: typo.csv: response 'mode2': no column 'mode2_hz'"
lacks_err "stack traceback"
[ "$(wc -l < "$WORK/.err")" = 1 ] && ok || bad "the failure is not one line"

# a bound function called by the stdlib: a failure without the stdlib's file:line in front
cat > refused.lua <<'LUA'
local s = require("smi.study").new{name = "x", out = "/proc/no-such-place"}
s:step("a", function() return {} end)
s:run()  -- smi.study's results file lies outside --out: the host's check, called by the stdlib, refuses it
LUA
run binding_from_stdlib 1 "$SMI" refused.lua
lacks_err "stdlib/"
lacks_err "stack traceback"
has_err "smi-lua: smi.study: the results file '/proc/no-such-place/results.json' does not lie under --out"
has_err "/proc/no-such-place"

# smi.fail inside a function C++ calls back (an objective, a model): still one line, no
# traceback, no binding's name in front; an error in code there keeps its traceback
cat > callback_fail.lua <<'LUA'
smi.calibrate{
  parameters = {{"k", 0, 10, 5}},
  objective = function(t)
    if t.k > -1 then smi.fail(("k.csv line 4: stiffness %g is not in the measured range"):format(t.k)) end
    return (t.k - 3)^2
  end,
}
LUA
run callback_failure 1 "$SMI" callback_fail.lua
has_err "smi-lua: k.csv line 4: stiffness 5 is not in the measured range"
lacks_err "stack traceback"
lacks_err "smi.calibrate:"
[ "$(wc -l < "$WORK/.err")" = 1 ] && ok || bad "the callback's failure is not one line"
sed 's/smi.fail(/error(/' callback_fail.lua > callback_error.lua
run callback_code_error 1 "$SMI" callback_error.lua
has_err "stack traceback"

# a study on an in-process Lua model: its usage line asks for no --allow-exec
cat > lua_model_study.lua <<'LUA'
require("smi.improve").run({name = "frame_decl", data = "tests.csv",
  responses = {{name = "mode_1_Hz"}},
  unknowns = {{name = "k", dist = "normal", mean = {1, 3, 2}, std = {0.1, 0.3, 0.2}}},
  model = function(applied, unknowns, ctx)
    return smi.model.lua{inputs = unknowns, outputs = {"mode_1_Hz"}, fn = function(X) return {mode_1_Hz = X:col(1) * 15} end}
  end}, arg)
LUA
run lua_model_usage 0 "$SMI" lua_model_study.lua --help
has_out "usage: smi-lua lua_model_study.lua [options]"
lacks_out "allow-exec"
# and a solver study's keeps it
run solver_usage 0 "$SMI" "$SMI_SOURCE_DIR/scripts/steering_column.lua" --help
has_out "usage: smi-lua [--allow-exec SOLVER] steering_column.lua [options]"

# smi-lua's own options: a misspelt one gets the closest name
run alow_exec 2 "$SMI" --alow-exec x data_study.lua
has_err "unrecognized option '--alow-exec' (did you mean --allow-exec?)"
run trace_typo 2 "$SMI" --tracebak data_study.lua
has_err "(did you mean --traceback?)"

# a study's --help: the script as it was run, and only the options that apply
cat > opts.lua <<'LUA'
local options = require "smi.options"
local opt = options.parse(arg, {name = "shear_frame_declaration", summary = "a Lua model study",
  usage = "smi-lua {script} [options]",
  {name = "quick", type = "flag", meaning = "the reduced run"},
  {name = "screening-sample", type = "integer", default = 40, applies = false, why_not = "this study screens nothing",
   meaning = "a 40-point screening sample"},
  options.study_steps})
print("quick", opt.quick)
LUA
run study_help 0 "$SMI" opts.lua --help
has_out "opts.lua: a Lua model study"
has_out "usage: smi-lua opts.lua [options]"
lacks_out "shear_frame_declaration"
lacks_out "screening"
run not_applying 2 "$SMI" opts.lua --screening-sample 10
has_err "--screening-sample does not apply to this study: this study screens nothing"
run own_option_typo 2 "$SMI" opts.lua --alow-exec x
has_err "did you mean smi-lua's own --allow-exec?"

# the end of a study: warnings grouped (same warning per trial once, with its count and where),
# and the last lines name results.json and the report, piped or not
cat > warn_study.lua <<'LUA'
local study = require "smi.study"
-- --loud: print as on a terminal (the test's output is piped, which makes a run quiet)
local quiet
if arg[1] == "--loud" then quiet = false end
local s = study.new{name = "w", quiet = quiet, report = {title = "W"}}
s:step("trials", function(ctx)
  for t = 1, 3 do
    ctx.report:section("Trial " .. t)
    ctx.report:callout(("input 'E' lies at its bound %d.5"):format(t), "warn")
    ctx.report:verdict{name = "Mode 1, trial " .. t, pass = t == 3}
  end
  ctx.report:callout("the data hold 3 tests only", "warn")
  ctx.report:supersede("Trial 1", "revised in trial 2")
  ctx.report:supersede("Trial 2", "revised in trial 3")
end)
s:run()
LUA
run study_end 0 "$SMI" warn_study.lua --loud
has_err "[w] 4 warnings (2 distinct):"
has_err "  3x input 'E' lies at its bound 1.5 (and 2 more like it)  [1 Trial 1; 2 Trial 2; 3 Trial 3]"
has_err "  the data hold 3 tests only  [3 Trial 3]"
has_out "PASS    Mode 1, trial 3"
lacks_out "Mode 1, trial 1"
has_out "1 passed, 0 failed, 2 warnings, 0 inconclusive"
[ "$(tail -n 2 "$WORK/.out" | head -n 1)" = "results: smi-out/warn_study/results.json" ] && ok || bad "results is not on the last lines"
[ "$(tail -n 1 "$WORK/.out")" = "report:  smi-out/warn_study/report.html" ] && ok || bad "report is not the last line"
# the report: the warnings section lists each group once with its count; superseded not counted
grep -q '<h2 id="warnings">Warnings</h2>' smi-out/warn_study/report.html && ok || bad "no Warnings section"
grep -q '<span class="count">3&#215;</span>' smi-out/warn_study/report.html && ok || bad "the count of the repeated warning"
grep -q 'Superseded: revised in trial 2' smi-out/warn_study/report.html && ok || bad "superseded note"

# --quiet: no warnings on the terminal, the last lines still there
run study_end_quiet 0 "$SMI" --quiet warn_study.lua
lacks_err "warnings"
[ "$(tail -n 1 "$WORK/.out")" = "report:  smi-out/warn_study/report.html" ] && ok || bad "report is not the last line when quiet"

# the installed tutorial: no solver where the source tree builds it nor on PATH: what it tried, and --solver
run tutorial_solver 1 "$SMI" "$SMI_SOURCE_DIR/scripts/tutorial/bracket_solver.lua"
has_err "smi-lua: no beam solver found; tried:"
has_err "  smi-beam-solver: program 'smi-beam-solver' not found on PATH"
has_err "--solver PATH"
[ "$(grep -c 'no beam solver found' "$WORK/.err")" = 1 ] && ok || bad "the message is printed more than once"

# doc --html renders the guides, escaping everything: no markup of the text reaches the page
mkdir -p guides
printf '# A guide <b>\n\nSee [the sandbox](sandbox.md) and [x](javascript:alert(1)).\n\n<script>alert(1)</script>\n\n| a | b |\n|---|---|\n| `x|y` | **z** |\n' > guides/intro.md
run doc_guides 0 "$SMI" --quiet doc --html html --guides guides
grep -q '<h1 id="a-guide-b">A guide &lt;b&gt;</h1>' html/guides/intro.html && ok || bad "heading escaped"
grep -q '<a href="sandbox.html">the sandbox</a>' html/guides/intro.html && ok || bad "a guide's link to another guide"
grep -q 'javascript' html/guides/intro.html && bad "a javascript: link kept" || ok
grep -q '<script' html/guides/intro.html && bad "markup passed through" || ok
grep -q '&lt;script&gt;alert(1)&lt;/script&gt;' html/guides/intro.html && ok || bad "text escaped"
grep -q '<td><code>x|y</code></td><td><strong>z</strong></td>' html/guides/intro.html && ok || bad "table cells"
grep -q 'href="guides/intro.html"' html/index.html && ok || bad "the index lists the guide"

# --help lists every command
run help 0 "$SMI" --help
has_out "  doc [NAME]"
has_out "  report --pdf HTML"
has_out "  --traceback"

finish
