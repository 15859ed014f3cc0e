#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A whole run of a study reuses the saved steps whose inputs are unchanged, and never a stale one:
# every kind of input is changed in turn (a data value, a study option, the script, a module it
# requires, a module a step requires, a library file, the seed, the smi-lua binary) and the steps
# that ran are checked (each appends its name to ran.log), with the numbers the study prints.
# The study: data (reads in/data.csv) -> fit (requires lazy.lua, scales by --scale) -> summary
# (requires the library module reflib). Expected: a change reruns the first step that read it and
# every later step, and nothing before it; --force reruns all.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / finish; cd's to a temp dir

mkdir -p study/in lib
printf 'x\n1\n2\n3\n' > study/in/data.csv
cat > study/helper.lua <<'LUA'
return { offset = 0 }
LUA
cat > study/lazy.lua <<'LUA'
return { factor = 1 }
LUA
cat > lib/reflib.lua <<'LUA'
return { label = "total" }
LUA
cat > study/reuse.lua <<'LUA'
local study = require "smi.study"
local options = require "smi.options"
local helper = require "helper"
local opt = options.parse(arg, { { name = "scale", type = "number", default = 1, meaning = "a factor" }, options.study_steps })
local function ran(name)
  local f = assert(io.open(smi.out("ran.log"), "a"))
  f:write(name, "\n")
  f:close()
end
local s = study.new{ name = "reuse", quiet = false, report = { title = "Reuse" } } -- progress lines say why a step runs
s:step("data", function(ctx)
  ran("data")
  local d = smi.csv.read("in/data.csv")
  ctx.report:section("Data"):text(("Sum of the data: %g"):format(d.x:sum()))
  return { sum = d.x:sum() + helper.offset, draw = smi.rng(smi.seed):uniform(1)[1] }
end)
s:step("fit", function(ctx)
  ran("fit")
  local lazy = require "lazy"
  return { fitted = ctx.results.data.sum * lazy.factor * opt.scale }
end)
s:step("summary", function(ctx)
  ran("summary")
  local lib = require "reflib"
  ctx.report:section("Summary"):text(("%s = %g"):format(lib.label, ctx.results.fit.fitted))
  ctx.report:table{ caption = "Fit.", columns = { "Quantity", { title = "Value", digits = 3 } }, rows = { { "fitted", ctx.results.fit.fitted } } }
  return { line = ("%s = %g, draw %.6f"):format(lib.label, ctx.results.fit.fitted, ctx.results.data.draw) }
end)
print(s:run(opt).summary.line)
LUA

# go SMI_BINARY [smi-lua options] -- [study args]: one run in ./study, ran.log emptied first
go() {
  local bin=$1; shift
  rm -f study/out/ran.log
  (cd study && "$bin" --out out --lib ../lib "$@") > .out 2> .err < /dev/null
  echo "exit $?" >> .out
}
# ran_is "STEPS": the steps that ran, in order, space-separated ("" for none)
ran_is() {
  local got
  got=""
  [ -f study/out/ran.log ] && got=$(tr '\n' ' ' < study/out/ran.log | sed 's/ $//')
  if [ "$got" = "$1" ]; then ok; else bad "steps run: '$got', expected '$1'"; fi
}

current="first run"; go "$SMI" reuse.lua; ran_is "data fit summary"; has_out "total = 6, draw"; has_out "exit 0"
first=$(head -1 .out)
current="unchanged rerun"; go "$SMI" reuse.lua; ran_is ""; has_out "$first"; has_err "3 of 3 step(s) reused"
# the report is the same page: the reused steps' sections are replayed
current="report replayed"; if grep -q "Sum of the data: 6" study/out/report.html && grep -q "total = 6" study/out/report.html \
  && grep -q "Fit\." study/out/report.html; then ok; else bad "report lacks the reused sections"; fi

current="a data value"; printf 'x\n1\n2\n4\n' > study/in/data.csv; go "$SMI" reuse.lua; ran_is "data fit summary"; has_out "total = 7,"
has_err "step 'data' runs again: it read file"
current="then unchanged"; go "$SMI" reuse.lua; ran_is ""; has_out "total = 7,"

current="a study option"; go "$SMI" reuse.lua --scale 2; ran_is "data fit summary"; has_out "total = 14,"
has_err "the options changed"
current="the same option again"; go "$SMI" reuse.lua --scale 2; ran_is ""; has_out "total = 14,"
current="--force"; go "$SMI" reuse.lua --scale 2 --force; ran_is "data fit summary"; has_out "total = 14,"
current="after --force"; go "$SMI" reuse.lua --scale 2; ran_is ""

current="the script"; echo "-- an edit" >> study/reuse.lua; go "$SMI" reuse.lua --scale 2; ran_is "data fit summary"
has_err "its code changed"
current="a module the script requires"; echo 'return { offset = 10 }' > study/helper.lua; go "$SMI" reuse.lua --scale 2
ran_is "data fit summary"; has_out "total = 34,"
current="a module a step requires"; echo 'return { factor = 3 }' > study/lazy.lua; go "$SMI" reuse.lua --scale 2
ran_is "fit summary"; has_out "total = 102,"
current="a library file"; echo 'return { label = "sum" }' > lib/reflib.lua; go "$SMI" reuse.lua --scale 2
ran_is "summary"; has_out "sum = 102,"
current="unchanged after all"; go "$SMI" reuse.lua --scale 2; ran_is ""; has_out "sum = 102,"
draw=$(sed -n 's/.*draw //p' .out | head -1)

current="the seed"; go "$SMI" --seed 7 reuse.lua --scale 2; ran_is "data fit summary"
if [ "$(sed -n 's/.*draw //p' .out | head -1)" != "$draw" ]; then ok; else bad "the draw did not change with the seed"; fi
go "$SMI" reuse.lua --scale 2; ran_is "data fit summary"   # back to the default seed

current="the smi-lua binary"; cp "$SMI" ./smi-copy; printf 'rebuilt' >> ./smi-copy
go "$PWD/smi-copy" reuse.lua --scale 2; ran_is "data fit summary"; has_err "smi-lua changed"
current="the same binary again"; go "$PWD/smi-copy" reuse.lua --scale 2; ran_is ""

# a partial run runs what it names; the whole run after it reuses it
current="--only then whole"; go "$SMI" reuse.lua --scale 2 --only summary; ran_is "summary"
go "$SMI" reuse.lua --scale 2; ran_is "data fit summary"   # the binary changed back since the last whole run
go "$SMI" reuse.lua --scale 2; ran_is ""

finish
