-- SPDX-License-Identifier: MIT
-- The small product the smi.improve tests run on (tests/lua/test_improve.lua, and
-- tests/cli/test_determinism.sh, which copies this file beside its study): two calibrated
-- responses f1 = 10a - k, f2 = 20a - 6k and a validation-only one f3 = 10a + 2k of a
-- stiffness-like unknown a. The initial model has no joint (k = 0); the candidate "joint" adds k.
-- Truth: a ~ N(1.05, 0.02), k = 0.5, so f2/f1 = 1.8 where the initial model can only give 2
-- (trial 1 invalid, trial 2 applies "joint", valid).
local M = {}

--- The model of the declaration: an smi.model.lua over the current unknowns.
function M.model(applied, unknowns, ctx)
  local joint = ctx.form.joint == "spring"
  return smi.model.lua{ name = ctx.name, inputs = unknowns, outputs = { "f1", "f2", "f3" }, fn = function(X)
    local idx = {}
    for j, n in ipairs(unknowns) do idx[n] = j end
    local a = X:col(idx.a)
    local k = joint and X:col(idx.k) or a * 0
    return { f1 = a * 10 - k, f2 = a * 20 - k * 6, f3 = a * 10 + k * 2 }
  end }
end

--- Writes 9 specimens of the truth to `path` (CSV: f1, f2, f3).
function M.write_data(path)
  local a = smi.rng(7):normal(9, 1.05, 0.02)
  smi.csv.write(path, { f1 = a * 10 - 0.5, f2 = a * 20 - 3, f3 = a * 10 + 1 }, { header = { "f1", "f2", "f3" } })
end

--- The declaration, named `name`, reading `data_file`; the fields of `over` replace its own.
function M.declaration(name, data_file, over)
  local d = {
    name = name,
    data = data_file,
    responses = { { name = "f1", unit = "Hz", role = "calibrate", grid_margin = 3 },
                  { name = "f2", unit = "Hz", role = "calibrate", grid_margin = 6 },
                  { name = "f3", unit = "", role = "validate" } },
    unknowns = { { name = "a", dist = "normal", mean = { 0.8, 1.3, 1.05 }, std = { 0.005, 0.06, 0.03 }, unit = "-" } },
    form = { joint = "none" },
    design = { n = 12, trend = "linear", test_points = 0, solver_check = 10 },
    model = M.model,
    candidates = {
      { name = "joint", implement_minutes = 30,
        revision = { form = { joint = "spring" }, n_design = 20,
                     unknowns = { { name = "k", dist = "normal", mean = { 0, 1, 0.5 }, std = { 0.001, 0.01, 0.005 } } } } },
      { name = "nothing", implement_minutes = 500, revision = {} },
    },
  }
  for k, v in pairs(over or {}) do d[k] = v end
  return d
end

return M
