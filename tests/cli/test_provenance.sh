# SPDX-License-Identifier: MIT
# Provenance end to end, on a small study of three steps with a helper module next to
# it, a data file, a prior file read with dofile and a "solver" program (a copy of a shell script):
#   - results.json has "schema" and records every file read, the program, the options, the build;
#   - `smi-lua verify` names an edited module, data file or solver (with both hashes), exits 1,
#     exits 0 when everything matches, 2 on a file that is not results.json or from a newer schema;
#   - --only after --data changed refuses to use the saved data step (names what changed and the
#     command to run); --only that recomputes a step marks later steps stale and no conclusion is
#     printed from them;
#   - --version prints the build line; the report's last section is the provenance.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / has_out / has_err / finish; cd's to a temp dir

mkdir -p study
cat > study/helpers.lua <<'LUA'
local M = {}
function M.mean(xs) local s = 0 for _, x in ipairs(xs) do s = s + x end return s / #xs end
return M
LUA
cat > study/solver.sh <<'SH'
#!/bin/sh
# reads "x = <number>" from the deck, writes "y = 2x"
if [ "$1" = "--version" ]; then echo "twice 1.0 (test solver)"; exit 0; fi
awk -F' = ' '/^x/ { print "y = " 2 * $2 }' "$1" > out.txt
SH
chmod +x study/solver.sh
cp study/solver.sh study/solver-copy.sh
printf 'x\n1\n2\n3\n' > study/a.csv
printf 'x\n10\n20\n30\n' > study/b.csv
printf 'return { scale = 1 }\n' > study/prior.lua
cat > study/study.lua <<'LUA'
local study = require "smi.study"
local helpers = require "helpers"
local o = study.parse_args(arg)
local data = smi.script_dir .. "/a.csv"
for i = 1, #o.rest do if o.rest[i] == "--data" then data = o.rest[i + 1] end end
local s = study.new{name = "prov", out = smi.out_dir, report = {title = "Provenance test"}}
s:step("data", function(ctx)
  local xs = {}
  for line in io.lines(data) do if tonumber(line) then xs[#xs + 1] = tonumber(line) end end
  local prior = dofile(smi.script_dir .. "/prior.lua")
  return {mean = helpers.mean(xs) * prior.scale}
end)
s:step("solve", function(ctx)
  local m = smi.model.command{name = "twice", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
    command = {smi.script_dir .. "/solver-copy.sh", "{deck}"}, version_args = {"--version"},
    parse = function(dir, h) return {y = h.regex("out.txt", "y = (\\S+)")} end}
  local Y = m:evaluate{{ctx.results.data.mean}}
  return {y = Y.y[1]}
end)
s:step("verdict", function(ctx)
  local v = ctx.results.solve.y > 10 and "large" or "small"
  ctx.report:verdict{name = "size", status = "pass", detail = v}
  return {verdict = v}
end)
local r = s:run(o)
print("CONCLUSION " .. r.verdict.verdict)
LUA
RUN=("$SMI" --quiet --seed 11 --allow-exec study/solver-copy.sh --out out)
results=out/results.json

# --- --version ------------------------------------------------------------------------------
run version 0 "$SMI" --version
has_out "smi-lua "
has_out "Eigen "
has_out "NLopt "
has_out "SQLite "
has_out "RE2 "
run version-v 0 "$SMI" -v -e 'print("v ok")'   # -v stays as it was: the banner, then the run
has_out "v ok"

# --- the run records everything it depends on -------------------------------------------------
run study 0 "${RUN[@]}" study/study.lua --data study/a.csv
has_out "CONCLUSION small"
for want in '"schema": 2' 'helpers.lua"' 'a.csv"' 'prior.lua"' 'solver-copy.sh"' '"eigen"' '"nlopt"' \
            '"sqlite"' '"re2"' '"compiler"' '"version_line": "twice 1.0 (test solver)"' '"--data"' '"seed": "11"' '"executor": "local"' '"result_hash"' \
            'embedded:stdlib/smi/study.lua'; do
  if grep -qF -- "$want" $results; then ok; else bad "results.json lacks $want"; fi
done
run verify-same 0 "$SMI" verify $results
has_out "everything matches; rerun with --seed 11"
run verify-json 0 "$SMI" verify --json $results
has_out '"match": true'

# --- verify names what changed, with both hashes ----------------------------------------------
old_helpers=$(sha256sum study/helpers.lua | cut -c1-64)
printf -- '-- tuned\n' >> study/helpers.lua
new_helpers=$(sha256sum study/helpers.lua | cut -c1-64)
run verify-module 1 "$SMI" verify $results
has_out "CHANGED  file (lua) $WORK/study/helpers.lua"
has_out "recorded sha256:$old_helpers"
has_out "now      sha256:$new_helpers"
has_out "verify: 1 difference"
run verify-module-json 1 "$SMI" verify --json $results
has_out '"match": false'
has_out '"change": "changed"'
has_out "\"now\": \"sha256:$new_helpers\""
sed -i '$d' study/helpers.lua
run verify-module-restored 0 "$SMI" verify $results

printf 'x\n1\n2\n4\n' > study/a.csv
run verify-data 1 "$SMI" verify $results
has_out "CHANGED  file (data) $WORK/study/a.csv"
printf 'x\n1\n2\n3\n' > study/a.csv

printf '# patched\n' >> study/solver-copy.sh
run verify-solver 1 "$SMI" verify $results
has_out "CHANGED  program ("
has_out "/study/solver-copy.sh"
cp study/solver.sh study/solver-copy.sh

mv study/prior.lua prior.gone
run verify-missing 1 "$SMI" verify $results
has_out "MISSING  file (lua) $WORK/study/prior.lua"
mv prior.gone study/prior.lua
run verify-all-back 0 "$SMI" verify $results

# --- verify on what is not a results file, or from a newer schema ------------------------------
run verify-not-json 2 "$SMI" verify study/study.lua
has_err "is not valid JSON"
has_err "expected the results.json a study writes"
printf '{"hello": 1}\n' > other.json
run verify-no-prov 2 "$SMI" verify other.json
has_err "has no 'provenance' object"
sed 's/"schema": 2/"schema": 99/' $results > newer.json
run verify-newer 2 "$SMI" verify newer.json
has_err "has schema 99, newer than this smi-lua"
printf '{"provenance": {"seed": 3, "libraries": []}}\n' > schema1.json
run verify-older 0 "$SMI" verify schema1.json
has_out "schema 1 is older"

# --- files over 1 GB: size and mtime, marked (a sparse file: no gigabyte written) ---------------
cat > big.lua <<'LUA'
local f = assert(io.open(smi.script_dir .. "/big.bin", "rb")) f:close()
local p = smi.provenance()
for path, d in pairs(p.files) do if path:match("big%.bin$") then print(("BIG %s %s %d"):format(d.large, d.hash == nil, d.size)) end end
LUA
truncate -s 1100M big.bin
run big 0 "$SMI" big.lua
has_out "BIG true true 1153433600"
rm -f big.bin

# --- the report's last section is the provenance (the answer and the story come first) ----------
html=out/report.html
last_h2=$(sed -n '/<main>/,/<\/main>/p' $html | grep -o '<h2 id="[^"]*"><span class="num">[0-9]*</span>[^<]*</h2>' | tail -n 1)
case "$last_h2" in *Provenance*) ok ;; *) bad "last section is '$last_h2', not Provenance" ;; esac
for want in "To reproduce this run: cd " "--seed 11" "helpers.lua" "a.csv" "solver-copy.sh" "twice 1.0 (test solver)" "eigen" "nlopt"; do
  if grep -q -- "$want" $html; then ok; else bad "report lacks $want"; fi
