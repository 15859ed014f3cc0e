-- SPDX-License-Identifier: MIT
--- smi.improve.step.data: the measurements (one CSV column per declared response, every value a
-- finite number) and the units check on one nominal run before any solver budget is spent.
local revise = require "smi.improve.revise"
local sanity = require "smi.sanity"
local common = require "smi.improve.step.common"
local view, hook = common.view, common.hook

local M = {}

local function read_data(run)
  local D, file = run.D, run.opt.data
  local d, header, notes = smi.csv.read(file)
  local out = { file = file, n = 0 }
  local cols = {}
  for i, r in ipairs(D.responses) do cols[i] = r.column end
  for _, r in ipairs(D.responses) do
    local col = d[r.column]
    if col == nil then
      error(("%s: response '%s': no column '%s' (columns: %s); the declaration's responses need %s"):format(
        file, r.name, r.column, table.concat(header, ", "), table.concat(cols, ", ")), 0)
    end
    if type(col) ~= "userdata" then
      error(("%s: response '%s': column '%s' holds text; every value must be a number"):format(file, r.name, r.column), 0)
    end
    if #col < 3 then
      error(("%s: %d rows; the study needs at least 3 measurements per response"):format(file, #col), 0)
    end
    for i = 1, #col do
      if not (col[i] > -math.huge and col[i] < math.huge) then
        error(("%s: row %d, %s = %s is not a finite number"):format(file, i, r.column, tostring(col[i])), 0)
      end
    end
    out[r.name] = col:totable()
    out.n = #col
  end
  local warnings = notes and notes.warnings or {}
  out.warnings = #warnings > 0 and warnings or nil
  return out
end

-- The nominal run (every declared unknown at its start mean) against the data: magnitudes a
-- power of ten away, or outside a declared plausible range. Returns the nominal run in words.
local function units_check(run, out)
  local D = run.D
  local T0 = revise.initial(D, D.unknowns)
  local Y = run.model(T0, { purpose = "nominal", name = "nominal" }):evaluate(revise.start_point(T0))
  out.nominal, out.units = {}, {}
  local words = {}
  for _, rr in ipairs(D.responses) do
    local y = Y[rr.name][1]
    out.nominal[rr.name] = y
    words[#words + 1] = ("%s %.6g%s"):format(rr.name, y, rr.unit ~= "" and (" " .. rr.unit) or "")
    local p = y > 0 and sanity.units(("response '%s' (%s)"):format(rr.name, rr.unit), out[rr.name], y, y, 5)
    local pl = rr.plausible
    if pl then
      local lo, hi = math.huge, -math.huge
      for _, v in ipairs(out[rr.name]) do lo, hi = math.min(lo, v), math.max(hi, v) end
      if lo < pl[1] or hi > pl[2] then
        p = (p and (p .. " ") or "") .. ("response '%s': the data [%.6g, %.6g] leave its declared plausible range"
          .. " [%.6g, %.6g] (%s)"):format(rr.name, lo, hi, pl[1], pl[2], rr.unit)
      end
    end
    if p then out.units[#out.units + 1] = p end
  end
  return words
end

local function data_step(run, ctx)
  local out = read_data(run)
  local words = units_check(run, out)
  view("data")(run, ctx.report, out, words)
  for _, p in ipairs(out.units) do ctx:log("%s", p) end
  if #out.units > 0 and not run.opt.accept_units then
    error(("%s: likely a units error, stopped before any solver budget is spent: %s Fix the data's units, or give"
      .. " --accept-units (or declare accept_units = true) to go on."):format(run.opt.data,
      table.concat(out.units, " ")), 0)
  end
  hook(run, "data", ctx, out)
  return out
end

M.run = data_step

return M
