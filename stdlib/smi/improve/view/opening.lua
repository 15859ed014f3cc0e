-- SPDX-License-Identifier: MIT
--- The report's opening page (smi.report:summary) and the marking of the trials the conclusion
-- does not rest on (smi.report:supersede): the answer before the story. out: the summary step's
-- result (its conclusion `c`); R: the steps' results.
local text = require "smi.improve.text"
local verdict = require "smi.improve.verdict"
local summary = require "smi.report.summary"

-- "normal(1000, 30)" for the declared or --prior entry on param, or nil.
local function prior_text(priors, param)
  for _, p in ipairs(priors or {}) do
    if p.param == param then return ("%s(%.4g, %.3g)"):format(p.dist or "normal", p.mean, p.std) end
  end
  return nil
end

-- The calibrated parameters of trial k: the probability-residual optimum (the paper's calibration)
-- with the interval it has (the bootstrap's, in a full run), else the posterior's.
local function parameters(D, R, k, T)
  local cal = R["trial" .. k .. "_calibration"]
  local ev = cal.evidence or {}
  local rows = {}
  for _, p in ipairs(cal.params or {}) do
    local unit = T.specs[p.input] and T.specs[p.input].unit
    for _, part in ipairs{ "mean", "std" } do
      local param = p.input .. "." .. part
      local b = cal.bootstrap
      -- the bootstrap's interval is centred on the PR optimum (estimate ± 1.645 sd): one mean;
      -- the posterior's has its own mean, so the optimum is shown beside it as the estimate
      local iv, level, sd, mean, estimate = nil, nil, nil, p[part], nil
      if b and b.lower and b.lower[param] and b.upper[param] then
        iv, level, sd = { b.lower[param], b.upper[param] }, b.level, b.std and b.std[param]
      elseif ev.interval and ev.interval[param] then
        iv, level, sd = ev.interval[param], ev.interval_level or 0.9, ev.std and ev.std[param]
        mean, estimate = ev.mean and ev.mean[param] or p[part], p[part]
      end
      rows[#rows + 1] = { name = param, unit = unit ~= "" and unit or nil, mean = mean, estimate = estimate,
                          std = sd, interval = iv, level = iv and level or nil,
                          prior = prior_text(ev.priors, param) }
    end
  end
  return rows
end

-- What the table's columns are, and the parameters whose estimate lies outside the posterior's
-- interval: the data's optimum where the priors and the data together put little weight.
local function parameters_note(k, rows)
  local posterior, outside = false, {}
  for _, p in ipairs(rows) do
    if p.estimate ~= nil then
      posterior = true
      if summary.estimate_outside(p) then outside[#outside + 1] = p.name end
    end
  end
  if not posterior then
    return ("Parameters: the probability-residual optimum of trial %d (the paper's calibration); std and interval:"
      .. " the bootstrap's over the data, when it ran."):format(k)
  end
  local note = ("Estimate: the probability-residual optimum of trial %d (the paper's calibration). Mean, std and"
    .. " interval: the posterior's, under the declared priors and the data (no bootstrap ran: --quick or"
    .. " --bootstrap 0)."):format(k)
  if #outside > 0 then
    note = note .. (" † %s: the optimum lies outside the posterior's interval, where the data alone pull (often a"
      .. " range bound) and the priors and data together put little weight; read the posterior, and see what"
      .. " would settle it below."):format(table.concat(outside, ", "))
  end
  return note
end

return function(run, r, out, R)
  local D, c = run.D, out.conclusion
  local k = c.chosen or #c.trials
  local T = R["trial" .. k .. "_surrogate"].model
  local chosen = c.trials[k]
  local verdicts = {}
  for _, m in ipairs(D.names) do
    local v = chosen.responses[m] or "not validated"
    verdicts[#verdicts + 1] = { name = D.by_name[m].title or m,
                                status = verdict.BADGE[v] or "skip",
                                detail = ("%s in trial %d"):format(v, k) }
  end
  local open = {}
  local val, cal = R["trial" .. k .. "_validation"], R["trial" .. k .. "_calibration"]
  for _, m in ipairs(c.undetermined or {}) do
    open[#open + 1] = { question = ("%s is not determined by these data"):format(m), settle = text.settle(m, cal) }
  end
  local open_forms = false
  for _, reason in ipairs(c.comparison or {}) do open_forms = open_forms or reason.kind == "inseparable" end
  if open_forms then
    open[#open + 1] = { question = "the data do not single out one model form",
                        settle = text.separate(D, c, R) }
  end
  local form = ("trial %d, %s; unknowns %s"):format(k, text.form_name(T.applied), table.concat(T.unknowns, ", "))
  local rows = parameters(D, R, k, T)
  -- the reasons under the short sentence, without repeating its opening words
  local detail = text.conclusion_detail(D, c, R):gsub("^%l", string.upper):gsub("%.?$", ".")
  r:summary{ conclusion = text.conclusion_short(D, c), detail = detail,
             form = form, verdicts = verdicts, parameters = rows, open = open,
             notes = parameters_note(k, rows) .. (val and val.skipped and (" " .. val.reason) or "") }
  -- the trials the conclusion does not rest on: in the page, not counted
  for _, it in ipairs(r.items or {}) do
    local n = it.kind == "section" and it.level == 1 and it.title and tonumber(it.title:match("^Trial (%d+) "))
    if n and n ~= k then
      r:supersede(it.title, ("the conclusion rests on trial %d (%s)"):format(k, text.form_name(T.applied)))
    end
  end
end
