-- SPDX-License-Identifier: MIT
-- The bracket plate's experimental data (docs/spec/bracket-plate.md §4): nine specimens whose
-- E, rho, t (and log10_kw for a truth with the compliant joint) are drawn from normal
-- distributions at the TRUE means and stds given here, each solved by CalculiX on a finer mesh
-- (h = 5 mm; the study uses 10 mm) in the truth's form, plus a small measurement noise (the mean
-- of several impact tests). Writes `specimen,mode1_hz,mode2_hz,mode3_hz` (P1 ... P9).
-- The study never reads the true values: they live in the command line (the harness's
-- experiments.csv, or README.md for the committed data).
--   smi-lua --allow-exec ccx --allow-read scripts/bracket_plate --allow-write DIR \
--     scripts/bracket_plate/data/generate.lua --csv DIR/tests.csv --truth joint_sensor --seed 7 \
--     --set E=70500:1200 --set log10_kw=2.7:0.08
local options = require "smi.options"
local here = smi.script_dir
local deck = dofile(here .. "/../deck.lua")

local FORMS = {
  clamped = {joint = "clamped", sensor = "none"},
  joint_sensor = {joint = "winkler", sensor = "mass"},
  joint = {joint = "winkler", sensor = "none"},
}
-- Defaults: the spec's nominal means and mid-range stds (every experiment sets its own).
local TRUE = {E = {69000, 1000}, rho = {2.70e-9, 0.02e-9}, t = {3.0, 0.03}, log10_kw = {3.0, 0.05}}

local opt = options.parse(arg, {
  name = "bracket_plate_data", summary = "Makes the bracket plate's test data with ccx at chosen true values.",
  {name = "csv", type = "path", meaning = "the CSV file to write"},
  {name = "truth", type = "string", default = "joint_sensor", allowed = {"clamped", "joint_sensor", "joint"},
   meaning = "the specimen's true model form"},
  {name = "seed", type = "integer", default = 1, meaning = "seed of the specimens' draws and the noise"},
  {name = "set", type = "list", meaning = "true mean and std of an input: NAME=MEAN:STD (E, rho, t, log10_kw)"},
  {name = "noise", type = "number", default = 0.001, min = 0, meaning = "relative std of the measurement noise"},
  {name = "specimens", type = "integer", default = 9, min = 2, meaning = "number of specimens"},
  {name = "h", type = "number", default = 5, meaning = "element size of the truth's mesh (mm)"},
  {name = "solver", type = "string", default = "ccx", meaning = "the CalculiX program (allow it with --allow-exec)"},
})
assert(opt.csv, "give --csv FILE")
for _, s in ipairs(opt.set or {}) do
  local name, mean, std = s:match("^([%w_]+)=([^:]+):(.+)$")
  if not (name and TRUE[name] and tonumber(mean) and tonumber(std)) then
    error(("--set %s: expected NAME=MEAN:STD with NAME one of E, rho, t, log10_kw"):format(s), 0)
  end
  TRUE[name] = {tonumber(mean), tonumber(std)}
end
local form = FORMS[opt.truth]
local names = {"E", "rho", "t", "log10_kw"}

-- Draws in a fixed order (input by input, specimen by specimen), then the noise: same seed, same data.
local rng = smi.rng(opt.seed)
local X = smi.mat(opt.specimens, #names)
for j, name in ipairs(names) do
  local z = rng:normal(opt.specimens)
  for i = 1, opt.specimens do X:set(i, j, TRUE[name][1] + TRUE[name][2] * z[i]) end
end
local noise = {rng:normal(opt.specimens), rng:normal(opt.specimens), rng:normal(opt.specimens)}

local h = opt.h
local model = smi.model.command{
  name = "truth_" .. opt.truth, inputs = names, outputs = {"mode1", "mode2", "mode3"},
  template = function(p) return deck.write(p, form, h) end,
  deck = "plate.inp", command = {opt.solver, "-i", "plate"}, concurrency = 2,
  parse = function(dir, hp)
    local r = hp.ccx_dat("plate.dat")
    return {mode1 = r.cycles[1], mode2 = r.cycles[2], mode3 = r.cycles[3]}
  end,
}
local Y = model:evaluate(X)
local cols = {specimen = {}, mode1_hz = {}, mode2_hz = {}, mode3_hz = {}}
for i = 1, opt.specimens do
  cols.specimen[i] = "P" .. i
  for k = 1, 3 do
    local f = Y["mode" .. k][i] * (1 + opt.noise * noise[k][i])
    cols["mode" .. k .. "_hz"][i] = tonumber(string.format("%.3f", f))
  end
end
smi.csv.write(opt.csv, cols, {header = {"specimen", "mode1_hz", "mode2_hz", "mode3_hz"}})
io.stderr:write(("wrote %s: %d specimens, truth %s, seed %d\n"):format(opt.csv, opt.specimens, opt.truth, opt.seed))
