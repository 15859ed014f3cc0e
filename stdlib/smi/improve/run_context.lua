-- SPDX-License-Identifier: MIT
--- smi.improve.run_context: the one record a study's steps share, passed to each explicitly:
-- the checked declaration D, the parsed options opt, the sample sizes cfg, the seed, the study,
-- the analyst's prior file, the trial limit, and the helpers every step uses (the factory's
-- checked model, the data as vecs, the experimental PDFs, the PR grid margins).
local factory = require "smi.improve.factory"
local calibration = require "smi.improve.calibration"

local M = {}

-- The sample sizes of a run. --quick differs only where the verdicts do not depend on it.
M.SIZES = {
  full = { screen_n = 200, cal_n = 2000, maxeval = 300, bootstrap = 50, boot_maxeval = 80, val_n = 20000, near_n = 5000 },
  quick = { screen_n = 40, cal_n = 2000, maxeval = 300, bootstrap = 0, boot_maxeval = 80, val_n = 20000, near_n = 5000 },
}

--- The sample sizes and design choices of a run (opt: the parsed options).
function M.config(opt, D)
  local cfg = {}
  for k, v in pairs(M.SIZES[opt.quick and "quick" or "full"]) do cfg[k] = v end
  cfg.screening, cfg.screen_runs, cfg.design = opt.screening, opt.screening_runs, opt.design
  if opt.bootstrap then cfg.bootstrap = opt.bootstrap end
  cfg.test_points = opt.test_points or D.design.test_points
  cfg.solver_check = opt.solver_check or D.design.solver_check
  return cfg
end

--- t: {D, opt, cfg, seed, study, prior ({entries, labels}), max_trials}.
function M.new(t)
  local run = { D = t.D, opt = t.opt, cfg = t.cfg, seed = t.seed, study = t.study, prior = t.prior,
                max_trials = t.max_trials, margins = {} }
  local D = t.D
  function run.model(T, ctx) return factory.model(D, t.opt, T, ctx) end
  function run.vecs(data)
    local d = {}
    for _, m in ipairs(D.names) do d[m] = smi.vec(data[m]) end
    return d
  end
  function run.f_exp(data) return calibration.experimental_pdfs(data, t.seed, D.names) end
  for _, r in ipairs(D.responses) do run.margins[r.name] = r.grid_margin end
  return run
end

return M
