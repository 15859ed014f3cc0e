-- SPDX-License-Identifier: MIT
--- An example of the analyst's prior knowledge for `--prior` (not used by default): the wheel
-- cover's mass relative to nominal, as weighing the wheels would give it (1 ± 0.05), on the
-- calibrated means of the cover's density and thickness. Entries follow smi.calibrate's `prior`
-- ({param = , mean = , std = } or {name = , fn = function(theta) end, mean = , std = }; see
-- `smi-lua doc smi.calibrate`).
--   smi-lua ... scripts/steering_column.lua --prior scripts/steering_column/priors/weighed_cover_mass.lua
local inputs = require "steering_column.inputs"
return {
  { name = "wheel cover mass / nominal (weighed)", mean = 1, std = 0.05,
    fn = function(th)
      return inputs.cover_mass_ratio(th["wheel_cover_rho.mean"], th["wheel_cover_thickness.mean"])
    end },
}
