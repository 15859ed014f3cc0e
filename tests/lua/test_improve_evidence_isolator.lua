-- SPDX-License-Identifier: MIT
-- smi.improve compares a trial that fits with its alternatives (the forms one candidate away),
-- end to end on a product whose forms only the priors separate. References: the generating form
-- (the truth) and the verdict rule of forms.lua.
local T = require "smi.testing"
local improve = require "smi.improve"

local function applied(f) return table.concat(f.applied, "+") end

local function report(c)
  for _, f in ipairs(c.forms) do
    print(("  form {%s}: verdict %s, log evidence %.3f ± %.3f%s"):format(applied(f), tostring(f.verdict),
      f.log_evidence or 0 / 0, f.log_evidence_error or 0 / 0, f.chosen and " (chosen)" or ""))
  end
end

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
