-- SPDX-License-Identifier: MIT
--- smi.report.summary: the opening of a report (smi.report:summary): the conclusion, the chosen
-- form, each response's verdict, the calibrated parameters and what is open. Checks what a study
-- hands in and turns the parameters into a table for the page (html.lua renders it).
local fmt = require "smi.report.format"

local M = {}

local STATUS = { pass = true, fail = true, warn = true, info = true, inconclusive = true, skip = true }

local function bad(level, msg) error("report:summary: " .. msg, level + 1) end

--- The summary `s`, checked and copied; raises naming the bad field.
function M.check(s, level)
  level = (level or 1) + 1
  if type(s) ~= "table" or type(s.conclusion) ~= "string" or s.conclusion == "" then
    bad(level, "expects {conclusion = \"one sentence\", form =, verdicts =, parameters =, open =}; 'conclusion' is missing")
  end
  local out = { conclusion = s.conclusion, detail = s.detail and tostring(s.detail) or nil,
                form = s.form and tostring(s.form) or nil, notes = s.notes and tostring(s.notes) or nil,
                verdicts = {}, parameters = {}, open = {} }
  for i, v in ipairs(s.verdicts or {}) do
    local status = v.status or (v.pass == true and "pass") or (v.pass == false and "fail") or nil
    if type(v) ~= "table" or type(v.name) ~= "string" or not STATUS[status] then
      bad(level, ("verdicts[%d] needs a name and a status (pass, fail, warn, inconclusive, skip) or pass = true/false"):format(i))
    end
    out.verdicts[i] = { name = v.name, status = status, detail = v.detail }
  end
  for i, p in ipairs(s.parameters or {}) do
    if type(p) ~= "table" or type(p.name) ~= "string" then bad(level, ("parameters[%d] needs a name"):format(i)) end
    local iv = p.interval
    if iv ~= nil and (type(iv) ~= "table" or type(iv[1]) ~= "number" or type(iv[2]) ~= "number") then
      bad(level, ("parameters[%d] ('%s'): interval must be {lo, hi}"):format(i, p.name))
    end
    if p.estimate ~= nil and type(p.estimate) ~= "number" then
      bad(level, ("parameters[%d] ('%s'): estimate must be a number"):format(i, p.name))
    end
    out.parameters[i] = { name = p.name, unit = p.unit, estimate = p.estimate, mean = p.mean, std = p.std, interval = iv,
                          level = p.level or 0.95, prior = p.prior }
  end
  for i, o in ipairs(s.open or {}) do
    if type(o) == "string" then o = { question = o } end
    if type(o) ~= "table" or type(o.question) ~= "string" then bad(level, ("open[%d] must be a string or {question =, settle =}"):format(i)) end
    out.open[i] = { question = o.question, settle = o.settle }
  end
  return out
end

--- Whether a parameter's point estimate lies outside its interval (the table's † mark).
function M.estimate_outside(p)
  return p.estimate ~= nil and p.interval ~= nil and (p.estimate < p.interval[1] or p.estimate > p.interval[2])
end

--- The parameters as a report table {columns =, rows =} (nil when none).
function M.parameter_table(s, digits)
  if #s.parameters == 0 then return nil end
  local any_prior, any_estimate, level = false, false, s.parameters[1].level
  for _, p in ipairs(s.parameters) do
    any_prior = any_prior or p.prior ~= nil
    any_estimate = any_estimate or p.estimate ~= nil
  end
  -- an estimate apart from the interval's distribution (a point calibration beside a posterior)
  -- gets a column of its own, marked † where it falls outside that interval
  local columns = { { title = "Parameter" } }
  if any_estimate then columns[#columns + 1] = { title = "Estimate" } end
  for _, c in ipairs{ { title = "Mean", digits = digits }, { title = "Std", digits = digits },
                      { title = ("%g %% interval"):format(100 * level) } } do columns[#columns + 1] = c end
  if any_prior then columns[#columns + 1] = { title = "Prior" } end
  local rows = {}
  for i, p in ipairs(s.parameters) do
    local iv = p.interval and ("[%s, %s]"):format(fmt.num(p.interval[1], digits), fmt.num(p.interval[2], digits)) or ""
    local row = { p.name .. (p.unit and p.unit ~= "" and (" (" .. p.unit .. ")") or "") }
    if any_estimate then
      row[#row + 1] = p.estimate and (fmt.num(p.estimate, digits) .. (M.estimate_outside(p) and " †" or "")) or ""
    end
    row[#row + 1], row[#row + 2], row[#row + 3] = p.mean, p.std, iv
    if any_prior then row[#row + 1] = p.prior or "not declared" end
    rows[i] = row
  end
  return { columns = columns, rows = rows }
end

return M
