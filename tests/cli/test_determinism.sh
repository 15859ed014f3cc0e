#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Same seed, same outputs: the same small studies run in separate smi-lua processes write
# byte-identical results.json, report, Kriging files and console output, and the same error
# messages. Lua seeds its string hashes per state, so any output built in pairs() order (or in a
# C++ loop over lua_next) changes from process to process; every check below has 8 or more keys
# whose order would then differ (8! orders), and each study runs RUNS times, each compared with
# the first.
#   1. a smi.improve study on a Lua function model (the test_improve product), its fast steps:
#      data, characterize, trial1_surrogate (three Krigings: not_saved, the .kriging files);
#   2. a smi.study with a report whose steps return 8 values JSON cannot hold, 8 Krigings and
#      8-key tables, then the error a partial run gives after all 8 of its data files changed;
#   3. messages that name one culprit of several (smi.json, unknown options, a model's columns,
#      a solver model's constants/env/executor, smi.improve fields and revision clashes,
#      smi.options suggestions, the figure check).
# Removed before comparing, as legitimately run-dependent (nothing else is):
#   results.json  "seconds", "wall_seconds", "run_seconds", "model_seconds", "kriging_seconds": N
#                 (timings)
#   report        "Generated YYYY-MM-DD HH:MM UTC"           (the date)
#                 "Steps of this run, N s|ms in total" and that table's time cells
# Output paths are the same in every run (each runs in ./run, moved aside after), so absolute
# paths need no removing; pids and dates appear nowhere else.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / finish; cd's to a temp dir
RUNS=${RUNS:-4}
: > .out; : > .err  # (lib.sh's bad() shows them; these checks compare files instead)

normalize() {  # FILE OUT
  sed -E -e 's/"(seconds|wall_seconds|run_seconds|model_seconds|kriging_seconds)": [-0-9.e+]+/"\1": T/g' \
         -e 's/Generated [0-9]{4}-[0-9]{2}-[0-9]{2} [0-9]{2}:[0-9]{2} UTC/Generated DATE/' \
         -e 's/Steps of this run, [0-9.]+ m?s in total/Steps of this run, T in total/' \
         -e 's#ran</td><td class="num">[0-9.]+</td>#ran</td><td class="num">T</td>#' "$1" > "$2"
}

