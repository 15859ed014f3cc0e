-- SPDX-License-Identifier: MIT
-- The public stats API, asserted against spec §8 values and closed forms.
local T = require "smi.testing"
local X = {30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}

T.case("kde with a rule name or a number (spec 8.1)", function()
  local d = smi.kde(X, {bandwidth = "silverman"})
  T.near(d.bandwidth, 0.2481836818, 1e-10, "silverman h")
  T.near(smi.kde(X, {bandwidth = "scott"}).bandwidth, 0.2343071145, 1e-10, "scott h")
  T.near(smi.kde(X, {bandwidth = "robust"}).bandwidth, 0.1861048387, 1e-10, "robust h")
  T.near(smi.kde(X).bandwidth, 0.2481836818, 1e-10, "default h")
  local k = smi.kde(X, {bandwidth = 0.2481836818})
  T.near(k:pdf(30.25), 0.8960452764, 1e-10, "pdf(30.25)")
  T.near(k:cdf(31.0), 0.9534190121, 1e-10, "cdf(31)")
  local p = k:pdf({29.5, 30.0})
  T.near(p[1], 0.1947599356, 1e-10, "pdf vec 1")
  T.near(p[2], 0.8497143052, 1e-10, "pdf vec 2")
  T.near(k:quantile(0.2950008950), 30.0, 1e-8, "quantile")
  local c = k:curve(101)
  T.eq(#c.x, 101, "curve length")
end)

T.case("kde bad input names the culprit", function()
  T.raises(function() smi.kde({}) end, "data is empty")
  T.raises(function() smi.kde({1.0}) end, "pass a fixed bandwidth")
  T.near(smi.kde({1.0}, {bandwidth = 0.5}):pdf(1.0), 0.7978845608, 1e-9, "one point with h")
  T.raises(function() smi.kde({2, 2, 2}) end, "all 3 data values are equal")
  T.raises(function() smi.kde({1, 2, 0 / 0, 4}) end, "data[3] is NaN")
  T.raises(function() smi.kde({1, 2, math.huge}) end, "data[3] is inf")
  T.raises(function() smi.kde(X, {bandwidth = "silvermann"}) end, "unknown bandwidth rule 'silvermann'")
  T.raises(function() smi.kde(X, {bandwith = 0.2}) end, "bandwith")
end)

T.case("kde_ebd bounds and reporting (spec 8.1)", function()
  local d, info = smi.kde_ebd(X, {alpha = 0.1, seed = 3})
  T.near(d.lower, 29.4147178852, 1e-9, "l")
  T.near(d.upper, 31.2352821148, 1e-9, "u")
  T.near(info.lower, 29.4147178852, 1e-9, "info.l")
  T.truthy(info.added >= 1 and info.added == d.added, "added reported")
  T.eq(#info.added_points, info.added, "added points")
  local d5 = smi.kde_ebd(X, {alpha = 0.05, seed = 3})
  T.near(d5.lower, 29.2958065869, 1e-9, "l(0.05)")
  T.near(d5.upper, 31.3541934131, 1e-9, "u(0.05)")
  -- Same seed, same result.
  local a = smi.kde_ebd(X, {seed = 11}); local b = smi.kde_ebd(X, {seed = 11})
  T.eq(a.bandwidth, b.bandwidth, "reproducible")
  -- Every loop rule is an option; a critical area of 1 never stops before max_added.
  local _, i2 = smi.kde_ebd(X, {critical_area = 1.0, max_added = 5, step = 1, seed = 1})
  T.eq(i2.added, 5, "max_added")
  T.eq(i2.converged, false, "not converged")
  T.raises(function() smi.kde_bd(X, {lower = 31, upper = 29}) end, "lower (31) must be < upper (29)")
  local bd = smi.kde_bd(X, {lower = 29, upper = 31.5, seed = 2})
  T.near(bd.lower, 29, 0, "bd lower")
end)

T.case("distributions (spec 8.5 parameterisations)", function()
  local ln = smi.dist.lognormal{mean = 5.5, std = 0.18}
  T.near(ln.mu_log, 1.7042128416, 1e-9, "mu_ln")
  T.near(ln.sigma_log, 0.0327185145, 1e-9, "sigma_ln")
  T.near(ln:quantile(0.8413447460685429), 5.6798871019, 1e-8, "x(z=1)")
  T.near(ln:mean(), 5.5, 1e-12, "mean")
  T.near(ln:std(), 0.18, 1e-12, "std")
  local u = smi.dist.uniform{mean = 1.0, std = 0.16}
  T.near(u.lower, 0.7228718708, 1e-9, "uniform a")
  T.near(u.upper, 1.2771281292, 1e-9, "uniform b")
  T.near(u:quantile(0.8413447460685429), 1.1891924618, 1e-9, "uniform x(z=1)")
  local n = smi.dist.normal{mean = 30.25, std = 0.36}
  T.near(n:cdf(30.25), 0.5, 1e-15, "normal cdf")
  T.near(-smi.metric.loglik(X, n), 3.1562182871, 1e-9, "-logL")
  T.raises(function() smi.dist.normal{mean = 0, std = -1} end, "std must be a positive finite number, got -1")
  T.raises(function() smi.dist.uniform{lower = 2, upper = 1} end, "lower (2) must be < upper (1)")
  T.raises(function() smi.dist.normal{mean = 0} end, "missing field 'std'")
  -- closed forms of the other families
  T.near(smi.dist.gumbel{loc = 0, scale = 1}:cdf(0), math.exp(-1), 1e-15, "gumbel")
  T.near(smi.dist.weibull{shape = 1, scale = 2}:cdf(2), 1 - math.exp(-1), 1e-15, "weibull=exp")
  T.near(smi.dist.gamma{shape = 1, scale = 2}:cdf(2), 1 - math.exp(-1), 1e-14, "gamma=exp")
  T.near(smi.dist.gamma{shape = 3, scale = 1}:cdf(2), 1 - 5 * math.exp(-2), 1e-14, "gamma k=3")
  T.near(smi.dist.beta{alpha = 2, beta = 1}:cdf(0.3), 0.09, 1e-14, "beta(2,1)")
  T.near(smi.dist.beta{alpha = 2, beta = 3}:quantile(smi.dist.beta{alpha = 2, beta = 3}:cdf(0.4)), 0.4, 1e-12, "beta q")
  T.near(smi.dist.triangular{lower = 0, mode = 1, upper = 3}:cdf(1), 1 / 3, 1e-15, "triangular")
  local tn = smi.dist.truncnormal{mean = 0, std = 1, lower = 0}
  T.near(tn:mean(), math.sqrt(2 / math.pi), 1e-12, "half-normal mean")
  T.near(tn:std(), math.sqrt(1 - 2 / math.pi), 1e-12, "half-normal std")
  local s = n:sample(1000, 42)
  T.eq(#s, 1000, "sample size")
  T.eq(n:sample(5, 42)[3], n:sample(5, 42)[3], "seeded sample")
end)

T.case("logpdf, logcdf, sf, isf in the tails (SciPy 1.10, tests/reference/families_tails.csv)", function()
  local g = smi.dist.gamma{shape = 2.5, scale = 1.5}
  T.near(g:isf(1e-12) / 48.92897716002588, 1, 1e-9, "gamma isf(1e-12)")
  T.near(g:sf(48.92897716002588) / 9.999999999999994e-13, 1, 1e-9, "gamma sf")
  T.near(g:logcdf(48.92897716002588) / -1.0000000000004994e-12, 1, 1e-9, "gamma logcdf near 1")
  T.near(g:logpdf(48.92897716002588) / -28.082109046025828, 1, 1e-9, "gamma logpdf")
  local t = smi.dist.truncnormal{mean = 0, std = 1, lower = 6}
  T.near(t:isf(1e-12) / 9.50643028070483, 1, 1e-9, "truncnormal [6, inf) isf(1e-12)")
  T.near(smi.dist.beta{alpha = 2, beta = 5}:isf(1e-12) / 0.9972166267363152, 1, 1e-9, "beta isf")
  local n = smi.dist.normal{mean = 1.5, std = 2}
  T.near(n:logcdf(-12.568967650602263) / -27.63102111592854, 1, 1e-9, "normal logcdf")
  local v = n:sf({1.5, 3.5})
  T.near(v[1], 0.5, 1e-15, "sf vec 1")
  T.near(v[2], 0.15865525393145707, 1e-15, "sf vec 2")
  T.raises(function() n:isf(1.5) end, "upper-tail probability must be in [0, 1]")
end)

T.case("fit ranks families by AIC", function()
  local r = smi.dist.fit(X, {"normal", "uniform", "gumbel"})
  T.eq(#r, 3, "three fits")
  T.truthy(r[1].aic <= r[2].aic and r[2].aic <= r[3].aic, "sorted by AIC")
  for _, f in ipairs(r) do
    if f.family == "normal" then
      T.near(f.dist:mean(), 30.2511111, 1e-7, "normal MLE mean")
      T.near(f.dist:std(), 0.3428133, 1e-7, "normal MLE std")
    end
  end
  T.raises(function() smi.dist.fit(X, {"normul"}) end, "unknown family 'normul'")
end)

T.case("distribution constructors read their parameters by their schemas", function()
  T.near(smi.dist.beta{alpha = 2, beta = 2}:cdf(0.5), 0.5, 1e-12, "beta's default [0, 1]")
  T.eq(smi.dist.gamma{shape = 2, rate = 0.5}:mean(), 4, "gamma's rate")
  T.raises(function() smi.dist.normal{mean = 0, sd = 1} end, "smi.dist.normal: unknown option 'sd' (did you mean 'std'?)")
  T.raises(function() smi.dist.normal{mean = 0} end, "missing field 'std' (a number)")
  T.raises(function() smi.dist.normal{mean = 0 / 0, std = 1} end, "smi.dist.normal: mean must be finite, got nan")
  T.raises(function() smi.dist.weibull{shape = 2, scale = 1, loc = "0"} end, "smi.dist.weibull: option 'loc' must be a number, got string")
  T.raises(function() smi.dist.lognormal{mu_log = 1} end, "missing field 'sigma_log'")
end)

T.case("metrics: pr's and intersection's grid options are checked by their schemas", function()
  local a, b = smi.dist.normal{mean = 0, std = 1}, smi.dist.normal{mean = 1, std = 1}
  T.raises(function() smi.metric.pr(a, b, {nodez = 3}) end, "smi.metric.pr: unknown option 'nodez' (did you mean 'nodes'?)")
  T.raises(function() smi.metric.intersection(a, b, {grid = {lowr = 1}}) end,
    "smi.metric.intersection grid: unknown option 'lowr' (did you mean 'lower'?)")
  T.raises(function() smi.metric.pr(a, b, {grid = {lower = "a", upper = 1}}) end, "option 'lower' must be a number, got string")
  T.raises(function() smi.metric.pr(a, b, {grid = 3}) end, "option 'grid' must be a table")
  -- a missing bound is a message naming it (it was a C++ exception escaping the binding: the options table as
  -- the error)
  T.raises(function() smi.metric.pr(a, b, {grid = {lower = -1}}) end, "smi.metric.pr: missing field 'upper' (a number)")
end)

T.case("metrics: pr, area, upool verdicts (spec 8.2, 8.3)", function()
  T.near(smi.metric.pr(smi.dist.normal{mean = 0, std = 1}, smi.dist.normal{mean = 1, std = 1}, {nodes = 20001}),
    0.7658498451, 1e-7, "PR closed form")
  T.near(smi.metric.pr(smi.dist.uniform{lower = 0, upper = 1}, smi.dist.uniform{lower = 2, upper = 3}), 2.0, 1e-3, "disjoint")
  T.near(smi.metric.pr(smi.kde(X, {bandwidth = 0.2481836818}), smi.dist.normal{mean = 30.25, std = 0.36},
    {grid = {lower = 27, upper = 33.5, nodes = 26001}}), 0.2050389, 1e-7, "PR spec")
  T.near(smi.metric.area(smi.dist.normal{mean = 0, std = 1}, smi.dist.normal{mean = 0.5, std = 1}), 0.5, 1e-8, "area shift")
  T.near(smi.metric.area({0}, smi.dist.normal{mean = 0, std = 1}), 0.7978845608, 1e-8, "area point")
  T.near(smi.metric.area({0, 1, 2}, {0.5, 3}), 0.5 / 3 + 0.5 / 6 + 1 / 6 + 0.5, 1e-15, "area steps")
  T.near(smi.metric.area(smi.ecdf({0, 1, 2}), smi.ecdf({0.5, 3})), 0.5 / 3 + 0.5 / 6 + 1 / 6 + 0.5, 1e-15, "ecdf objects")
  local thr = smi.metric.upool_threshold(9, 0.95)
  T.near(thr, 0.1927, 4e-4, "threshold n=9")
  T.near(smi.metric.upool_threshold(1, 0.95), 0.475625, 1e-12, "threshold n=1")
  T.raises(function() smi.metric.upool_threshold(9, 1.5) end, "confidence must be in (0, 1)")
  local v = smi.metric.upool{data = X, predicted = smi.dist.normal{mean = 30.25, std = 0.36}}
  T.near(v.metric, 0.0340603, 1e-7, "U valid")
  T.eq(v.pass, true, "pass")
  T.truthy(v.p > 0.999, "p valid")
  T.near(v.threshold, thr, 0, "threshold in verdict")
  local w = smi.metric.upool{data = X, predicted = smi.dist.normal{mean = 30.6, std = 0.36}}
  T.near(w.metric, 0.2574441, 1e-7, "U invalid")
  T.eq(w.pass, false, "fail")
  T.near(w.p, 0.0064, 4e-4, "p invalid")
  T.truthy(tostring(w):find("INVALID", 1, true), "prints")
  local c = w:curve()
  T.eq(#c.x, 20, "curve points")
  -- Pooling across conditions, each against its own prediction.
  local g = smi.metric.upool{data = {{30.12, 30.45}, {29.88}}, predicted = {smi.dist.normal{mean = 30.25, std = 0.36},
    smi.dist.normal{mean = 30.0, std = 0.2}}}
  T.eq(g.n, 3, "pooled n")
  T.raises(function() smi.metric.upool{data = {{1}, {2}}, predicted = {smi.dist.normal{mean = 0, std = 1}}} end,
    "2 groups but predicted has 1")
end)

T.finish()
