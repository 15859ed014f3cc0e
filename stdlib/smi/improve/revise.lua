-- SPDX-License-Identifier: MIT
--- smi.improve.revise: the model of a trial as plain data (saved in results.json, so a step
-- running alone rebuilds it) and how revisions combine:
--   {candidate = "initial"|<name>, applied = {names, in order}, dropped = {{name, why}},
--    form = {switch = value}, fixed = {input = value}, unknowns = {names}, specs = {name = spec},
--    new_unknowns = {names}, trend, n_design}
-- A trial after a refinement applies the chosen candidate ON TOP of the revisions the previous
-- trial kept. A revision that sets a form switch, an unknown or a fixed value an applied one
-- already sets replaces it (the earlier is dropped, with why); a revision whose trial fitted the
-- calibrated responses worse than the trial before it is dropped before the next trial (M.keep).
local M = {}

local function copy(t)
  if type(t) ~= "table" then return t end
  local c = {}
  for k, v in pairs(t) do c[k] = copy(v) end
  return c
end
M.copy = copy

local function sorted(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  return keys
end

--- The initial model over the given unknowns (the declared pool, or the screening rule's pick).
function M.initial(D, unknowns)
  local specs = {}
  for _, n in ipairs(unknowns) do
    if not D.specs[n] then
      error(("smi.improve: the screening rule returned '%s', which is not a declared unknown"):format(tostring(n)), 0)
    end
    specs[n] = copy(D.specs[n])
  end
  return { candidate = "initial", applied = {}, dropped = {}, form = copy(D.form), fixed = {}, trend = D.design.trend,
           n_design = D.design.n, unknowns = copy(unknowns), specs = specs, new_unknowns = {}, base_unknowns = copy(unknowns) }
end

local function candidate(D, name)
  for _, c in ipairs(D.candidates) do if c.name == name then return c end end
  error(("smi.improve: no candidate named '%s'"):format(tostring(name)), 0)
end

-- What two revisions both set (a form switch, an unknown, a fixed value), or nil.
-- (Keys in name order: of several clashes the one named is the same every run.)
local function clash(a, b)
  for _, k in ipairs(sorted(b.form)) do if a.form[k] ~= nil then return ("both set the form switch '%s'"):format(k) end end
  local set = {}
  for _, n in ipairs(a.unknowns) do set[n] = true end
  for n in pairs(a.fixed) do set[n] = true end
  for _, n in ipairs(b.unknowns) do if set[n] then return ("both set '%s'"):format(n) end end
  for _, n in ipairs(sorted(b.fixed)) do if set[n] then return ("both set '%s'"):format(n) end end
  return nil
end

--- The model with the named revisions applied in order over `base_unknowns` (no clash check).
local function fold(D, base_unknowns, names)
  local m = M.initial(D, base_unknowns)
  for _, name in ipairs(names) do
    local r = candidate(D, name).revision
    for k, v in pairs(r.form) do m.form[k] = v end
    for k, v in pairs(r.fixed) do m.fixed[k] = v end
    for _, n in ipairs(r.unknowns) do
      if m.fixed[n] ~= nil then error(("smi.improve: candidate '%s': '%s' is fixed by an applied revision"):format(name, n), 0) end
      m.unknowns[#m.unknowns + 1], m.specs[n] = n, copy(r.specs[n])
      m.new_unknowns[#m.new_unknowns + 1] = n
    end
    m.trend, m.n_design = r.trend or m.trend, r.n_design or m.n_design
    m.applied[#m.applied + 1] = name
  end
  -- a revision may fix an unknown of the initial model: it is then no longer calibrated
  local left = {}
  for _, n in ipairs(m.unknowns) do
    if m.fixed[n] == nil then left[#left + 1] = n else m.specs[n] = nil end
  end
  m.unknowns = left
  return m
end

--- The next trial's model: `name` on top of the previous trial's model `prev` (its applied
-- revisions minus `drop` ({name = why}), and minus those that clash with it).
function M.apply(D, prev, name, drop)
  local c = candidate(D, name).revision
  local keep, dropped = {}, {}
  for _, a in ipairs(prev.applied) do
    local why = drop and drop[a] or clash(candidate(D, a).revision, c)
    if why then dropped[#dropped + 1] = { name = a, why = drop and drop[a] or ("replaced by " .. name .. ": " .. why) }
    else keep[#keep + 1] = a end
  end
  keep[#keep + 1] = name
  local m = fold(D, prev.base_unknowns, keep)
  m.candidate, m.dropped = name, dropped
  return m
end

--- Whether two trial models are the same model whatever their revisions' names: the same form
-- switches, fixed values and unknowns (a revision that changes nothing, or only repeats what
-- another set, gives no new form to compare).
function M.same_model(a, b)
  local function same_map(x, y)
    for k, v in pairs(x) do if y[k] ~= v then return false end end
    for k, v in pairs(y) do if x[k] ~= v then return false end end
    return true
  end
  if #a.unknowns ~= #b.unknowns or not same_map(a.form, b.form) or not same_map(a.fixed, b.fixed) then return false end
  local set = {}
  for _, n in ipairs(a.unknowns) do set[n] = true end
  for _, n in ipairs(b.unknowns) do if not set[n] then return false end end
  return true
end

--- The model `m` without its applied revision `name` (a step back: a revision applied before the
-- one that mattered may have been kept only because it absorbed part of the truth's change).
function M.without(D, m, name, why)
  local keep = {}
  for _, a in ipairs(m.applied) do if a ~= name then keep[#keep + 1] = a end end
  local out = fold(D, m.base_unknowns, keep)
  out.candidate = keep[#keep] or "initial"
  out.dropped = { { name = name, why = why } }
  out.without = name
  return out
end

--- Which of the previous trial's revisions the next keeps, on evidence: the last-applied revision
-- of trial k is dropped when trial k's calibrated objective is worse than trial k-1's (same
-- calibrated responses, the same metric). Returns {name = why} or nil.
function M.keep(R, k)
  if k < 2 then return nil end
  local prev, cur = R["trial" .. (k - 1) .. "_calibration"], R["trial" .. k .. "_calibration"]
  local T = R["trial" .. k .. "_surrogate"].model
  if not (prev and cur and prev.objective and cur.objective) or T.candidate == "initial" then return nil end
  if cur.objective > prev.objective then
    return { [T.candidate] = ("its trial fitted the calibrated responses worse: objective %.4g against %.4g before it")
      :format(cur.objective, prev.objective) }
  end
  return nil
end

--- Values of the model at its start means (the nominal and correctness runs): one row, in the
-- order of m.unknowns.
function M.start_point(m)
  local row = {}
  for i, n in ipairs(m.unknowns) do row[i] = m.specs[n].mean[3] end
  return smi.mat{ row }
end

return M
