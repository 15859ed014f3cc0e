-- SPDX-License-Identifier: MIT
--- smi.improve.step.characterize: uncertainty characterization of the data, the plain KDE
-- against the KDE with estimated bounded data (Son et al. 2020 §4.1.1), with their curves.
local trial = require "smi.improve.trial"
local common = require "smi.improve.step.common"
local view = common.view

local M = {}

local function characterize_step(run, ctx)
  local D = run.D
  local data = run.vecs(ctx.results.data)
  local ebd = run.f_exp(ctx.results.data)
  local out, curves = {}, {}
  for _, m in ipairs(D.names) do
    local k = smi.kde(data[m], { bandwidth = "silverman" })
    local e = ebd[m]
    local lo = math.min(e.lower, data[m]:min()) - 3 * e.bandwidth
    local hi = math.max(e.upper, data[m]:max()) + 3 * e.bandwidth
    curves[m] = { kde = trial.pdf_curve(k, data[m], lo, hi), ebd = trial.pdf_curve(e, data[m], lo, hi),
                  data = data[m]:totable() }
    out[m] = { mean = data[m]:mean(), std = data[m]:std(), kde_bandwidth = k.bandwidth, ebd_bandwidth = e.bandwidth,
               ebd_lower = e.lower, ebd_upper = e.upper, ebd_added = e.added, ebd_std = e:std() }
  end
  view("characterize")(run, ctx.report, out, curves, #data[D.names[1]])
  return out
end

M.run = characterize_step

return M
