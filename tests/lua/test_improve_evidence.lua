-- SPDX-License-Identifier: MIT
-- smi.improve's model-form evidence end to end on a product of its own (the isolator's is
-- test_improve_evidence_isolator.lua). The chain (tests/lua/chain_product.lua):
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
T.finish()
