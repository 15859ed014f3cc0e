-- SPDX-License-Identifier: MIT
--- Screening at the real solver's cost: the 46 steering-column inputs screened by the
-- full eq.-3 PDF-area method ((46 + 1) x n smi-column-fe solutions) and by the surrogate method
-- (`runs` solutions, a ridge quadratic per mode, eq.-3 on it; Borgonovo delta from the same
-- runs), both on model A (rigid airbag) through the study's own batch driver. Writes
-- screening_budget.md under --out: solver runs, wall time, top four per mode side by side.
-- usage: smi-lua --lib scripts --allow-exec SOLVER --store DB --out DIR bench/screening_budget.lua
--        SOLVER [N_FULL = 200] [RUNS = 300] [SEED = 20200234]
local solver_path = assert(arg[1], "usage: screening_budget.lua SOLVER [N_FULL] [RUNS] [SEED]")
local n_full, runs = tonumber(arg[2] or 200), tonumber(arg[3] or 300)
local seed = tonumber(arg[4] or 20200234)  -- the study's screening seed (its seed + 20)
local inputs = require "steering_column.inputs"
local solver = require "steering_column.solver"
local cost = require "smi.improve.cost"
local modes = { "mode1", "mode2", "mode4" }

local base = solver.write_deck(smi.out("screening_base_rigid.deck"), "rigid")
local function batch(name, n)
  return cost.wrap(solver.batch{ solver = solver_path, airbag = "rigid", vary = inputs.names, name = name, base = base,
                                 batch_size = math.ceil(n / 2), concurrency = 2 }, name)
end

local function top(rows, key, k)
  local t = {}
  for i = 1, #rows do t[i] = rows[i] end
  table.sort(t, function(a, b) return a[key] > b[key] end)
  local out = {}
  for i = 1, k do out[i] = t[i].input end
  return out
end
local function same_set(a, b)
  local s = {}
  for _, x in ipairs(a) do s[x] = true end
  for _, x in ipairs(b) do if not s[x] then return false end end
  return true
end
local function points(name) return (cost.counts[name] or {}).launched and cost.counts[name].points or 0 end

io.stderr:write(("full eq.-3 screening: %d x %d = %d solutions\n"):format(#inputs.names + 1, n_full, (#inputs.names + 1) * n_full))
local t0 = smi.now()
local full = smi.screen{ model = batch("full", n_full), inputs = inputs.screening_inputs(), n = n_full, seed = seed, sobol = false }
local t_full = smi.now() - t0

io.stderr:write(("surrogate screening: %d solutions\n"):format(runs))
t0 = smi.now()
local sur = smi.screen{ model = batch("surrogate", runs), inputs = inputs.screening_inputs(), n = 10000, seed = seed,
                        sobol = false, method = "surrogate", runs = runs }
local t_sur = smi.now() - t0

local L = {}
local function w(fmt, ...) L[#L + 1] = fmt:format(...) end
w("# Screening at the solver's cost: full eq.-3 vs surrogate")
w("")
w("Model A (rigid airbag), the 46 inputs at the spec's default distributions, smi-column-fe in batch mode on 2 cores,")
w("CRN seed %d. Written by bench/run_screening_budget.sh on %s.", seed, os.date("!%Y-%m-%d %H:%M UTC"))
w("")
w("| mode of screening | solver runs | wall time (s) | note |")
w("|---|---:|---:|---|")
w("| full eq.-3 (n = %d per sample, 47 samples) | %d | %.1f | the study's screening |", n_full, points("full"), t_full)
w("| surrogate: ridge quadratic (%d terms) from a Latin hypercube, eq.-3 on it (n = 10000) | %d | %.1f | Borgonovo delta from the same runs |",
  sur.mode1.terms + 1, points("surrogate"), t_sur)
w("")
w("Top four inputs by N_e (eq. 7), and by Borgonovo's delta from the surrogate's runs:")
w("")
w("| mode | full eq.-3 | surrogate eq.-3 | surrogate Q2 (LOO) | same four? | same order? | delta (given data) | delta floor |")
w("|---|---|---|---:|---|---|---|---:|")
local agree_all = true
for _, m in ipairs(modes) do
  local f, s = top(full[m], "ne", 4), top(sur[m], "ne", 4)
  local d = top(sur[m], "delta", 4)
  local set, order = same_set(f, s), table.concat(f, ",") == table.concat(s, ",")
  agree_all = agree_all and set
  w("| %s | %s | %s | %.4f | %s | %s | %s | %.3f |", m, table.concat(f, ", "), table.concat(s, ", "), sur[m].q2,
    set and "yes" or "**no**", order and "yes" or "no", table.concat(d, ", "), sur[m].delta_floor)
end
w("")
for _, m in ipairs(modes) do
  for _, msg in ipairs(sur[m].warnings) do w("- warning (%s): %s", m, msg) end
end
w("Top four agree as sets in every mode: **%s**. Solver runs saved: %d of %d (%.0f %%).", agree_all and "yes" or "no",
  points("full") - points("surrogate"), points("full"), 100 * (points("full") - points("surrogate")) / points("full"))
w("")
w("N_e of the eight largest inputs per mode, full vs surrogate:")
w("")
for _, m in ipairs(modes) do
  w("- %s: %s", m, (function()
    local t = {}
    for i = 1, 8 do
      local r = full[m][i]
      t[i] = ("%s %.3f/%.3f"):format(r.input, r.ne, sur[m].by_input[r.input].ne)
    end
    return table.concat(t, "; ")
  end)())
end
local text = table.concat(L, "\n") .. "\n"
local f = assert(io.open(smi.out("screening_budget.md"), "wb"))
f:write(text)
f:close()
io.write(text)
