-- SPDX-License-Identifier: MIT
-- A second small product for smi.improve's model-form tests (tests/lua/test_improve_evidence.lua):
-- two masses on a chain of springs, ground - k1 - m1 - k2 - m2. Responses: the two natural frequencies f1, f2 (Hz, calibrate) and
-- d1, the static deflection of m1 under a unit force at m2, read by a gauge across k1 alone
-- (mm/N, validate). Unknowns: k1 and k2 (N/mm). Candidates: "tip mass", a known 0.1 kg on m2 (a
-- change of form, no new unknown), and "base spring", a support of stiffness kb in series with k1
-- (a new unknown). The frequencies see k1 and kb only through their series stiffness, so without
-- a prior the initial form absorbs the base spring on f1 and f2; the gauge across k1 does not.
-- Closed form: det(K - λM) = 0 for K = [[ks + k2, -k2], [-k2, k2]], M = diag(m1, m2), ks the
-- series stiffness of k1 and kb; f = sqrt(λ) / 2π with k in N/m.
local M = {}

M.m1, M.m2, M.tip = 1.0, 0.5, 0.1
-- design values (the priors' centres, 3 % on the means) and the specimen-to-specimen scatter
M.design = { k1 = 1000, k2 = 600, kb = 4000 }
M.scatter = { k1 = 20, k2 = 15, kb = 60 }
-- the four true forms a batch may come from, by the candidates they apply
M.forms = { { name = "initial", applied = {} }, { name = "tip", applied = { "tip mass" } },
            { name = "base", applied = { "base spring" } }, { name = "both", applied = { "tip mass", "base spring" } } }

--- {f1, f2, d1} of the rows of k1, k2, kb (vecs, N/mm) with tip mass `tip` (kg).
function M.respond(k1, k2, kb, tip)
  local ks = kb and (k1 * kb) / (k1 + kb) or k1
  local a, c = ks * 1000, k2 * 1000 -- N/m
  local m1, m2 = M.m1, M.m2 + tip
  local b = a * m2 + c * m2 + c * m1
  local disc = (b * b - a * c * (4 * m1 * m2)):sqrt()
  local l1, l2 = (b - disc) / (2 * m1 * m2), (b + disc) / (2 * m1 * m2)
  return { f1 = l1:sqrt() / (2 * math.pi), f2 = l2:sqrt() / (2 * math.pi), d1 = (k1 * 0 + 1) / k1 }
end

--- The model of the declaration: an smi.model.lua over the current unknowns.
function M.model(applied, unknowns, ctx)
  local base, tip = ctx.form.base == "spring", ctx.form.tip == "mass" and M.tip or 0
  return smi.model.lua{ name = ctx.name, inputs = unknowns, outputs = { "f1", "f2", "d1" }, fn = function(X)
    local idx = {}
    for j, n in ipairs(unknowns) do idx[n] = j end
    return M.respond(X:col(idx.k1), X:col(idx.k2), base and X:col(idx.kb) or nil, tip)
  end }
end

--- The true means of a batch: each drawn from its prior (3 % around the design value), seed `seed`.
function M.draw_truth(seed)
  local g = smi.rng(seed, "chain truth")
  local t = {}
  for _, n in ipairs{ "k1", "k2", "kb" } do t[n] = g:normal(1, M.design[n], 0.03 * M.design[n])[1] end
  return t
end

--- Writes n specimens (default 9) of the true form `applied` (candidate names) with true means
-- `truth` (M.draw_truth; default the design values) to path, seed `seed`.
function M.write_data(path, applied, truth, seed, n)
  n, truth = n or 9, truth or M.design
  local on = {}
  for _, a in ipairs(applied) do on[a] = true end
  local g = smi.rng(seed, "chain specimens")
  local k1 = g:normal(n, truth.k1, M.scatter.k1)
  local k2 = g:normal(n, truth.k2, M.scatter.k2)
  local kb = g:normal(n, truth.kb, M.scatter.kb)
  local y = M.respond(k1, k2, on["base spring"] and kb or nil, on["tip mass"] and M.tip or 0)
  smi.csv.write(path, { f1 = y.f1, f2 = y.f2, d1 = y.d1 }, { header = { "f1", "f2", "d1" } })
end

--- The declaration; priors = true adds the design values as priors (3 % on the means).
function M.declaration(name, data_file, priors)
  local function prior(v) return priors and { mean = { dist = "normal", mean = v, std = 0.03 * v } } or nil end
  return {
    name = name, data = data_file,
    responses = { { name = "f1", unit = "Hz" }, { name = "f2", unit = "Hz" }, { name = "d1", unit = "mm/N", role = "validate" } },
    unknowns = { { name = "k1", dist = "normal", mean = { 750, 1250, 1000 }, std = { 5, 60, 20 }, prior = prior(1000) },
                 { name = "k2", dist = "normal", mean = { 450, 750, 600 }, std = { 5, 45, 15 }, prior = prior(600) } },
    form = { base = "rigid", tip = "none" },
    design = { n = 20, test_points = 0, solver_check = 10 },
    -- small evidence sizes keep the tests fast; the forms' evidence differs by far more than its error
    evidence = { n = 200, samples = 200 },
    model = M.model,
    candidates = {
      { name = "tip mass", implement_minutes = 10, revision = { form = { tip = "mass" } } },
      { name = "base spring", implement_minutes = 30,
        revision = { form = { base = "spring" }, n_design = 30,
                     unknowns = { { name = "kb", dist = "normal", mean = { 3000, 5000, 4000 }, std = { 10, 150, 60 },
                                    prior = prior(4000) } } } },
    },
  }
end

return M
