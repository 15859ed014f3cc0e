-- SPDX-License-Identifier: MIT
--- The kernel bootstrap through smi.calibrate (bootstrap = {...}) on a three-unknown calibration
-- of Kriging surrogates: wall time of the calibration alone and with 50 and 200 replicates, the
-- replicates one after another (threads = 1) and side by side (threads = 2), whether both give the
-- same numbers, and the intervals' Monte Carlo errors and the replicates they need. Writes
-- bootstrap.md under --out (bench/run_bootstrap.sh copies it to bench/results/).
--   smi-lua --out OUT bench/bootstrap.lua [--replicates 50,200]
local options = require "smi.options"
local opt = options.parse(arg, {
  name = "bootstrap",
  { name = "replicates", type = "list", default = { "50", "200" }, meaning = "bootstrap sizes to time" },
  { name = "n", type = "integer", default = 2000, min = 100, meaning = "CRN sample size of the calibration" },
})

-- Three unknown means; three responses of them, known only through Kriging fits of 60 runs.
local function truth(a, b, c) return a * b + c, a + b * c * c, math.sin(a) + 0.3 * b end
local g = smi.rng(11)
local N = 60
local rows = {}
local Y1, Y2, Y3 = {}, {}, {}
for i = 1, N do
  local a, b, c = 0.6 + 0.8 * g:uniform(1)[1], 1.2 + 1.6 * g:uniform(1)[1], 0.3 + 1.4 * g:uniform(1)[1]
  rows[i] = { a, b, c }
  Y1[i], Y2[i], Y3[i] = truth(a, b, c)
end
local X = smi.mat(rows)
local model = { y1 = smi.kriging.fit(X, smi.vec(Y1)), y2 = smi.kriging.fit(X, smi.vec(Y2)), y3 = smi.kriging.fit(X, smi.vec(Y3)) }
-- 12 specimens of a ~ N(1.0, 0.04), b ~ N(2.0, 0.08), c ~ N(0.9, 0.05)
local d = { y1 = {}, y2 = {}, y3 = {} }
local s = smi.rng(5)
for i = 1, 12 do
  local a, b, c = s:normal(1, 1.0, 0.04)[1], s:normal(1, 2.0, 0.08)[1], s:normal(1, 0.9, 0.05)[1]
  d.y1[i], d.y2[i], d.y3[i] = truth(a, b, c)
end

local function spec(boot, threads)
  return { model = model, order = { "a", "b", "c" },
           inputs = { a = { mean = { 0.7, 1.3, 0.9 }, std = 0.04 }, b = { mean = { 1.4, 2.6, 2.2 }, std = 0.08 },
                      c = { mean = { 0.4, 1.6, 1.0 }, std = 0.05 } },
           data = d, n = opt.n, seed = 3, threads = threads, identifiability = false, progress = false, bootstrap = boot }
end

local function timed(boot, threads)
  local t0, c0 = smi.now(), os.clock()
  local r = smi.calibrate(spec(boot, threads))
  return r, smi.now() - t0, os.clock() - c0
end

local rows = {}
local base, base_wall, base_cpu = timed(nil, 2)
rows[#rows + 1] = ("| calibration alone | 2 | %.2f | %.2f | 1.0 | %d evaluations | | |"):format(base_wall, base_cpu, base.evaluations)
for _, word in ipairs(opt.replicates) do
  local b = math.tointeger(tonumber(word))
  local r1, w1, c1 = timed({ replicates = b, level = 0.95 }, 1)
  local r2, w2, c2 = timed({ replicates = b, level = 0.95 }, 2)
  local same = true
  for i = 1, r1.bootstrap.samples:rows() do
    for j = 1, 3 do same = same and r1.bootstrap.samples[i][j] == r2.bootstrap.samples[i][j] end
  end
  local bs = r2.bootstrap
  local mc = {}
  for _, p in ipairs({ "a.mean", "b.mean", "c.mean" }) do
    mc[#mc + 1] = ("%s [%.4f, %.4f] ± %.4f / %.4f"):format(p, bs.lower[p], bs.upper[p], bs.lower_mc_error[p], bs.upper_mc_error[p])
  end
  rows[#rows + 1] = ("| %d replicates | 1 | %.2f | %.2f | %.1f | %d evaluations | | |"):format(b, w1, c1, w1 / base_wall, r1.bootstrap.evaluations)
  rows[#rows + 1] = ("| %d replicates | 2 | %.2f | %.2f | %.1f | %d evaluations | %s | %s; %d replicates needed |"):format(
    b, w2, c2, w2 / base_wall, bs.evaluations, same and "same numbers as 1 thread" or "DIFFERENT from 1 thread",
    table.concat(mc, "; "), bs.replicates_needed)
end
local text = table.concat({
  "# Bootstrap through smi.calibrate",
  "",
  ("`smi-lua bench/bootstrap.lua`, %s; three unknown means, three responses of Kriging fits (60 runs each),"):format(os.date("!%Y-%m-%d %H:%M UTC")),
  ("12 data, n = %d CRN, PR, 95 %% percentile intervals with each endpoint's Monte Carlo error (lower / upper)."):format(opt.n),
  "Wall and CPU seconds; the ratio is to the calibration alone.",
  "",
  "| run | threads | wall (s) | CPU (s) | x calibration | work | threads agree | intervals |",
  "|---|---|---|---|---|---|---|---|",
  table.concat(rows, "\n"), "" }, "\n")
require("smi.file").write(smi.out("bootstrap.md"), text, "bench/bootstrap.lua")
io.write(text)
