-- SPDX-License-Identifier: MIT
-- The reference cannot drift from the code. Documented option lists are compared with
-- the names the bindings check (smi.kde's here, after a call); misspelt module members and doc
-- names get the closest names.
local T = require "smi.testing"
local doc = require "smi.doc"

T.case("documented options match the options the code reads", function()
  smi.kde(smi.vec{ 1, 2, 3, 4 }, { bandwidth = "scott" })
  smi.csv.write(smi.out("drift.csv"), { x = smi.vec{ 1, 2 } })
  smi.csv.read(smi.out("drift.csv"), { sep = "," })
  local known = smi._known_options()
  T.truthy(known["smi.kde"], "smi.kde recorded its option names")
  for _, p in ipairs(doc.check_options()) do T.truthy(false, p) end
  -- a name the code reads and the text does not list is caught, and the reverse
  local fake = { ["smi.kde"] = { "bandwidth", "method", "tol", "threads", "oversmooth" },
                 ["smi.csv.read"] = { "sep", "strings" } }
  local problems = table.concat(doc.check_options(fake), "\n")
  T.truthy(problems:find("smi.kde: read by the code but not documented: oversmooth", 1, true), problems)
  T.truthy(problems:find("smi.csv.read: documented but not read by the code: decimal", 1, true), problems)
end)

T.case("misspelt members name the closest ones", function()
  local ok, err = pcall(function() return smi.dist.Normal{ mean = 0, std = 1 } end)
  T.truthy(not ok, "smi.dist.Normal is an error")
  T.truthy(tostring(err):find("no smi.dist.Normal; did you mean smi.dist.normal?", 1, true), tostring(err))
  ok, err = pcall(function() return smi.Kde end)
  T.truthy(not ok and tostring(err):find("did you mean smi.kde?", 1, true), "smi.Kde: " .. tostring(err))
  T.eq(smi.no_such_host_field, nil, "an unknown field of smi itself stays nil (optional host fields are probed)")
  T.eq(smi.dist._private, nil, "private names are probed freely")
  T.eq(doc.suggest("smi.kdee")[1], "smi.kde", "doc names")
end)
T.finish()
