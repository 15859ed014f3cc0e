-- SPDX-License-Identifier: MIT
--- What a study on a cheap in-process model costs: smi.improve on a small analytic product
-- (tests/lua/chain_product.lua, nine specimens of its "tip mass" form at the design values, the
-- priors on), wall time of each trial step and the calibrated means, and where the trial ran
-- (on the model or on its Krigings). usage:
--   smi-lua --allow-read tests/lua --out OUT bench/direct_model.lua tests/lua/chain_product.lua [--quick]
local improve = require "smi.improve"

local product_file = arg[1] or error("usage: direct_model.lua PRODUCT.lua [--quick]", 0)
local quick = arg[2] == "--quick"
local P = dofile(product_file)
local data = smi.out("direct_model.csv")
P.write_data(data, { "tip mass" }, nil, 11)
local name = "direct_model" .. (quick and "_quick" or "")
local results = smi.out(name .. ".json")
os.remove(results)
local t0 = smi.now()
local R = improve.run(P.declaration(name, data, true), quick and { "--quick" } or {}, { results = results })
print(("%s: study %.2f s"):format(name, smi.now() - t0))
for k = 1, 4 do
  local cal = R["trial" .. k .. "_calibration"]
  if cal == nil or cal.skipped then break end
  local sur, val = R["trial" .. k .. "_surrogate"], R["trial" .. k .. "_validation"]
  local means = {}
  for _, p in ipairs(cal.params) do means[#means + 1] = ("%s %.4f (std %.4f)"):format(p.input, p.mean, p.std) end
  print(("trial %d: on %s; surrogate %.2f s, calibration %.2f s, validation %.2f s; evidence on %s; means %s"):format(
    k, tostring(cal.on or "surrogate"), sur.wall_seconds or 0, cal.wall_seconds or 0,
    val.skipped and 0 or val.wall_seconds or 0, cal.evidence and cal.evidence.on or "-", table.concat(means, ", ")))
end
