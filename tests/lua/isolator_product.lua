-- SPDX-License-Identifier: MIT
-- A small product whose candidate forms the data separate only through declared priors (the
-- model-form tests and bench/forms_sweep.lua): a motor on an isolator on a frame,
-- ground - k1 - m1 (frame) - k2 - m2 (motor, 1 kg). Responses: the two natural frequencies f1, f2
-- (Hz, calibrate) and s, the static sag of the motor under its own weight and the frame's
-- (mm, validate). Unknowns: k1, k2 (N/mm) and the frame mass m1 (kg): three means and stds.
-- Candidates: "bracket mass", the motor bracket's known 0.15 kg on m2 (a change of form, no new
-- unknown), and "soft foot", a foot pad of stiffness kf in series with k1 (a new unknown).
-- With the means free within ±25 % the initial form absorbs either: the soft foot only ever
-- acts through the series stiffness of k1 and kf (on every response), and three free means fit
-- three responses. Priors on the design values (3 % on the means) are what tell the forms apart.
-- Closed form: det(K - λM) = 0 for K = [[ks + k2, -k2], [-k2, k2]], M = diag(m1, m2),
-- f = sqrt(λ) / 2π (k in N/m); s = g (m1 + m2) / ks + g m2 / k2 (mm for k in N/mm).
local M = {}

M.m2, M.bracket, M.g = 1.0, 0.15, 9.81
-- design values (the priors' centres); the truth of a batch is drawn around them (M.draw_truth)
M.design = { k1 = 800, k2 = 300, m1 = 2.0, kf = 4000 }
M.prior_cov = { k1 = 0.03, k2 = 0.03, m1 = 0.03, kf = 0.05 }
-- specimen-to-specimen scatter (coefficient of variation)
M.scatter = { k1 = 0.02, k2 = 0.02, m1 = 0.01, kf = 0.03 }
-- the four true forms a batch may come from, by the candidates they apply
M.forms = { { name = "initial", applied = {} }, { name = "bracket", applied = { "bracket mass" } },
            { name = "foot", applied = { "soft foot" } }, { name = "both", applied = { "bracket mass", "soft foot" } } }

--- {f1, f2, s} of the rows of k1, k2, m1, kf (vecs; kf nil: no foot pad) with motor mass m2.
function M.respond(k1, k2, m1, kf, m2)
  local ks = kf and (k1 * kf) / (k1 + kf) or k1
  local a, c = ks * 1000, k2 * 1000 -- N/m
  local b = a * m2 + c * m2 + c * m1
  local disc = (b * b - a * c * (m1 * (4 * m2))):sqrt()
  local den = m1 * (2 * m2)
  local l1, l2 = (b - disc) / den, (b + disc) / den
  local sag = (m1 + m2) * M.g / ks + M.g * m2 / k2
  return { f1 = l1:sqrt() / (2 * math.pi), f2 = l2:sqrt() / (2 * math.pi), s = sag }
end

--- The model of the declaration: an smi.model.lua over the current unknowns.
function M.model(applied, unknowns, ctx)
  local foot, m2 = ctx.form.foot == "pad", M.m2 + (ctx.form.bracket == "on" and M.bracket or 0)
  return smi.model.lua{ name = ctx.name, inputs = unknowns, outputs = { "f1", "f2", "s" }, fn = function(X)
    local idx = {}
    for j, n in ipairs(unknowns) do idx[n] = j end
    return M.respond(X:col(idx.k1), X:col(idx.k2), X:col(idx.m1), foot and X:col(idx.kf) or nil, m2)
  end }
end

--- The true means of a batch: each drawn from its prior (the design value, M.prior_cov), seed `seed`.
function M.draw_truth(seed)
  local g = smi.rng(seed, "isolator truth")
  local t = {}
  for _, n in ipairs{ "k1", "k2", "m1", "kf" } do t[n] = g:normal(1, M.design[n], M.prior_cov[n] * M.design[n])[1] end
  return t
end

--- Writes n specimens (default 9) of the true form `applied` (candidate names) with true means
-- `truth` (M.draw_truth) to path, seed `seed`.
function M.write_data(path, applied, truth, seed, n)
  n = n or 9
  local on = {}
  for _, a in ipairs(applied) do on[a] = true end
  local g = smi.rng(seed, "isolator specimens")
  local x = {}
  for _, k in ipairs{ "k1", "k2", "m1", "kf" } do x[k] = g:normal(n, truth[k], M.scatter[k] * truth[k]) end
  local y = M.respond(x.k1, x.k2, x.m1, on["soft foot"] and x.kf or nil, M.m2 + (on["bracket mass"] and M.bracket or 0))
  smi.csv.write(path, { f1 = y.f1, f2 = y.f2, s = y.s }, { header = { "f1", "f2", "s" } })
end

--- The declaration; priors = true adds the design values as priors on the means.
function M.declaration(name, data_file, priors)
  local function unknown(n, unit)
    local v, sc = M.design[n], M.scatter[n]
    return { name = n, dist = "normal", unit = unit, mean = { 0.75 * v, 1.25 * v, v }, std = { 0.25 * sc * v, 3 * sc * v, sc * v },
             prior = priors and { mean = { dist = "normal", mean = v, std = M.prior_cov[n] * v } } or nil }
  end
  return {
    name = name, data = data_file,
    responses = { { name = "f1", unit = "Hz" }, { name = "f2", unit = "Hz" }, { name = "s", unit = "mm", role = "validate" } },
    unknowns = { unknown("k1", "N/mm"), unknown("k2", "N/mm"), unknown("m1", "kg") },
    form = { bracket = "off", foot = "none" },
    design = { n = 30, test_points = 0, solver_check = 10 },
    model = M.model,
    candidates = {
      { name = "bracket mass", implement_minutes = 10, revision = { form = { bracket = "on" } } },
      { name = "soft foot", implement_minutes = 30,
        revision = { form = { foot = "pad" }, n_design = 40, unknowns = { unknown("kf", "N/mm") } } },
    },
  }
end

return M
