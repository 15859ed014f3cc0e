--- The model of a trial: the initial model (rigid airbag, the four unknowns of Table 4) or the
-- revision a refinement candidate declares (refinement/candidates.lua). A trial model is plain
-- data, so it is saved in results.json and a step running alone rebuilds it from there:
--   {candidate = "initial"|<name>, airbag, fixed = {input = value}, trend, n_design,
--    unknowns = {name, ...}, specs = {name = {dist, mean = {lo, hi, start}, std = {...}, unit}},
--    new_unknowns = {name, ...}}
local inputs = require "steering_column.inputs"

local M = {}

local function copy(t)
  local c = {}
  for k, v in pairs(t) do c[k] = type(v) == "table" and copy(v) or v end
  return c
end

--- The initial model of trial 1 (Son et al. Table 4; Kriging with a linear trend on 80 points).
function M.initial()
  local specs = {}
  for _, n in ipairs(inputs.initial_unknowns) do specs[n] = copy(inputs.unknown[n]) end
  return { candidate = "initial", airbag = "rigid", fixed = {}, trend = "linear", n_design = 80,
           unknowns = copy(inputs.initial_unknowns), specs = specs, new_unknowns = {} }
end

--- The initial model revised as the candidate declares: its variant and fixed values, the initial
-- unknowns plus the candidate's new ones (a new unknown that is also fixed is an error).
function M.revised(candidate)
  local r = candidate.revision
  local m = M.initial()
  m.candidate, m.airbag, m.fixed = candidate.name, r.airbag, copy(r.fixed or {})
  m.trend, m.n_design = r.trend or m.trend, r.n_design or m.n_design
  for _, u in ipairs(r.unknowns) do
    local name, spec = u[1], u[2]
    if m.specs[name] then
      error(("candidate '%s' declares unknown '%s', which the model already has"):format(candidate.name, name), 0)
    end
    if m.fixed[name] ~= nil then
      error(("candidate '%s' both fixes and calibrates '%s'"):format(candidate.name, name), 0)
    end
    m.unknowns[#m.unknowns + 1] = name
    m.specs[name] = copy(spec)
    m.new_unknowns[#m.new_unknowns + 1] = name
  end
  return m
end

--- Deck values of the model at the initial means (the correctness run of the decision matrix):
-- the fixed values and every new unknown at its start mean.
function M.at_initial(m)
  local fixed = copy(m.fixed)
  for _, n in ipairs(m.new_unknowns) do fixed[n] = m.specs[n].mean[3] end
  return fixed
end

return M
