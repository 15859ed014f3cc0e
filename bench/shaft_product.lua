-- SPDX-License-Identifier: MIT
--- A three-unknown in-process product for bench/run_study_modes.sh, written as a new analyst would
-- (not tuned to any result): a shaft on two bearings with a disc; unknowns: bearing
-- stiffness kb, shaft stiffness ks, disc mass md. Responses: two frequencies (calibrate) and a
-- static deflection (validate). Candidate: a flexible mount (kf in series with kb).
local M = {}
function M.model(applied, unknowns, ctx)
  local mount = ctx.form.mount == "flexible"
  return smi.model.lua{ name = ctx.name, inputs = unknowns, outputs = { "f1", "f2", "d" }, fn = function(X)
    local idx = {}
    for j, n in ipairs(unknowns) do idx[n] = j end
    local kb, ks, md = X:col(idx.kb), X:col(idx.ks), X:col(idx.md)
    if mount then local kf = X:col(idx.kf); kb = kb * kf / (kb + kf) end
    -- two-DOF eigenvalues of [[kb+ks, -ks], [-ks, ks]] / diag(1, md)
    local a, b, c = (kb + ks), ks / md, ks
    local tr = a + b
    local det = (kb + ks) * ks / md - ks * ks / md
    local disc = (tr * tr - det * 4):sqrt()
    local l1, l2 = (tr - disc) * 0.5, (tr + disc) * 0.5
    return { f1 = l1:sqrt() * (1 / (2 * math.pi)), f2 = l2:sqrt() * (1 / (2 * math.pi)), d = (1 / kb + 1 / ks) * 1000 }
  end }
end
function M.write_data(path, seed)
  local r = smi.rng(seed or 3)
  local kb = r:normal(9, 900, 30)
  local ks = r:normal(9, 400, 12)
  local md = r:normal(9, 1.1, 0.02)
  local kf = 4000
  local kbe = kb * kf / (kb + kf)
  local tr = (kbe + ks) + ks / md
  local det = (kbe + ks) * ks / md - ks * ks / md
  local disc = (tr * tr - det * 4):sqrt()
  local l1, l2 = (tr - disc) * 0.5, (tr + disc) * 0.5
  smi.csv.write(path, { f1 = l1:sqrt() * (1 / (2 * math.pi)), f2 = l2:sqrt() * (1 / (2 * math.pi)), d = (1 / kbe + 1 / ks) * 1000 },
                { header = { "f1", "f2", "d" } })
end
function M.declaration(name, data_file)
  return {
    name = name, data = data_file,
    responses = { { name = "f1", unit = "Hz", role = "calibrate" }, { name = "f2", unit = "Hz", role = "calibrate" },
                  { name = "d", unit = "mm/kN", role = "validate" } },
    unknowns = { { name = "kb", dist = "normal", mean = { 600, 1200, 900 }, std = { 5, 80, 30 }, unit = "N/mm" },
                 { name = "ks", dist = "normal", mean = { 300, 500, 400 }, std = { 2, 40, 12 }, unit = "N/mm" },
                 { name = "md", dist = "normal", mean = { 0.9, 1.3, 1.1 }, std = { 0.002, 0.08, 0.02 }, unit = "kg" } },
    form = { mount = "rigid" },
    design = { n = 20, trend = "linear", test_points = 0, solver_check = 10 },
    model = M.model,
    candidates = {
      { name = "flexible mount", implement_minutes = 60,
        revision = { form = { mount = "flexible" }, n_design = 30,
                     unknowns = { { name = "kf", dist = "normal", mean = { 2000, 8000, 5000 }, std = { 1, 100, 10 } } } } },
    },
  }
end
return M
