-- SPDX-License-Identifier: MIT
--- The model-form sweep: smi.improve on small products of its own, with data generated from every
-- true form, with and without the design values as priors, and its conclusion judged against the
-- truth. usage (bench/run_forms_sweep.sh runs it on every product):
--   smi-lua --allow-read tests/lua --out OUT bench/forms_sweep.lua PRODUCT.lua [BATCHES] [FIRST_SEED] [--quick]
-- PRODUCT.lua: a module with forms, draw_truth, write_data and declaration
-- (tests/lua/isolator_product.lua, tests/lua/chain_product.lua). The true means of each batch are drawn from the priors, the specimens around
-- them: nothing is set to the design values.
-- Criteria (the class of claims smi.improve makes):
--   with priors:    the true form called valid (and chosen), and no other form ever called valid;
--   without priors: no form the truth lacks ever called valid ("undetermined" is an honest answer).
-- Prints one line per study and the counts; writes OUT/forms_sweep_PRODUCT.json.
local improve = require "smi.improve"
local json = require "smi.report.json"
local forms = require "smi.improve.forms"

local product_file = arg[1] or error("usage: forms_sweep.lua PRODUCT.lua [BATCHES] [FIRST_SEED] [--quick]", 0)
local product_name = product_file:match("([^/]+)%.lua$"):gsub("_product$", "")
local batches = tonumber(arg[2] or "4")
local first_seed = tonumber(arg[3] or "9100")
local quick = arg[4] == "--quick"
local P = dofile(product_file)

-- a form in the lines' words: its revisions in name order (smi.improve.forms.key)
local function key(applied) return (forms.key(applied):gsub("\n", " + ")) end

local rows = {}
local counts = { priors = { right = 0, other_valid = 0, n = 0 }, none = { lacking_valid = 0, valid_true = 0, n = 0 } }
for b = 1, batches do
  local seed = first_seed + 17 * b
  local truth = P.draw_truth(seed)
  for _, form in ipairs(P.forms) do
    local data = smi.out(("%s_%s_%d.csv"):format(product_name, form.name, b))
    P.write_data(data, form.applied, truth, seed + 1, 9)
    for _, priors in ipairs{ true, false } do
      local name = ("%s_%s_%d_%s"):format(product_name, form.name, b, priors and "priors" or "none")
      local results = smi.out(name .. ".json")
      os.remove(results)
      local t0 = smi.now()
      local ok, _, c = pcall(improve.run, P.declaration(name, data, priors), quick and { "--quick" } or {},
                             { results = results, out = smi.out(name) })
      local row = { product = product_name, batch = b, truth = form.name, priors = priors, seconds = smi.now() - t0 }
      if not ok then
        row.error = tostring(_)
      else
        row.verdict = c.verdict
        row.forms = {}
        for _, f in ipairs(c.forms) do
          row.forms[#row.forms + 1] = { applied = key(f.applied), log_evidence = f.log_evidence,
                                        log_evidence_error = f.log_evidence_error, verdict = f.verdict,
                                        supported = f.supported, chosen = f.chosen }
          if f.chosen then row.chosen = key(f.applied) end
        end
      end
      local true_key = key(form.applied)
      local valid_form = row.verdict == "valid" and row.chosen or nil
      if priors then
        counts.priors.n = counts.priors.n + 1
        row.right = valid_form == true_key
        if row.right then counts.priors.right = counts.priors.right + 1 end
        if valid_form and valid_form ~= true_key then counts.priors.other_valid = counts.priors.other_valid + 1 end
      else
        counts.none.n = counts.none.n + 1
        -- a form lacks the truth's revisions, or has one the truth lacks
        row.right = valid_form == nil or valid_form == true_key
        if not row.right then counts.none.lacking_valid = counts.none.lacking_valid + 1 end
        if valid_form == true_key then counts.none.valid_true = counts.none.valid_true + 1 end
      end
      local ev = {}
      for _, f in ipairs(row.forms or {}) do
        ev[#ev + 1] = ("{%s}%s %.1f±%.1f%s"):format(f.applied, f.verdict == "invalid" and "x" or "",
          f.log_evidence or 0 / 0, f.log_evidence_error or 0 / 0, f.chosen and "*" or "")
      end
      print(("%-9s b%d %-8s %-6s %-12s %-28s %s  %s [%.0f s]"):format(product_name, b, form.name,
        priors and "priors" or "none", tostring(row.verdict or "ERROR"), row.chosen and ("{" .. row.chosen .. "}") or "",
        row.right and "right" or "WRONG", row.error or table.concat(ev, " "), row.seconds))
      rows[#rows + 1] = row
    end
  end
end
print(("with priors: the true form valid in %d of %d studies; another form called valid in %d"):format(
  counts.priors.right, counts.priors.n, counts.priors.other_valid))
print(("without priors: a form the truth lacks called valid in %d of %d studies (the true form valid in %d)"):format(
  counts.none.lacking_valid, counts.none.n, counts.none.valid_true))
smi.write_file(smi.out("forms_sweep_" .. product_name .. ".json"), json.encode{ rows = rows, counts = counts })