done

# --- partial runs: changed --data is not mixed silently with the saved data step ------------------
run only-new-data 1 "${RUN[@]}" study/study.lua --data study/b.csv --only solve
has_err "the saved results of step 'data'"
has_err "the study's arguments were '--data study/a.csv', now '--data study/b.csv'"
has_err "--data study/b.csv --from data"
lacks_out "CONCLUSION"
# the data file itself edited in place (same arguments): also refused
printf 'x\n1\n2\n30\n' > study/a.csv
run only-edited-data 1 "${RUN[@]}" study/study.lua --data study/a.csv --only solve
has_err "a.csv, which changed since"
# recomputing a step marks the later ones stale; no conclusion comes from a stale step
run only-data 1 "${RUN[@]}" study/study.lua --data study/a.csv --only data
has_err "now stale, their saved results will not be used: solve, verdict"
has_err "solve: read the results of step 'data', which this run recomputed with a different result"
has_err "verdict: read step 'solve'"
has_err "to bring them up to date, run: "
has_err "--from solve"
lacks_out "CONCLUSION"
if grep -q '"stale"' $results; then ok; else bad "results.json does not mark the stale steps"; fi
run verdict-of-stale 1 "${RUN[@]}" study/study.lua --data study/a.csv --only verdict
has_err "step 'solve' is stale"
lacks_out "CONCLUSION"
run from-solve 0 "${RUN[@]}" study/study.lua --data study/a.csv --from solve
has_out "CONCLUSION large"
if grep -q '"stale"' $results; then bad "stale marks left after the rerun"; else ok; fi
# an unchanged partial rerun is fine
run only-verdict 0 "${RUN[@]}" study/study.lua --data study/a.csv --only verdict
has_out "CONCLUSION large"

# a results file of schema 1 (no "schema", steps without inputs): a partial run says so and asks
# for the whole study, instead of trusting steps whose inputs are unknown
printf '{"study": "prov", "seed": 11, "order": ["data", "solve", "verdict"], "steps": {"data": {"status": "ok", "result": {"mean": 2}}, "solve": {"status": "ok", "result": {"y": 4}}}, "provenance": {"seed": 11, "libraries": []}}\n' > $results
run schema1-only 1 "${RUN[@]}" study/study.lua --data study/a.csv --only verdict
has_err "was saved without its inputs (results.json of schema 1, from an older smi-lua)"
lacks_out "CONCLUSION"

finish
