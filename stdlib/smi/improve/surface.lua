-- SPDX-License-Identifier: MIT
--- smi.improve.surface: what a trial's calibration, validation and evidence run on, decided once
-- per trial in its surrogate step and recorded there (`on`, `cost`): the model itself when it runs
-- in-process and a pass of it is cheaper than the Krigings' fit and predict (a Lua model of a few
-- degrees of freedom is), else the Krigings. The choice is measured, never assumed: one batch of
-- the calibration's sample size through each, timed (evidence.costs). A model that launches a
-- solver process is never run directly: its runs are the study's budget.
--
-- Where the Krigings are used they must resolve what the data resolve: a leave-one-out error
-- that is not clearly smaller than the specimens' scatter is a surrogate error the calibration
-- would read as a property of the unknowns. A fixed design of an in-process model then gets more
-- points, once (they cost no solver run); a solver model's design is not grown: its points are
-- solver runs that the plan (--dry-run) and limits.runs did not count, so the analyst decides.
-- What is still unresolved is a warning naming the response, both figures and the fix.
local evidence = require "smi.improve.evidence"
local stream = require "smi.improve.stream"

local M = {}

-- The largest LOO RMSE, as a fraction of a response's sample std over the specimens, that still
-- counts as resolving the data. The calibration matches the predicted distribution to the data;
-- a surrogate error e shifts the predicted mean by about e, and the data fix their own mean only
-- to the standard error std/√n, 0.30-0.33 std for the 9-11 specimens of a typical test series:
-- an error above 0.3 std moves the calibrated means by more than the data determine them. (As an
-- error spread over the sample it inflates the predicted std by √(1 + 0.3²), 4 %, well inside
-- the std's own sampling error with so few specimens, about 25 %.)
M.LOO_OVER_SCATTER = 0.3
-- The fixed design grows once, by its own size, to at most this many points: a Kriging fit is
-- cubic in the points, and a design this large that still misses the scatter needs a better
-- trend or a sequential design, not more of the same points.
M.MAX_DESIGN = 400

--- The trial's decision: m the factory's model (cost.wrap's, `kind` and the raw `model`), sur
-- the surrogate's result (design, outputs, box), n points per batch. Returns {on = "model" |
-- "surrogate", model_seconds, kriging_seconds, points, why}. The times stay out of `why`: it
-- goes to the report and the console, which the same seed must reproduce byte for byte.
function M.decide(m, sur, responses, n, seed, trend)
  if m.kind ~= "lua" then
    return { on = "surrogate", why = ("the model runs a solver (%s model): its runs are the study's budget"):format(
      tostring(m.kind)) }
  end
  local Y, box = {}, {}
  for _, r in ipairs(responses) do Y[r] = smi.vec(sur.diagnostics[r].observed) end
  for i, u in ipairs(sur.unknowns) do box[i] = sur.design_bounds[u] end
  local model_s, kriging_s = evidence.costs(m.model, smi.mat(sur.design), Y, responses, box, n, seed, trend)
  local on = model_s < kriging_s and "model" or "surrogate"
  return { on = on, model_seconds = model_s, kriging_seconds = kriging_s, points = n,
           why = ("a pass of %d points through the model was measured %s than the Krigings' fit and predict;"
             .. " both times: the surrogate step's cost in results.json"):format(n, on == "model" and "faster" or "slower") }
end

--- The in-process smi.model a trial runs on (its surrogate result `sur` says where), or nil: the
-- Krigings. model_for(ctx) is the run's factory call (run.model(T, ctx)).
function M.direct(sur, model_for, purpose, name)
  if sur.on ~= "model" then return nil end
  return model_for{ purpose = purpose, name = name }.model
end

--- The responses whose Kriging does not resolve the data's scatter: {response, loo_rmse, scatter}
-- in declared order. data: {response = list of the specimens' values}.
function M.unresolved(sur, data, names)
  local out = {}
  for _, r in ipairs(names) do
    local scatter, loo = smi.vec(data[r]):std(), sur.diagnostics[r].loo_rmse
    if loo > M.LOO_OVER_SCATTER * scatter then out[#out + 1] = { response = r, loo_rmse = loo, scatter = scatter } end
  end
  return out
end

--- The trial's surrogate and the decision where it runs. build(added) is trial.surrogate with
-- `added` more design points; how: M.decide's arguments {m, responses, n, seed, trend}; data:
-- the specimens; sequential: the design is sequential (it already grows to its own target).
-- log(fmt, ...) writes to the console. Returns the surrogate result with `on`, `cost` and, per
-- unresolved response, a warning in its diagnostics.
function M.surrogate(build, how, data, n_design, sequential, log)
  local sur = build(0)
  local d = M.decide(how.m, sur, how.responses, how.n, how.seed, how.trend)
  local poor = d.on == "surrogate" and M.unresolved(sur, data, how.responses) or {}
  local added = math.min(n_design, M.MAX_DESIGN - n_design)
  if #poor > 0 and not sequential and added > 0 and how.m.kind == "lua" then
    log("the Krigings of %s do not resolve the data's scatter: %d more design points", poor[1].response, added)
    sur = build(added)
    poor = M.unresolved(sur, data, how.responses)
    sur.added_points = added
  end
  for _, p in ipairs(poor) do
    local w = ("the Kriging's leave-one-out RMSE %.4g is %.2f times the data's scatter (sample std %.4g over the"
      .. " %d specimens), above the %.1f the data resolve: the calibration would read the surrogate's error as a"
      .. " property of the unknowns. Fix: a larger design (n_design; now %d points), a trend that follows the"
      .. " response (trend), or a cheaper model that runs in-process (the trial then runs on it)"):format(p.loo_rmse,
      p.loo_rmse / p.scatter, p.scatter, #data[p.response], M.LOO_OVER_SCATTER, sur.n_design)
    local dg = sur.diagnostics[p.response]
    local ws = {}
    for i, x in ipairs(dg.warnings or {}) do ws[i] = x end
    ws[#ws + 1] = w
    dg.warnings = ws
    log("%s: %s", p.response, w)
  end
  sur.on, sur.cost = d.on, d
  return sur
end

--- The seed stream of a trial's measurement.
function M.seed(seed, k) return stream(seed, "trial cost", k) end

return M
