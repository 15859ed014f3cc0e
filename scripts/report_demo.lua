-- SPDX-License-Identifier: MIT
--- A demonstration of smi.study and smi.report on synthetic numbers: every kind of chart and
-- block the real studies use (PDFs, screening bars, leave-one-out scatter, calibration history,
-- CDFs with a threshold, a decision matrix, verdicts, provenance), no solver needed.
--
--   smi-lua --out OUT_DIR scripts/report_demo.lua [--only STEP] [--quiet]
-- writes OUT_DIR/report.html and OUT_DIR/results.json (default OUT_DIR: smi-out/report_demo/).
-- The numbers are made up for the demo; the estimators here are a few lines of plain Lua,
-- not the smi kernels.
local study = require "smi.study"
local svg = require "smi.report.svg"

local args = study.parse_args(arg)
local out = smi.out_dir or "."
local seed = smi.seed or 20200214

local s = study.new{ name = "report-demo", out = out, seed = seed,
  report = { title = "Demonstration study: a two-mode structure", subtitle = "Synthetic data; shows each block of an smi-lua report",
             author = "smi-lua report demo" } }

local function normal_pdf(x, m, sd) return math.exp(-0.5 * ((x - m) / sd) ^ 2) / (sd * math.sqrt(2 * math.pi)) end
local function normal_cdf(x, m, sd)
  -- Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7), enough for a picture
  local z = (x - m) / (sd * math.sqrt(2))
  local t = 1 / (1 + 0.3275911 * math.abs(z))
  local y = 1 - (((((1.061405429 * t - 1.453152027) * t) + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t * math.exp(-z * z)
  return 0.5 * (1 + (z >= 0 and y or -y))
end
local function mean_sd(v)
  local m, n = 0, #v
  for i = 1, n do m = m + v[i] end
  m = m / n
  local q = 0
  for i = 1, n do q = q + (v[i] - m) ^ 2 end
  return m, math.sqrt(q / (n - 1))
end

s:step("data", function(ctx)
  local rng = smi.rng(ctx.seed)
  local mode1 = rng:normal(9, 31.8, 0.9):totable()
  local mode4 = rng:normal(9, 58.2, 1.6):totable()
  ctx.report:section("Data")
  ctx.report:text("Nine synthetic specimens, the mean of five tests each. The two modes below stand in for measured natural frequencies.")
  local rows = {}
  for i = 1, 9 do rows[i] = { ("S%d"):format(i), mode1[i], mode4[i] } end
  ctx.report:table{ caption = "Synthetic measurements (Hz).", columns = { "Specimen", { title = "Mode 1 (Hz)", digits = 4 }, { title = "Mode 4 (Hz)", digits = 4 } }, rows = rows }
  return { mode1 = mode1, mode4 = mode4 }
end)

s:step("density", function(ctx)
  local d = ctx.results.data
  ctx.report:section("Uncertainty characterization")
  ctx.report:text("Kernel density estimates of each mode with two bandwidths (Silverman's rule, and 1.5 times it), with the data as a rug.")
  local figs, out_bw = {}, {}
  for _, mode in ipairs{ "mode1", "mode4" } do
    local v = d[mode]
    local m, sd = mean_sd(v)
    local h = 1.06 * sd * (#v) ^ (-1 / 5)
    local xs, a, b = {}, {}, {}
    for i = 1, 161 do
      local x = m - 4 * sd + 8 * sd * (i - 1) / 160
      xs[i] = x
      local fa, fb = 0, 0
      for j = 1, #v do fa = fa + normal_pdf(x, v[j], h); fb = fb + normal_pdf(x, v[j], 1.5 * h) end
      a[i], b[i] = fa / #v, fb / #v
    end
    local c = svg.chart{ title = mode == "mode1" and "Mode 1" or "Mode 4", xlabel = "Frequency (Hz)", ylabel = "Density", width = 470, height = 330 }
    c:line(xs, a, { label = "KDE, Silverman" }):line(xs, b, { label = "KDE, 1.5 h" }):rug(v, { label = "data" })
    figs[#figs + 1] = { c:render(), ("%s: density estimates (bandwidth %.3g Hz)."):format(mode == "mode1" and "Mode 1" or "Mode 4", h) }
    out_bw[mode] = h
  end
  ctx.report:figures(figs)
  return { bandwidth = out_bw }
end)

s:step("screening", function(ctx)
  local names = { "E_tube", "t_tube", "k_bracket_z", "k_bracket_y", "m_wheel", "J_wheel", "rho_tube", "k_joint", "d_tube", "m_airbag", "L_column", "nu" }
  local total = { 0.41, 0.22, 0.13, 0.09, 0.31, 0.05, 0.018, 0.007, 0.15, 0.026, 0.012, 0.001 }
  local first = {}
  for i, t in ipairs(total) do first[i] = t * 0.85 end
  local chosen = {}
  for i, n in ipairs(names) do if total[i] >= 0.05 then chosen[n] = true end end
  ctx.report:section("Variable screening")
  ctx.report:text("Variance-based indices of the inputs for mode 1; inputs above the 0.05 cut-off (bold) are kept as unknowns.")
  ctx.report:figure(svg.bars{ labels = names, series = { { label = "first order", values = first }, { label = "total effect", values = total } },
    sort = true, highlight = chosen, threshold = 0.05, threshold_label = "cut-off 0.05", title = "Sensitivity indices, mode 1", xlabel = "Index" },
    "Screening of 12 inputs, sorted by first-order index.")
  local kept = {}
  for _, n in ipairs(names) do if chosen[n] then kept[#kept + 1] = n end end
  return { names = names, total = total, kept = kept }
end)

s:step("surrogate", function(ctx)
  local rng = smi.rng(ctx.seed + 1)
  local obs = rng:uniform(30, 28, 36):totable()
  local noise = rng:normal(30, 0, 0.12):totable()
  local pred = {}
  for i = 1, #obs do pred[i] = obs[i] + noise[i] end
  local sse = 0
  for i = 1, #obs do sse = sse + (pred[i] - obs[i]) ^ 2 end
  local rmse = math.sqrt(sse / #obs)
  ctx.report:section("Surrogate model")
  local c = svg.chart{ title = "Leave-one-out, mode 1", xlabel = "Solver (Hz)", ylabel = "Surrogate (Hz)", equal = true, width = 470, height = 400 }
  c:scatter(obs, pred, { label = "LOO prediction" }):diagonal{ label = "y = x" }
  c:note(("RMSE %.3g Hz over %d design points"):format(rmse, #obs))
  ctx.report:figure(c:render(), "Leave-one-out predictions of the Kriging surrogate against the solver.")
  return { loo_rmse = rmse, n_design = #obs }
end)

s:step("calibration", function(ctx)
  local hist, iters = {}, {}
  for i = 1, 25 do iters[i] = i; hist[i] = 2.5 * math.exp(-0.35 * i) + 1e-3 end
  ctx.report:section("Calibration")
  ctx.report:subsection("Optimizer history")
  local c = svg.chart{ title = "Objective PR(mode 1) + PR(mode 4)", xlabel = "Iteration", ylabel = "Objective", ylog = true, legend = "none" }
  c:line(iters, hist, { label = "objective" })
  ctx.report:figure(c:render(), "SLSQP history of the calibration objective (log scale).")
  ctx.report:subsection("Calibrated inputs")
  local params = {
    { "E_tube (GPa)", 205.1, 199.0, 3.9, 2.8 }, { "t_tube (mm)", 2.02, 2.10, 0.061, 0.05 }, { "m_wheel (kg)", 3.41, 3.30, 0.12, 0.1 },
  }
  ctx.report:table{ caption = "Calibrated means and standard deviations, with the initial guesses.",
    columns = { "Input", "Mean", "Initial mean", "Std", "Initial std" }, rows = params, digits = 4 }
  ctx.report:callout("m_wheel: the objective changes by less than 1 % over its bounds; the calibrated value is weakly identified.", "warn")
  return { objective = hist, final = hist[#hist] }
end)

s:step("validation", function(ctx)
  local d = ctx.results.data
  local threshold = 0.12
  ctx.report:section("Validation")
  ctx.report:text("u-pooling: each measurement is mapped through the calibrated model's CDF; the area between the ECDF of the u values and the uniform CDF is the validation metric.")
  local figs, metrics = {}, {}
  for _, case in ipairs{ { "mode1", 31.8, 0.9 }, { "mode4", 56.0, 1.0 } } do
    local u = {}
    for i, x in ipairs(d[case[1]]) do u[i] = normal_cdf(x, case[2], case[3]) end
    table.sort(u)
    local area, n = 0, #u
    for i = 0, n do
      local a, b = i == 0 and 0 or u[i], i == n and 1 or u[i + 1]
      local F = i / n
      -- integral of |F - t| for t from a to b
      if F <= a then area = area + ((b - F) ^ 2 - (a - F) ^ 2) / 2
      elseif F >= b then area = area + ((F - a) ^ 2 - (F - b) ^ 2) / 2
      else area = area + ((F - a) ^ 2 + (b - F) ^ 2) / 2 end
    end
    metrics[case[1]] = area
    local c = svg.chart{ title = (case[1] == "mode1" and "Mode 1" or "Mode 4") .. ": u-pooling", xlabel = "u", ylabel = "Cumulative probability", width = 470, height = 360, legend = "top-left", xlim = { 0, 1 }, ylim = { 0, 1 } }
    -- the area metric is the shaded area between the ECDF of u and the uniform CDF
    local bx, blo, bhi = { 0 }, { 0 }, { 0 }
    for i = 1, n do
      bx[#bx + 1], blo[#blo + 1], bhi[#bhi + 1] = u[i], (i - 1) / n, u[i]
      bx[#bx + 1], blo[#blo + 1], bhi[#bhi + 1] = u[i], i / n, u[i]
    end
    bx[#bx + 1], blo[#blo + 1], bhi[#bhi + 1] = 1, 1, 1
    c:band(bx, blo, bhi, { label = "area metric", color = "#D55E00", opacity = 0.2 })
    c:ecdf(u, { label = "ECDF of u", color = "#0072B2" }):line({ 0, 1 }, { 0, 1 }, { label = "uniform CDF", color = "#7b8794", dash = "5 4" })
    c:note(("area metric %.4f, threshold %.2f"):format(area, threshold))
    figs[#figs + 1] = { c:render(), ("%s: area metric %.4f."):format(case[1] == "mode1" and "Mode 1" or "Mode 4", area) }
  end
  ctx.report:figures(figs)
  for _, m in ipairs{ "mode1", "mode4" } do
    local pass = metrics[m] <= threshold
    ctx.report:verdict{ name = ("Validation of %s"):format(m == "mode1" and "mode 1" or "mode 4"), pass = pass, value = metrics[m], threshold = threshold,
      detail = ("area metric %.4f %s threshold %.2f"):format(metrics[m], pass and "<=" or ">", threshold) }
  end
  return { area = metrics, threshold = threshold }
end)

s:step("refinement", function(ctx)
  local options = { "Rigid airbag", "Airbag as spring", "Airbag as shell" }
  local criteria = { "Accuracy", "Cost", "Robustness" }
  local weights = { 0.5, 0.2, 0.3 }
  local scores = { { 0.2, 0.9, 0.5 }, { 0.8, 0.8, 0.7 }, { 0.9, 0.2, 0.6 } }
  local totals = {}
  for i = 1, #options do
    local t = 0
    for j = 1, #criteria do t = t + weights[j] * scores[i][j] end
    totals[i] = t
  end
  local best = 1
  for i = 2, #options do if totals[i] > totals[best] then best = i end end
  ctx.report:section("Model refinement")
  local rows = {}
  for i = 1, #options do rows[i] = { options[i], scores[i][1], scores[i][2], scores[i][3], totals[i] } end
  ctx.report:table{ caption = "Weighted decision matrix (weights 0.5, 0.2, 0.3).", columns = { "Option", "Accuracy", "Cost", "Robustness", "Weighted score" }, rows = rows, digits = 3 }
  ctx.report:figure(svg.bars{ labels = options, values = totals, highlight = { [options[best]] = true }, title = "Weighted scores", xlabel = "Score", width = 560 },
    "Decision matrix scores; the highlighted option is chosen.")
  ctx.report:verdict{ name = "Refinement choice: " .. options[best], status = "info", detail = ("score %.3f"):format(totals[best]) }
  ctx.report:provenance{ versions = { ["smi-lua"] = smi.version or "dev", lua = _VERSION }, solver_runs = { ["demo (synthetic)"] = 0 },
    inputs = { ["(none)"] = "synthetic data, seed " .. tostring(ctx.seed) } }
  return { chosen = options[best], totals = totals }
end)

s:run(args)
