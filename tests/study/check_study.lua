-- Checks of the reduced steering-column study (scripts/steering_column.lua --quick).
-- arg[1] = its results.json, arg[2] = its report.html.
--
-- The true values are those of scripts/steering_column/data/make_data.cpp (the study itself
-- never reads them): wheel level wheel_cover_rho U(1.25e-9, sd 0.12e-9), wheel_cover_thickness
-- LN(4.6, 0.15), airbag_stiffness N(850, 25); column level column_frame_E N(240000, 12000),
-- ecu_bracket_thickness LN(3.9, 0.10); model B; 0.3 % noise per impact, mean of 5.
--
-- What is asserted, and why these tolerances:
-- * The paper's course of events: trial 1 fails the u-pooling check on mode 4, the decision
--   matrix picks the airbag modelling, trial 2 passes modes 1, 2 and 4. Modes 1 and 4 leave
--   combinations of the means undetermined (below); the mode-2 pass rests on the calibration's
--   prior that the wheel cover's mass is known from weighing (scripts/steering_column/inputs.lua),
--   and the test also checks that the study reports that dependence.
-- * Identifiable quantities only. Modes 1 and 4 cannot separate the five means: mode 1 is
--   driven by column_frame_E and by the ECU bracket (whose plate stiffness is E·t³), the wheel
--   cover's density and thickness act alike, so those means trade off along valleys of the
--   objective. Identifiable are:
--   - airbag_stiffness (mode 4 alone moves with it): within 10 % of 850. The 9 data hold only 3
--     wheels, whose sample mean of N(850, 25) scatters by 25/√3 ≈ 14 N/mm; the Kriging test
--     RMSE of mode 4 (≈ 0.1-0.3 Hz at dmode4/dk ≈ 0.013 Hz per N/mm) adds up to ≈ 25 N/mm; 10 %
--     (85 N/mm) is about 3 of these combined deviations.
--   - the ECU bracket's bending stiffness E·t³ of the calibrated means: within 20 % of
--     240000·3.9³. The column modulus also stiffens the jacket, so part of the bracket's share
--     can move to E; 20 % allows that trade without letting the calibration miss mode 1.
--   - the calibrated model's predicted mode means (Kriging, 5000 samples) within 0.5 Hz of the
--     data means (data std ≈ 0.5 Hz; 9 data give a standard error ≈ 0.17 Hz, plus the Kriging
--     RMSE ≈ 0.2 Hz), for modes 1, 4 and the unseen mode 2;
--   - predicted stds within a factor 2 of the data stds: the std lower bounds of Table 8
--     (column_frame_E ≥ 7790 MPa alone gives ≈ 0.5 Hz in mode 1) and the KDE smoothing keep the
--     predicted spread above the data's, and 9 data estimate a std to ±25 % only.
-- * Every calibrated mean near its true value, with tolerances stated per parameter. The 9 data
--   hold 3 wheels and 3 columns, so the truth is only seen through 3-specimen sample means, which
--   scatter by sd/√3: column_frame_E 2.9 %, airbag 1.7 %, ECU bracket 1.5 %, cover density 5.5 %,
--   cover thickness 1.9 %.
--   - column_frame_E, ecu_bracket_thickness, airbag_stiffness: within 10 % (about twice the
--     sampling scatter plus the Kriging error and the E-bracket trade-off bounded by E·t³ below);
--   - the wheel cover's mass (density × tube area, inputs.cover_mass_ratio): within 10 % of the
--     truth's. Density and thickness act on the modes almost only through that mass, so each
--     alone is weakly determined: within 25 % (their ranges are ±50 % of nominal; seen in
--     development: +20 % / −16 % when SLSQP is allowed 800 evaluations along that valley).
local T = require "smi.testing"
local json = require "smi.report.json"

local function read(path)
  local f = assert(io.open(path, "rb"), "cannot open " .. tostring(path))
  local s = f:read("a")
  f:close()
  return s
end

local R = json.lua_decode(read(arg[1]))
local S = R.steps
local data = S.data.result

