-- SPDX-License-Identifier: MIT
-- The bolted bracket plate (docs/spec/bracket-plate.md): statistical model improvement of a
-- CalculiX shell model on smi.improve. Only the product is here: its responses, unknowns, model
-- factory (the deck writer in bracket_plate/deck.lua, run as a deck function), its two
-- refinement candidates and a note in the report on what the data can determine.
--   smi-lua --allow-exec ccx scripts/bracket_plate.lua [--data FILE.csv] [--quick] [--solver PATH]
local improve = require "smi.improve"
local deck = require "bracket_plate.deck"
local here = smi.script_dir or "scripts"

-- E and rho stay at their nominal values: in every clamped form the frequencies depend on E, rho
-- and t only through t*sqrt(E/rho) (plate bending: f ~ t/L^2 sqrt(E/rho)), so the data determine
-- that combination and not each input. t carries it (t_eff = t*sqrt(E/rho) / sqrt(E0/rho0)).
local NOMINAL = {E = 69000, rho = 2.70e-9}
local IDENTIFIABILITY = "In every clamped form the natural frequencies depend on E, rho and t only through "
  .. "t*sqrt(E/rho) (plate bending), so the data determine that combination, not each input: E and rho are "
  .. "fixed at their nominal values (69000 MPa, 2.70e-9 t/mm^3) and the calibrated thickness t is an effective "
  .. "one, t*sqrt(E/rho)/sqrt(E0/rho0). Its std is the unit-to-unit scatter of that combination. The sensor "
  .. "mass and the joint's springs add a weak dependence on rho*t and E*t^3 that nine specimens cannot resolve."

local function model(applied, unknowns, ctx)
  local form, fixed, solver = ctx.form, ctx.fixed, ctx.opt.solver
  return smi.model.command{
    name = ctx.name, inputs = unknowns, outputs = {"mode1", "mode2", "mode3"},
    constants = {E = NOMINAL.E, rho = NOMINAL.rho},
    -- a deck function: it computes the springs' stiffnesses (10^log10_kw times tributary areas)
    template = function(p)
      for k, v in pairs(fixed) do p[k] = v end
      return deck.write(p, form, 10)
    end,
    deck = "plate.inp", command = {solver, "-i", "plate"}, concurrency = 2, version = "calculix-ccx 2.20, S8R h=10",
    parse = function(dir, h)
      local r = h.ccx_dat("plate.dat")
      return {mode1 = r.cycles[1], mode2 = r.cycles[2], mode3 = r.cycles[3]}
    end,
  }
end

return improve.run({
  name = "bracket_plate",
  title = "Bolted bracket plate: statistical model improvement",
  subtitle = "CalculiX 2.20, S8R shells", author = "scripts/bracket_plate.lua",
  data = here .. "/bracket_plate/data/tests.csv",
  responses = {
    {name = "mode1", column = "mode1_hz", unit = "Hz", role = "calibrate", title = "Mode 1 (first bending)",
     plausible = {5, 2000}},
    {name = "mode2", column = "mode2_hz", unit = "Hz", role = "calibrate", title = "Mode 2 (second bending)"},
    {name = "mode3", column = "mode3_hz", unit = "Hz", role = "validate", title = "Mode 3 (first torsion)"},
  },
  unknowns = {
    {name = "t", dist = "normal", mean = {2.7, 3.3, 3.0}, std = {0.01, 0.09, 0.03}, unit = "mm"},
  },
  form = {joint = "clamped", sensor = "none"},
  design = {n = 8, test_points = 6, solver_check = 12},
  model = model,
  candidates = {
    {name = "sensor mass", short = "sensor", implement_minutes = 15,
     why = "the 3 g accelerometer as a point mass at (190, 40); no new unknown",
     revision = {form = {sensor = "mass"}}},
    {name = "compliant joint", short = "joint", implement_minutes = 120,
     why = "the clamped strip on a Winkler foundation of modulus k_w (SPRING1 per node)",
     revision = {form = {joint = "winkler"}, n_design = 16,
                 unknowns = {{name = "log10_kw", dist = "normal", mean = {1.7, 4.3, 3.0}, std = {0.02, 0.2, 0.05},
                              unit = "log10(N/mm^3)"}}}},
  },
  limits = {refinements = 2, runs = 300},
  sections = {
    data = function(ctx)   -- in the report and on the terminal, before anything is calibrated
      ctx.report:text(IDENTIFIABILITY)
      print("Note: " .. IDENTIFIABILITY)
    end,
  },
  options = {
    {name = "solver", type = "string", default = "ccx", meaning = "the CalculiX program (allow it with --allow-exec)"},
  },
}, arg)
