-- SPDX-License-Identifier: MIT
--- smi.improve.step.common: what every step of the trial loop shares: its view (the report
-- section it hands its data to), its timing and solver count, "skipped" with the reason, and the
-- declaration's section hooks.
local cost = require "smi.improve.cost"
local text = require "smi.improve.text"

local M = {}

--- The view of a report section (smi/improve/view/<name>.lua).
function M.view(name) return require("smi.improve.view." .. name) end

--- A step's function with its wall-clock seconds and the solver solutions it made recorded.
function M.timed(fn)
  return function(ctx)
    local t0, mark = os.time(), cost.mark()
    local r = fn(ctx) or ctx.result
    r.wall_seconds = os.time() - t0
    r.solver_runs = cost.since(mark)
    return r
  end
end

--- The result of a step that did not run, and why.
function M.skipped(reason) return { skipped = true, reason = reason } end

--- The declaration's hook for a section (D.sections[name]), called when declared.
function M.hook(run, name, ...)
  local f = run.D.sections[name]
  if f then return f(...) end
end

M.label = text.trial_label

return M