T.case("every step ran", function()
  for _, name in ipairs(R.order) do T.eq(S[name].status, "ok", name) end
  T.eq(#R.order, 11, "eleven steps")
end)

T.case("trial 1 fails on mode 4 and holds mode 1", function()
  local v = S.trial1_validation.result.modes
  T.eq(v.mode4.pass, false, "mode 4 invalid")
  T.truthy(v.mode4.metric > v.mode4.threshold, "U above the threshold")
  T.near(v.mode4.threshold, 0.1927, 2e-3, "exact n = 9 threshold (spec §8.3)")
  T.eq(v.mode1.pass, true, "mode 1 valid after calibration")
  -- the rigid airbag cannot reach the measured wheel-pitch frequency
  T.truthy(v.mode4.predicted_mean - smi.vec(data.mode4):mean() > 5, "mode 4 predicted too high by > 5 Hz")
end)

T.case("refinement picks the airbag modelling", function()
  local r = S.refinement.result
  T.eq(r.best_name, "airbag modelling type")
  T.eq(r.picks_airbag_modelling, true)
  -- eq. (13) on mode 4 with nominal inputs: spring 72.67 Hz (spec §11) vs rigid 80.23 Hz
  T.near(r.candidates[3].prediction.mode4, 72.6656, 1e-3, "revised model run at the initial means (spec §11 model B)")
  T.near(r.candidates[1].prediction.mode4, 80.2333, 1e-3, "candidate 1 runs as model A at the initial means (spec §11)")
  T.truthy(r.candidates[3].magnitudes[1] < r.candidates[2].magnitudes[1], "airbag spring is the most correct")
end)

T.case("trial 2 passes all three modes; the study says what mode 2 rests on", function()
  local v = S.trial2_validation.result.modes
  for _, m in ipairs{ "mode1", "mode2", "mode4" } do
    T.eq(v[m].pass, true, m)
    T.truthy(v[m].metric <= v[m].threshold, m .. " U below threshold")
  end
  T.eq(S.summary.result.trial2_passes_all, true, "summary")
  T.eq(S.summary.result.paper_reproduced, true, "the paper's course of events")
  -- modes 1 and 4 leave most of mode 2's sensitivity unconstrained: the report must say so
  T.truthy(S.trial2_calibration.result.sensitivity.mode2_unconstrained_share > 0.2, "mode 2 flagged as not determined by modes 1 and 4")
  -- the weighing prior holds: the calibrated wheel cover mass is within 3 sigma (15 %) of nominal
  T.near(S.trial2_calibration.result.cover_mass_ratio, 1, 0.15, "cover mass ratio")
end)

T.case("trial 2: calibrated means and identifiable quantities near the truth", function()
  local p = {}
  for _, q in ipairs(S.trial2_calibration.result.params) do p[q.input] = q end
  local truth = { wheel_cover_rho = 1.25e-9, wheel_cover_thickness = 4.6, airbag_stiffness = 850,
                  column_frame_E = 240000, ecu_bracket_thickness = 3.9 }
  local tol = { wheel_cover_rho = 0.25, wheel_cover_thickness = 0.25, airbag_stiffness = 0.10,
                column_frame_E = 0.10, ecu_bracket_thickness = 0.10 }
  for name, v in pairs(truth) do
    T.rel(p[name].mean, v, tol[name], ("%s mean within %d %% of the truth"):format(name, tol[name] * 100))
  end
  local area = function(w) return (12 + w) ^ 2 - 12 ^ 2 end  -- as scripts/steering_column/inputs.lua
  T.rel(p.wheel_cover_rho.mean * area(p.wheel_cover_thickness.mean), truth.wheel_cover_rho * area(truth.wheel_cover_thickness),
        0.10, "wheel cover mass within 10 % of the truth's")
  local ei = p.column_frame_E.mean * p.ecu_bracket_thickness.mean ^ 3
  T.rel(ei, 240000 * 3.9 ^ 3, 0.20, "ECU bracket stiffness E·t³")
  local v = S.trial2_validation.result.modes
  for _, m in ipairs{ "mode1", "mode2", "mode4" } do
    local d = smi.vec(data[m])
    T.near(v[m].predicted_mean, d:mean(), 0.5, m .. " predicted mean vs data")
    local ratio = v[m].predicted_std / d:std()
    T.truthy(ratio > 0.5 and ratio < 2, ("%s predicted std / data std = %.3f"):format(m, ratio))
  end
end)

T.case("screening and surrogates", function()
  local top = S.screening.result.modes.mode1.top
  T.eq(top[1], "column_frame_E", "spec §12: column_frame_E dominates mode 1")
  T.eq(top[2], "ecu_bracket_thickness", "spec §12: then the ECU bracket")
  for _, t in ipairs{ "trial1", "trial2" } do
    for _, m in ipairs{ "mode1", "mode2", "mode4" } do
      T.truthy(S[t .. "_surrogate"].result.diagnostics[m].loo_q2 > 0.98, t .. " " .. m .. " LOO Q2")
    end
  end
end)

T.case("report: one self-contained file with the study's figures and verdicts", function()
  local html = read(arg[2])
  T.truthy(not html:find("<script[^>]-src=") and not html:find("<link[^>]-href=\"http"), "no external resources")
  local n = select(2, html:gsub("<svg", ""))
  T.truthy(n >= 20, "figures: " .. n)
  T.truthy(html:find("Trial 2 passes modes 1, 2 and 4", 1, true) ~= nil, "summary verdict")
end)

T.finish()
