-- SPDX-License-Identifier: MIT
--- The steering-column model's inputs (docs/spec/steering-column.md §2) and the unknowns of
-- the two trials of Son et al. (2020), Tables 4 and 8: distribution type, bounds of the mean and
-- standard deviation, and start values. Pure data plus small helpers; no solver, no I/O.
local M = {}

-- name, nominal (= mean), distribution, std (the default for screening and propagation)
M.list = {
  { "column_frame_E", 205000, "normal", 15580 }, { "hub_E", 200000, "normal", 6000 },
  { "housing_E", 71000, "normal", 2500 }, { "heatsink_E", 69000, "normal", 2000 },
  { "wheel_frame_E", 45000, "normal", 1800 }, { "wheel_cover_E", 200, "lognormal", 20 },
  { "column_frame_nu", 0.29, "normal", 0.01 }, { "hub_nu", 0.30, "normal", 0.01 },
  { "housing_nu", 0.33, "normal", 0.01 }, { "heatsink_nu", 0.33, "normal", 0.01 },
  { "wheel_frame_nu", 0.35, "normal", 0.01 }, { "wheel_cover_nu", 0.45, "normal", 0.01 },
  { "column_frame_rho", 7.85e-9, "normal", 0.08e-9 }, { "hub_rho", 7.85e-9, "normal", 0.08e-9 },
  { "housing_rho", 2.70e-9, "normal", 0.04e-9 }, { "heatsink_rho", 2.70e-9, "normal", 0.14e-9 },
  { "wheel_frame_rho", 1.77e-9, "normal", 0.03e-9 }, { "wheel_cover_rho", 1.00e-9, "uniform", 0.05e-9 },
  { "column_tube_thickness", 2.0, "lognormal", 0.05 }, { "housing_thickness", 4.0, "lognormal", 0.10 },
  { "ecu_bracket_thickness", 3.2, "lognormal", 0.14 }, { "tilt_bracket_thickness", 2.6, "lognormal", 0.06 },
  { "heatsink_thickness", 5.0, "lognormal", 0.15 }, { "spoke_thickness", 3.0, "lognormal", 0.08 },
  { "wheel_cover_thickness", 5.5, "lognormal", 0.18 },
}
do -- bushes (5 % std), bearings (5 %), tilt lock (5 %)
  local bush = { { 2000, 3000, 3000 }, { 2000, 3000, 3000 }, { 1000, 1500, 200 }, { 1000, 1500, 200 } }
  for b = 1, 4 do
    for k, dir in ipairs{ "ka", "kl", "kv" } do
      M.list[#M.list + 1] = { ("bush%d_%s"):format(b, dir), bush[b][k], "normal", 0.05 * bush[b][k] }
    end
  end
  for b = 1, 4 do
    for _, dir in ipairs{ "kl", "kv" } do
      M.list[#M.list + 1] = { ("bearing%d_%s"):format(b, dir), 15000, "normal", 750 }
    end
  end
  M.list[#M.list + 1] = { "tilt_lock_k", 200, "normal", 10 }
end
assert(#M.list == 46, "steering_column.inputs: expected 46 inputs")

M.airbag_stiffness = { "airbag_stiffness", 1000, "normal", 31 }

M.nominal, M.names = {}, {}
for i, r in ipairs(M.list) do M.nominal[r[1]] = r[2]; M.names[i] = r[1] end
M.nominal.airbag_stiffness = 1000

--- The smi.dist of an input row {name, mean, dist, std}.
function M.dist(row, mean, std)
  mean, std = mean or row[2], std or row[4]
  return smi.dist[row[3]]{ mean = mean, std = std }
end

--- Screening inputs: {{name, dist}, ...} in table order.
function M.screening_inputs()
  local t = {}
  for i, r in ipairs(M.list) do t[i] = { r[1], M.dist(r) } end
  return t
end

-- The initial model's unknowns (Tables 4 and 8): type, bounds of the mean and std {lower, upper,
-- start}, unit, in the order of the trials' designs. The unknowns a refinement adds are declared
-- by its candidate (steering_column.lua), not here.
M.initial_unknowns = {
  { name = "wheel_cover_rho", dist = "uniform", mean = { 0.5e-9, 1.5e-9, 1.00e-9 }, std = { 0.08e-9, 0.24e-9, 0.16e-9 },
    unit = "t/mm³" },
  { name = "column_frame_E", dist = "normal", mean = { 102500, 307500, 205000 }, std = { 7790, 23370, 15580 }, unit = "MPa" },
  { name = "wheel_cover_thickness", dist = "lognormal", mean = { 2.75, 8.25, 5.5 }, std = { 0.09, 0.26, 0.18 }, unit = "mm" },
  { name = "ecu_bracket_thickness", dist = "lognormal", mean = { 1.6, 4.8, 3.2 }, std = { 0.07, 0.20, 0.14 }, unit = "mm" },
}

--- Wheel cover mass per unit length relative to nominal: density × the area of the cover tube
-- (inner diameter 24 mm, wall t; spec §5 rim) — what weighing the wheels would measure.
function M.cover_mass_ratio(rho, t)
  local area = function(w) return (12 + w) ^ 2 - 12 ^ 2 end
  return (rho * area(t)) / (M.nominal.wheel_cover_rho * area(M.nominal.wheel_cover_thickness))
end
return M
