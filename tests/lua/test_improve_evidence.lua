-- SPDX-License-Identifier: MIT
-- smi.improve's model-form evidence end to end on two products of its own. The chain
-- (tests/lua/chain_product.lua):
-- nine specimens generated from the "tip mass" form (a known 0.1 kg on m2). The frequencies alone
-- let the initial form absorb part of the tip mass in its stiffnesses; the gauge d1 = 1/k1 and
-- the design values as priors (3 % on the stiffness means) are what separate the forms.
-- References: the generating form (the truth), and the verdict rule of forms.lua (a form is
-- called valid only with a Bayes factor of at least evidence.margin over every other tried form).
local T = require "smi.testing"
local improve = require "smi.improve"
local chain = require "chain_product"

local data_file = smi.out("chain_tip_mass.csv")
chain.write_data(data_file, { "tip mass" }, nil, 11)

local function run(name, priors)
  local d = chain.declaration(name, data_file, priors)
  -- a fresh study each run: a results.json left by an earlier run would be resumed
  local results = smi.out(name .. "_results.json")
  os.remove(results)
  local _, c = improve.run(d, { "--quick" }, { results = results })
  return c
end

local function applied(f) return table.concat(f.applied, "+") end

local function report(c)
  for _, f in ipairs(c.forms) do
    print(("  form {%s}: verdict %s, log evidence %.3f ± %.3f%s"):format(applied(f), tostring(f.verdict),
      f.log_evidence or 0 / 0, f.log_evidence_error or 0 / 0, f.chosen and " (chosen)" or ""))
  end
end

T.case("with priors that separate the forms, the true form is chosen and valid, and no other", function()
  local c = run("chain_priors", true)
  report(c)
  T.eq(c.verdict, "valid")
  local chosen
  for _, f in ipairs(c.forms) do
    T.truthy(type(f.log_evidence) == "number" and type(f.log_evidence_error) == "number",
      "every tried form has its evidence")
    if f.chosen then chosen = f end
  end
  T.truthy(chosen, "a form is chosen")
  T.eq(applied(chosen), "tip mass")
  for _, f in ipairs(c.forms) do
    if f ~= chosen then T.truthy(f.verdict ~= "valid" or not f.supported, "form {" .. applied(f) .. "} is not also valid") end
  end
end)

T.case("without priors, no form the truth lacks is called valid", function()
  local c = run("chain_no_priors", false)
  report(c)
  for _, f in ipairs(c.forms) do
    T.truthy(type(f.log_evidence) == "number", "every tried form has its evidence")
    local lacks = false
    for _, a in ipairs(f.applied) do if a ~= "tip mass" then lacks = true end end
    if #f.applied == 0 then lacks = true end
    if lacks then
      T.truthy(not (f.chosen and c.verdict == "valid"), "form {" .. applied(f) .. "} (not the truth) called valid")
    end
  end
end)
-- The isolator (tests/lua/isolator_product.lua): with the means free within ±25 % the initial
-- form absorbs the bracket's mass; the design values as priors (3 %) separate the forms. The true
-- means are drawn from the priors (the sweep's first batch, bench/forms_sweep.lua).
local iso = require "isolator_product"
local iso_data = smi.out("isolator_bracket.csv")
local seed = 9100 + 17
iso.write_data(iso_data, { "bracket mass" }, iso.draw_truth(seed), seed + 1, 9)

local function run_iso(name, priors)
  local results = smi.out(name .. "_results.json")
  os.remove(results)
  local _, c = improve.run(iso.declaration(name, iso_data, priors), { "--quick" }, { results = results })
  report(c)
  return c
end

T.case("a valid trial is compared with its alternatives: with priors, the true form is the valid one", function()
  local c = run_iso("iso_priors", true)
  T.eq(c.verdict, "valid")
  local chosen, alternatives = nil, 0
  for _, f in ipairs(c.forms) do
    if f.chosen then chosen = f end
    if f.validated == false then alternatives = alternatives + 1 end
  end
  T.eq(applied(chosen), "bracket mass")
  T.truthy(alternatives >= 1, "the forms one candidate away were compared by their evidence")
  T.eq(c.refinements[1], "bracket mass", "the initial form fits; the alternative that beats it is the next trial")
end)

T.case("without priors the forms fit alike: undetermined, never valid in one form", function()
  local c = run_iso("iso_no_priors", false)
  T.eq(c.verdict, "undetermined")
  local supported = 0
  for _, f in ipairs(c.forms) do if f.supported then supported = supported + 1 end end
  T.truthy(supported >= 2, "the forms the data cannot separate are named")
end)

T.finish()
