-- SPDX-License-Identifier: MIT
--- smi.improve.step.screening (optional): variance-based screening, eq. 3, on a surrogate or on
-- the model; the declared rule picks the unknowns.
local revise = require "smi.improve.revise"
local stream = require "smi.improve.stream"
local common = require "smi.improve.step.common"
local view = common.view

local M = {}

local function screening_step(run, ctx)
  local D, cfg = run.D, run.cfg
  local sc = D.screening
  local names = {}
  for i, row in ipairs(sc.inputs) do names[i] = row[1] end
  local sur = cfg.screening == "surrogate"
  local runs = sur and cfg.screen_runs or (#names + 1) * cfg.screen_n
  local T0 = revise.initial(D, {})
  T0.unknowns = names
  local bm = run.model(T0, { purpose = "screening", batch = true, name = sur and "screening-surrogate" or "screening",
                             points = sur and cfg.screen_runs or cfg.screen_n })
  local n = sur and 10000 or cfg.screen_n
  ctx:log("%d inputs: %d solutions%s", #names, runs, sur and ", a ridge quadratic per response, eq. 3 on it" or "")
  local seed = stream(run.seed, "screening")
  local res = smi.screen{ model = bm, inputs = sc.inputs, n = n, seed = seed, sobol = false,
                          method = sur and "surrogate" or nil, runs = sur and cfg.screen_runs or nil }
  local out = { n = n, seed = seed, responses = {}, method = cfg.screening, solver_solutions = runs, inputs = #names }
  for _, m in ipairs(D.names) do
    local rows, top = {}, {}
    for i, row in ipairs(res[m]) do rows[i] = { input = row.input, e = row.e, ne = row.ne, rank = row.rank } end
    for i = 1, math.min(4, #rows) do top[i] = rows[i].input end
    out.responses[m] = { rows = rows, warnings = res[m].warnings, top = top, q2 = res[m].q2 }
  end
  out.unknowns = sc.rule and sc.rule(out) or D.unknowns
  revise.initial(D, out.unknowns) -- checks the rule's names
  view("screening")(run, ctx.report, out)
  return out
end

M.run = screening_step

return M
