-- SPDX-License-Identifier: MIT
--- The study's two paths side by side: reads the results.json of the economical and
-- the full run (bench/run_study_budget.sh) and writes study_budget.md under --out: solver runs
-- per step, wall time and the conclusions the issue names (screening's top four per mode, each
-- trial's verdicts, the refinement's choice, the calibrated means against the full run's bootstrap
-- intervals). Exit status 1 when a conclusion differs or the economical path exceeds 1,000 runs.
-- usage: smi-lua --allow-read DIR --out OUT bench/study_budget.lua ECO.json ECO_WALL FULL.json FULL_WALL [OPTIONS]
local eco_file, eco_wall, full_file, full_wall, extra = arg[1], tonumber(arg[2]), arg[3], tonumber(arg[4]), arg[5] or ""
assert(eco_file and full_file, "usage: study_budget.lua ECO.json ECO_WALL FULL.json FULL_WALL [OPTIONS]")
local MODES = { "mode1", "mode2", "mode4" }
local E, F = smi.json.read(eco_file), smi.json.read(full_file)
local function res(R, step) return R.steps[step] and R.steps[step].result end

local L = {}
local function w(fmt, ...) L[#L + 1] = fmt:format(...) end
local same = true
local function mark(ok) if not ok then same = false end return ok and "yes" or "**no**" end

w("# The study at the solver's cost: economical vs full path")
w("")
w("scripts/steering_column.lua on the committed data, each path in a fresh output folder (no run reused),")
w("smi-column-fe on 2 cores%s. Written by bench/run_study_budget.sh on %s.", extra ~= "" and (", extra options `" .. extra .. "`") or "",
  os.date("!%Y-%m-%d %H:%M UTC"))
w("Economical (the default): surrogate screening of 300 runs, 20 Kriging test points, a 40-point stratified solver check.")
w("Full: `--screening full --design fixed --test-points 50 --solver-check 300` (the study before the surrogate screening); both with `--design fixed`.")
w("")
w("## Solver runs (smi-column-fe solutions) per step")
w("")
w("| step | economical | full |")
w("|---|---:|---:|")
local te, tf = 0, 0
for _, st in ipairs{ "screening", "trial1_surrogate", "trial1_validation", "refinement1", "trial2_surrogate", "trial2_validation",
                     "refinement2", "trial3_surrogate", "trial3_validation" } do
  local e, f = res(E, st), res(F, st)
  local ne, nf = e and e.solver_runs and e.solver_runs.solutions or 0, f and f.solver_runs and f.solver_runs.solutions or 0
  if ne + nf > 0 then w("| %s | %d | %d |", st, ne, nf) end
  te, tf = te + ne, tf + nf
end
w("| **total** | **%d** | **%d** |", te, tf)
w("| wall time, whole study (s) | %d | %d |", eco_wall or -1, full_wall or -1)
w("")
w("Economical path within 1,000 runs: %s (%d, %.1f %% of the full path's %d).", mark(te <= 1000), te, 100 * te / tf, tf)
w("")
w("## Conclusions")
w("")
w("Screening, top four inputs per mode (as sets: the study's trial-1 unknowns come from mode 1's four):")
w("")
w("| mode | economical (surrogate) | full (eq. 3 on smi-column-fe) | same four |")
w("|---|---|---|---|")
local se, sf = res(E, "screening"), res(F, "screening")
for _, m in ipairs(MODES) do
  local a, b = (se.responses or se.modes)[m].top, (sf.responses or sf.modes)[m].top
  local set = {}
  for _, x in ipairs(a) do set[x] = true end
  local ok = true
  for _, x in ipairs(b) do ok = ok and set[x] == true end
  w("| %s | %s | %s | %s |", m, table.concat(a, ", "), table.concat(b, ", "), mark(ok))
end
w("")
w("Trials (verdict per mode) and the refinement's choice:")
w("")
w("| trial | economical | full | same |")
w("|---|---|---|---|")
local ce, cf = E.conclusion, F.conclusion
for k = 1, math.max(#ce.trials, #cf.trials) do
  local function desc(c)
    local t = c.trials[k]
    if not t then return "not run" end
    local v = {}
    for _, m in ipairs(MODES) do v[#v + 1] = m .. " " .. t.modes[m] end
    return ("%s (%s): %s%s"):format(t.candidate, t.airbag, table.concat(v, ", "), c.refinements[k] and ("; refined by " .. c.refinements[k]) or "")
  end
  local a, b = desc(ce), desc(cf)
  w("| %d | %s | %s | %s |", k, a, b, mark(a == b))
end
w("| conclusion | %s | %s | %s |", ce.verdict, cf.verdict, mark(ce.verdict == cf.verdict))
w("")
w("Calibrated means: economical against the full path's (its 90 %% bootstrap interval where it has one):")
w("")
w("| trial | input | economical | full | full's interval | inside |")
w("|---|---|---:|---:|---|---|")
for k = 1, math.min(#ce.trials, #cf.trials) do
  local ca, cb = res(E, "trial" .. k .. "_calibration"), res(F, "trial" .. k .. "_calibration")
  for _, p in ipairs(cb.params) do
    local pe
    for _, q in ipairs(ca.params) do if q.input == p.input then pe = q end end
    local b = cb.bootstrap
    local lo, hi = b and b.lower and b.lower[p.input .. ".mean"], b and b.upper and b.upper[p.input .. ".mean"]
    local inside = "—"
    if lo and hi and pe then
      -- an interval at a bound collapses to it: the comparison allows the last digit
      local eps = 1e-9 * math.max(math.abs(lo), math.abs(hi))
      inside = mark(pe.mean >= lo - eps and pe.mean <= hi + eps)
    end
    w("| %d | %s | %.6g | %.6g | %s | %s |", k, p.input, pe and pe.mean or 0 / 0, p.mean, lo and ("[%.6g, %.6g]"):format(lo, hi) or "none", inside)
  end
end
w("")
w("Same conclusions in every row above: **%s**.", same and "yes" or "no")
local text = table.concat(L, "\n") .. "\n"
local f = assert(io.open(smi.out("study_budget.md"), "wb"))
f:write(text)
f:close()
io.write(text)
if not same then os.exit(1) end
