-- SPDX-License-Identifier: MIT
-- Tutorial, step 1 (docs/tutorial.md): calibrate a model written in Lua against nine tests.
-- A steel bracket is a cantilever; its first bending frequency follows from beam theory. Its
-- thickness h is known from the drawing (2.0 mm +- 0.03); its modulus E is not: we calibrate
-- E's mean and standard deviation so that the predicted frequencies match the measured ones.
local tests = smi.csv.read(smi.script_dir .. "/bracket_tests.csv")
local measured = tests.freq_hz
print(("measured: n = %d, mean = %.2f Hz, std = %.2f Hz"):format(#measured, measured:mean(), measured:std()))

-- The model works on whole vectors: X has one row per point, columns E (MPa) and h (mm).
local lambda, L, rho = 1.875104068711961, 100, 7.85e-9
local beam = smi.model.lua{
  name = "beam", inputs = {"E", "h"}, outputs = {"freq_hz"},
  fn = function(X)
    local E, h = X:col(1), X:col(2)
    return {freq_hz = (E / (12 * rho)):sqrt() * h * (lambda ^ 2 / (2 * math.pi) / L ^ 2)}
  end,
}

-- A range {lower, upper, start} is calibrated; a number is fixed.
local r = smi.calibrate{
  model = beam,
  inputs = {{name = "E", dist = "normal", mean = {150000, 250000, 180000}, std = {1000, 20000, 5000}},
            {name = "h", dist = "normal", mean = 2.0, std = 0.03}},
  data = {freq_hz = measured},
}
print(("E: mean = %.0f MPa, std = %.0f MPa (PR = %.4f, %d evaluations, converged: %s)"):format(
  r.params["E.mean"], r.params["E.std"], r.objective, r.evaluations, tostring(r.converged)))

-- Is the calibrated model valid? Predict the frequency distribution and pool the tests' u-values.
local Y = smi.propagate{model = beam, inputs = {{"E", r.distributions.E}, {"h", smi.dist.normal{mean = 2.0, std = 0.03}}}}
local verdict = smi.metric.upool{data = measured, predicted = smi.kde(Y.freq_hz)}
print(verdict)
