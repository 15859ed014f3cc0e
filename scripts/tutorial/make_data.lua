-- SPDX-License-Identifier: MIT
-- How bracket_tests.csv was made: nine brackets whose modulus E and thickness h vary as the
-- truth below says, each "tested" for its first bending frequency (beam theory, no noise).
-- The calibration in the tutorial does not know E's mean and std; it should find them.
--   build/smi-lua --out scripts/tutorial scripts/tutorial/make_data.lua
local g = smi.rng(2026, "bracket tests")
local E = g:normal(9, 205000, 8000)   -- MPa: the truth the tutorial recovers
local h = g:normal(9, 2.0, 0.03)      -- mm: known from the drawing's tolerance
local lambda = 1.875104068711961
local f = (E / (12 * 7.85e-9)):sqrt() * h * (lambda ^ 2 / (2 * math.pi) / 100 ^ 2)
smi.csv.write(smi.out("bracket_tests.csv"), {bracket = {"B1", "B2", "B3", "B4", "B5", "B6", "B7", "B8", "B9"}, freq_hz = f},
              {header = {"bracket", "freq_hz"}})
print(f)
