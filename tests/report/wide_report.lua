-- SPDX-License-Identifier: MIT
--- A report with what once made a report overflow and read wrong: a ten-column table of
-- calibrated parameters with long names and intervals, numbers with binary noise in the text
-- and the provenance, a chart with a long title, a verdict contradicting its solver check, and
-- steps that do not run. tests/report/print_report.sh renders it on screen and printed.
local study = require "smi.study"
local svg = require "smi.report.svg"

local s = study.new{ name = "wide-report", seed = smi.seed,
  report = { title = "Steering column: wide tables and printed pages", subtitle = "tests/report/wide_report.lua",
             date = "2026-01-01 00:00 UTC" } }

local names = { "column_frame_E (Young's modulus of the column frame)", "bracket_stiffness_z", "wheel_mass",
                "airbag_inertia_Jxx", "tube_thickness", "joint_rotational_stiffness" }

s:step("data", function(ctx)
  local r = ctx.report
  r:section("Data")
  -- %.17g shows the binary noise a "%s" of a computed value can carry
  r:text(("The nine specimens have a mean first frequency of %.17g Hz and a density of %.17g kg/m3; the solver's"
    .. " time step is %.17g s."):format(31.840000000000003, 7790.000000000005, 1.4999999999999998e-09))
  return { n = 9 }
end)

s:step("calibration", function(ctx)
  local r = ctx.report
  r:section("Trial 1: calibration")
  local rows = {}
  for i, n in ipairs(names) do
    local m = 2.0612345678e11 / i ^ 3
    rows[i] = { n, "normal", m, m * 0.0312345678, m * 0.98, m * 1.02, ("[%.6g, %.6g]"):format(m * 0.9712345, m * 1.0312345),
                m * 0.0412345678, ("[%.6g, %.6g]"):format(m * 0.95, m * 1.05), 0.123456789 * i }
  end
  r:table{ caption = "Calibrated parameters (SI units) with the bootstrap's intervals.", rows = rows,
           columns = { "Parameter", "Family", "Calibrated mean", "Calibrated std", "Lower bound", "Upper bound",
                       "Bootstrap CI of the mean", "Bootstrap std", "Bootstrap CI of the std", { title = "Share", unit = "%" } } }
  -- the steering column's decision matrix as its quick run printed it: ten columns of short
  -- numbers that asked for 726 px of the printed page's 688 (fixed by equal column widths)
  r:table{ caption = "Weighted decision matrix: magnitudes M, standardized S, overall rating.",
           columns = { "Candidate", "M correctness", "M robustness", "M computational cost", "M implementation cost",
                       "S correctness", "S robustness", "S computational cost", "S implementation cost", "Rating" },
           rows = { { "material properties per part", 0.1302, 3.000, 0.01667, 240.0, 0.0000, 0.000, 0, 0.0000, 0.0000 },
                    { "airbag location", 0.1276, 1.000, 0.01667, 30.00, 0.05130, 1.000, 0, 0.8750, 0.3953 },
                    { "airbag modelling type", 0.07611, 2.000, 0.02500, 60.00, 1.0000, 0.5000, 1.000, 0.7500, 0.8500 } } }
  local c = svg.chart{ title = "Trial 2 calibration: the objective (probability residual of modes 1 and 4) over the optimizer's evaluations, every start",
                       xlabel = "evaluation", ylabel = "objective", width = 640, height = 360 }
  local xs, ys = {}, {}
  for i = 1, 50 do xs[i], ys[i] = i, 2 / i + 0.1 end
  c:line(xs, ys, { label = "start 1" })
  r:figure(c, "Calibration history.")
  return { params = #names }
end)

s:step("validation", function(ctx)
  local r = ctx.report
  r:section("Trial 1: validity check")
  r:verdict{ name = "Trial 1, mode 1", pass = true, detail = "U = 0.0571 <= 0.1932" }
  r:verdict{ name = "Trial 1, mode 2", status = "inconclusive", detail = "U in [0.12, 0.31] over the near-optimal calibrations; threshold 0.1932",
             checks = { { name = "Solver check", pass = false, detail = "U = 0.3112 on 40 solver runs" } } }
  r:verdict{ name = "Trial 1, mode 4", pass = false, detail = "U = 0.4100 > 0.1932",
             checks = { { name = "Solver check", pass = false } } }
  r:callout("Data: the frequencies look like kHz (31.84 where the model predicts about 30000): check the units.", "warn")
  return { verdicts = 3 }
end)

s:step("trial3_calibration", function(ctx) return ctx:skip("trial 2 is valid: nothing to refine") end)
s:step("trial3_validation", function(ctx) return { skipped = true, reason = "trial 3 did not run" } end)

s:step("summary", function(ctx)
  local r = ctx.report
  r:section("Summary")
  r:verdict{ name = "Conclusion: the model is inconclusive", status = "inconclusive",
             detail = "mode 2 is undecided and mode 4 is invalid" }
  r:provenance{ time_step = 1.4999999999999998e-09, density = 7790.000000000005, solver = "build/smi-column-fe",
                sample_sizes = { screen_n = 200, val_n = 20000, tol = 0.30000000000000004 } }
  return {}
end)

s:run(study.parse_args(arg))