# same RUN_DIR_A RUN_DIR_B WHAT: every file of A equals B's (results.json and reports normalized)
same() {
  current="$3: $(basename "$2") against $(basename "$1")"
  local f n differ=""
  for f in "$1"/* "$1"/.console; do
    n=$(basename "$f")
    [ -e "$2/$n" ] || { differ="$differ $n(missing)"; continue; }
    case "$n" in
      results.json|*.html) normalize "$f" "a.$n"; normalize "$2/$n" "b.$n"; cmp -s "a.$n" "b.$n" ;;
      *) cmp -s "$f" "$2/$n" ;;
    esac || differ="$differ $n"
  done
  if [ -z "$differ" ]; then ok; else
    bad "differ:$differ"
    for n in $differ; do if [ -e "a.$n" ]; then diff "a.$n" "b.$n" | head -8 >&2; else cmp "$1/$n" "$2/$n" >&2; fi; done
  fi
}

# runs SCRIPT ARGS... RUNS times into r1..rN (each in ./run, then moved), console in .console
runs() {
  local k
  rm -rf run r[0-9]*
  for k in $(seq "$RUNS"); do
    "$SMI" --out run "$@" > .console 2>&1
    echo "exit $?" >> .console
    mv run "r$k"; mv .console "r$k/.console"
  done
}

# ---- 1. smi.improve on a Lua function model
cp "$SMI_SOURCE_DIR/tests/lua/small_product.lua" .   # the test_improve product, beside the study
cat > improve.lua <<'LUA'
local small = require "small_product"
local data_file = smi.out("data.csv")
small.write_data(data_file)
require("smi.improve").run(small.declaration("determinism", data_file), arg)
LUA
runs improve.lua --quick --only data,characterize,trial1_surrogate
current="improve: the run made its files"
if [ -s r1/results.json ] && [ -s r1/report-partial.html ] && [ -s r1/trial1_f3.kriging ] && grep -q "exit 0" r1/.console
then ok; else bad "r1: $(ls r1) $(cat r1/.console)"; fi
for k in $(seq 2 "$RUNS"); do same r1 "r$k" improve; done

# ---- 2. smi.study with many keys, then a partial run after its data files changed
mkdir -p in
for i in $(seq 8); do printf 'x\n%d\n%d\n%d\n' "$i" $((i + 1)) $((i + 2)) > "in/input_$i.csv"; done
cat > plain.lua <<'LUA'
local study = require "smi.study"
local N = 8
local names = {}
for i = 1, N do names[i] = ("input_%d"):format(i) end
local data = {}  -- the data files, read before the steps: an input of every step
for _, n in ipairs(names) do data[n] = smi.csv.read("in/" .. n .. ".csv").x end
local s = study.new{ name = "det", out = smi.out_dir, report = { title = "Determinism" } }
s:step("data", function(ctx)
  local r = {}
  for i, n in ipairs(names) do
    r[n] = data[n]
    r["fn_" .. n] = function() return i end  -- not JSON: listed in not_saved
  end
  return r
end)
s:step("fit", function(ctx)
  local d = ctx.results.data
  local X, Y, out, means = {}, {}, {}, {}
  for i, n in ipairs(names) do X[i] = { i / N }; Y[i] = d[n][1] + math.sin(i) end
  for _, n in ipairs(names) do
    out["model_" .. n] = smi.kriging.fit(smi.mat(X), smi.vec(Y))
    means[n] = d[n][2] * 1.5
  end
  ctx.report:verdict{ name = "means", pass = true, detail = "fine" }
  ctx.report:provenance{ per_input = means }
  out.means = means
  return out
end)
s:step("sum", function(ctx)
  local t = 0
  for _, n in ipairs(names) do t = t + ctx.results.fit.means[n] end
  return { total = t }
end)
s:run(study.parse_args(arg))
LUA
runs plain.lua
current="study: the run made its files"
if [ -s r1/results.json ] && [ -s r1/report.html ] && grep -q "exit 0" r1/.console; then ok; else bad "r1: $(cat r1/.console)"; fi
for k in $(seq 2 "$RUNS"); do same r1 "r$k" study; done
# every data file changed: a partial run names the same one of the 8 every time
mv r1 saved
rm -rf r[0-9]*
for i in $(seq 8); do printf 'x\n9\n9\n9\n' > "in/input_$i.csv"; done
for k in $(seq "$RUNS"); do
  cp -r saved run
  "$SMI" --out run plain.lua --only sum > "stale$k.txt" 2>&1
  rm -rf run
done
current="stale: the partial run is refused, naming the first changed file by name"
if grep -q "read file .*/in/input_1.csv, which changed since" stale1.txt; then ok; else bad "$(cat stale1.txt)"; fi
for k in $(seq 2 "$RUNS"); do
  current="stale: run $k against run 1"
  if cmp -s stale1.txt "stale$k.txt"; then ok; else bad "$(diff stale1.txt "stale$k.txt" | head -4)"; fi
done

# ---- 3. messages naming one culprit of several
cat > errors.lua <<'LUA'
local N = 8
local function say(what, ok, msg) print(what .. ": " .. tostring(ok) .. " " .. tostring(msg)) end
local function many(prefix, value)
  local t = {}
  for i = 1, N do t[prefix .. i] = value end
  return t
end
-- smi.json: the first value JSON cannot hold, the list `skip` returns, a key JSON cannot hold
say("json function", pcall(smi.json.encode, many("f", print)))
local _, skipped = smi.json.encode({ a = many("f", print), b = many("g", print) }, { skip = true })
say("json skipped", true, table.concat(skipped, ", "))
say("json key type", pcall(smi.json.encode, { [true] = 1, [print] = 2, [{}] = 3, x = 1 }))
-- a bound function's unknown options
say("unknown option", pcall(smi.kriging.fit, smi.mat{ { 0 }, { 1 } }, smi.vec{ 0, 1 }, many("zz_option_", 1)))
-- a model's input columns
local m = smi.model.lua{ name = "m", inputs = { "a" }, outputs = { "y" }, fn = function(X) return { y = X:col(1) } end }
local X = many("not_an_input_", smi.vec{ 1 })
X.a = smi.vec{ 1 }
say("model column", pcall(m.evaluate, m, X))
-- a solver model's constants, env and executor tables
for _, field in ipairs({ "constants", "env", "executor" }) do
  local decl = { name = "c", inputs = { "x" }, outputs = { "y" }, command = { "/bin/true" }, template_string = "{{x}}",
                 deck = "in.txt", parse = function() return {} end }
  decl[field] = many(field .. "_", true)
  say("solver " .. field, pcall(smi.model.command, decl))
end
-- smi.improve: a declaration's unknown fields
say("improve field", pcall(require("smi.improve.declare").check, many("unknown_field_", 1)))
-- smi.options: a misspelt option equally close to several
local spec = { name = "s" }
for i = 1, N do spec[#spec + 1] = { name = "opt-" .. string.char(96 + i), type = "flag", meaning = "x" } end
say("option suggestion", require("smi.options").check({ "--opt-z" }, spec))
-- smi.improve.revise: two revisions setting the same 8 switches (the why goes to results.json)
local revise = require "smi.improve.revise"
local form = many("switch_", 1)
local D = { form = {}, specs = {}, design = { trend = "linear", n = 10 },
            candidates = { { name = "A", revision = { form = form, fixed = {}, unknowns = {}, specs = {} } },
                           { name = "B", revision = { form = form, fixed = {}, unknowns = {}, specs = {} } } } }
say("revision clash", true, revise.apply(D, revise.apply(D, revise.initial(D, {}), "A"), "B").dropped[1].why)
-- smi.report's figure check: several refused attributes
local attrs = {}
for i = 1, N do attrs[#attrs + 1] = ('bad%d="1"'):format(i) end
say("svg attribute", require("smi.report.svgsafe").check('<svg xmlns="http://www.w3.org/2000/svg" '
  .. table.concat(attrs, " ") .. '></svg>'))
LUA
for k in $(seq "$RUNS"); do "$SMI" errors.lua > "errors$k.txt" 2>&1; done
# and each names the first culprit by name
for want in 'json function: false .*\$\.f1 is a function' \
            'json skipped: true \$\.a\.f1 \(function\), \$\.a\.f2 .*\$\.a\.f8 \(function\), \$\.b\.g1 .*\$\.b\.g8 \(function\)$' \
            "json key type: false .*key of type boolean" "unknown option: false .*'zz_option_1'" \
            "model column: false .*'not_an_input_1'" "solver constants: false .*'constants_1'" \
            "solver env: false .*env\.env_1 " "solver executor: false .*'executor_1'" \
            "improve field: false .*'unknown_field_1'" "option suggestion: .*did you mean --opt-a\?" \
            "revision clash: true .*'switch_1'" "svg attribute: false attribute bad1 "; do
  current="errors: /$want/"
  if grep -qE -- "$want" errors1.txt; then ok; else bad "$(cat errors1.txt)"; fi
done
for k in $(seq 2 "$RUNS"); do
  while IFS= read -r line; do
    what=${line%%:*}
    current="errors: $what, run $k against run 1"
    if grep -qxF -- "$line" "errors$k.txt"; then ok; else bad "$(grep -F "$what:" "errors$k.txt")"; fi
  done < errors1.txt
done
finish
