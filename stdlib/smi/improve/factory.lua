-- SPDX-License-Identifier: MIT
--- smi.improve.factory: the declaration's model factory called for one trial model (revise.lua's
-- record): the factory's error names the candidate, the model's outputs are checked against the
-- responses and its inputs against the trial's unknowns, and its runs are counted (cost.lua).
local declare = require "smi.improve.declare"
local cost = require "smi.improve.cost"

local M = {}

--- The factory's model for `T` (a trial model record or the initial one), checked and counted.
-- ctx: {purpose, name, ...} handed to the factory with form, fixed and opt added.
function M.model(D, opt, T, ctx)
  local who = #T.applied > 0 and ("candidate '%s'"):format(T.applied[#T.applied]) or "the initial model"
  ctx.form, ctx.fixed, ctx.opt = T.form, T.fixed, opt
  local ok, m = pcall(D.model, T.applied, T.unknowns, ctx)
  if not ok then error(("smi.improve: %s: the model factory failed (%s): %s"):format(who, ctx.purpose, tostring(m)), 0) end
  if type(m) ~= "table" and type(m) ~= "userdata" then
    error(("smi.improve: %s: the model factory returned a %s, not an smi.model"):format(who, type(m)), 0)
  end
  declare.outputs(D, m, who)
  local ins = m.inputs
  if type(ins) == "table" and table.concat(ins, ",") ~= table.concat(T.unknowns, ",") then
    error(("smi.improve: %s: the model factory's model takes inputs {%s}, but the trial's unknowns are {%s} (%s):"
      .. " give smi.model the `unknowns` list it receives, in that order"):format(who, table.concat(ins, ", "),
      table.concat(T.unknowns, ", "), ctx.purpose), 0)
  end
  return cost.wrap(m, ctx.name)
end

return M
