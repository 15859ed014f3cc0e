-- SPDX-License-Identifier: MIT
-- A study whose second step picks its points from the first step's solver outputs (as a
-- calibration or a refinement does), for the --dry-run test (test_cli_dry_run.sh).
-- arg[1] = solver, arg[2] = launch log.
local study = require "smi.study"
local solver, log = arg[1], arg[2]
local m = smi.model.command{
  name = "dry", inputs = {"x1", "x2"}, outputs = {"f"},
  template_string = "x1 = {{x1}}\nx2 = {{x2}}\nlog = {{log}}\n",
  constants = {log = log}, deck = "run.deck", version = "dry-1",
  command = {solver, "{deck}", "-o", "out.txt"},
  parse = function(dir, h) return {f = h.regex("out.txt", "f = (\\S+)")} end,
}
local s = study.new{name = "dry", out = smi.out_dir, quiet = true}
s:step("first", function()
  local Y = m:evaluate{{1, 0}, {2, 0}, {3, 0}}
  return {f = {Y.f[1], Y.f[2], Y.f[3]}}
end)
s:step("second", function(ctx)
  local f = ctx.results.first.f
  local X = {}
  for i = 1, 3 do
    -- a kernel would refuse NaN here ("model output 1 is not finite")
    assert(f[i] == f[i], "model output " .. i .. " is not finite")
    X[i] = {f[i], 1}
  end
  local Y = m:evaluate(X)
  return {g = Y.f[1] + Y.f[2] + Y.f[3]}
end)
s:run()
print("study finished")
