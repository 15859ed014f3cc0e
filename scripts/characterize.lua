-- SPDX-License-Identifier: MIT
-- Uncertainty characterization and validation of a 9-point data set (Son et al. 2020, steps 1
-- and 5; spec §1, §5, §8.1): KDE and KDE-ebd of the measurements, a parametric fit for
-- comparison, then u-pooling verdicts of two candidate model predictions.
--   smi-lua scripts/characterize.lua
-- Data (inline, spec §8.1): nine measurements of a response, e.g. a natural frequency [Hz].
local X = {30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}

local kde = smi.kde(X, {bandwidth = "silverman"})
print(("KDE (normal reference): h = %.6f, mean %.4f, std %.4f"):format(kde.bandwidth, kde:mean(), kde:std()))
for _, rule in ipairs({"robust", "scott", "lscv", "sj"}) do
  print(("  bandwidth %-7s h = %.6f"):format(rule, smi.kde(X, {bandwidth = rule}).bandwidth))
end

local ebd, info = smi.kde_ebd(X, {alpha = 0.1, critical_area = 0.95, seed = 2020})
print(("KDE-ebd: bounds [%.4f, %.4f], %d bounded point(s) added (%s), h = %.6f"):format(
  info.lower, info.upper, info.added, info.converged and "converged" or "NOT converged", ebd.bandwidth))
print(("  PR(KDE, KDE-ebd) = %.4f; 5%%/95%% quantiles KDE %.3f/%.3f, KDE-ebd %.3f/%.3f"):format(
  smi.metric.pr(kde, ebd), kde:quantile(0.05), kde:quantile(0.95), ebd:quantile(0.05), ebd:quantile(0.95)))

local fits = smi.dist.fit(X, {"normal", "lognormal", "weibull", "gumbel", "gamma", "uniform"})
print("Parametric fits ranked by AIC:")
for _, f in ipairs(fits) do
  print(("  %-10s AIC %8.3f  BIC %8.3f  KS %.3f  %s"):format(f.family, f.aic, f.bic, f.ks, tostring(f.dist)))
end

-- Two candidate predictions of the response (e.g. a model before and after calibration).
local candidates = {
  {"calibrated model", smi.dist.normal{mean = 30.25, std = 0.36}},
  {"nominal model", smi.dist.normal{mean = 30.6, std = 0.36}},
}
print(("u-pooling threshold for n = %d at 95 %%: %.4f"):format(#X, smi.metric.upool_threshold(#X, 0.95)))
for _, c in ipairs(candidates) do
  local name, pred = c[1], c[2]
  local v = smi.metric.upool{data = X, predicted = pred, confidence = 0.95}
  print(("%-17s area metric %.4f, PR(KDE-ebd, prediction) %.4f"):format(name, smi.metric.area(X, pred),
    smi.metric.pr(ebd, pred)))
  print("  " .. tostring(v))
end
