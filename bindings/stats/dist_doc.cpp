// SPDX-License-Identifier: MIT
// Reference texts of smi.dist (constructors in dist_lua.cpp, methods in dist_box.cpp); the
// constructors' option lists come from their schemas (dist_options.cpp).
#include "bindings/doc.hpp"
#include "bindings/stats/dist_options.hpp"
#include "platform/core/defaults.hpp"

namespace smi::bind {

// long: one raw string of reference text (data, no logic); doc.lua reads it entry by entry
DocText doc_stats_dist() {
  return {"bindings/stats/dist_doc.cpp", fill(R"DOC(
@ module smi.dist
Probability distributions by the variable's own mean and std where the paper's tables give them
(normal, lognormal, uniform), and by their usual parameters (truncnormal, weibull, gumbel, gamma,
beta, triangular); every one has the methods smi.dist:* (pdf, cdf, quantile, sample, ...).

@ smi.dist.normal{mean =, std =} -> dist
The normal distribution.
options:
${normal_options}
returns: a dist (d.family = "normal", d.mean, d.std)
errors: a missing or non-finite parameter; std <= 0; an unknown option (the closest name is suggested)
example:
  local d = smi.dist.normal{mean = 30.25, std = 0.36}
  print(d, d:cdf(30.25))

@ smi.dist.lognormal{mean =, std =} -> dist
The lognormal distribution given by the variable's own mean and std (as the paper's tables), or
by the parameters of its logarithm.
options:
${lognormal_options}
returns: a dist (d.family = "lognormal")
errors: neither pair given; mean <= 0 or std <= 0
example:
  local d = smi.dist.lognormal{mean = 2, std = 0.5}
  print(d, d:mean(), d:std())

@ smi.dist.uniform{lower =, upper =} -> dist
The uniform distribution on [lower, upper], or given by its mean and std.
options:
${uniform_options}
returns: a dist (d.family = "uniform")
errors: lower >= upper; neither pair given
example:
  print(smi.dist.uniform{mean = 1, std = 0.1})

@ smi.dist.truncnormal{mean =, std =, lower =, upper =} -> dist
A normal distribution truncated to [lower, upper] (mean and std are those of the parent normal).
options:
${truncnormal_options}
returns: a dist (d.family = "truncnormal")
errors: std <= 0; lower >= upper; bounds holding no probability mass
example:
  print(smi.dist.truncnormal{mean = 0, std = 1, lower = 0}:mean())

@ smi.dist.weibull{shape =, scale =} -> dist
The Weibull distribution.
options:
${weibull_options}
returns: a dist (d.family = "weibull")
errors: shape or scale <= 0
example:
  print(smi.dist.weibull{shape = 2, scale = 1}:quantile(0.5))

@ smi.dist.gumbel{loc =, scale =} -> dist
The Gumbel (largest extreme value) distribution.
options:
${gumbel_options}
returns: a dist (d.family = "gumbel")
errors: scale <= 0
example:
  print(smi.dist.gumbel{loc = 0, scale = 1}:mean())

@ smi.dist.gamma{shape =, scale = | rate =} -> dist
The gamma distribution.
options:
${gamma_options}
returns: a dist (d.family = "gamma")
errors: shape, scale or rate <= 0; neither scale nor rate
example:
  print(smi.dist.gamma{shape = 2, rate = 1}:mean())

@ smi.dist.beta{alpha =, beta =} -> dist
The beta distribution on [lower, upper].
options:
${beta_options}
returns: a dist (d.family = "beta")
errors: alpha or beta <= 0; lower >= upper
example:
  print(smi.dist.beta{alpha = 2, beta = 2}:cdf(0.5))

@ smi.dist.triangular{lower =, mode =, upper =} -> dist
The triangular distribution.
options:
${triangular_options}
returns: a dist (d.family = "triangular")
errors: not lower <= mode <= upper with lower < upper
example:
  print(smi.dist.triangular{lower = 0, mode = 1, upper = 3}:mean())

@ smi.dist.fit(data [, families]) -> ranked
Fits each family by maximum likelihood and ranks them by AIC, with BIC and the Kolmogorov-Smirnov
statistic for each.
families is a list of names, default {"normal", "lognormal", "uniform", "weibull", "gumbel", "gamma"}.
returns: a list, best first, of {family =, dist =, loglik =, aic =, bic =, ks =, k =, rank =};
  ranked.best is the first dist
errors: fewer than 2 data; a family name not known; data a family cannot hold (lognormal with a
  value <= 0), named with the family
example:
  local r = smi.dist.fit(smi.vec{1.2, 2.3, 1.9, 2.8, 2.2, 1.7, 2.5}, {"normal", "lognormal"})
  print(r[1].family, r.best, r[1].aic < r[2].aic)

@ smi.dist:pdf(x) -> number | vec
The probability density at x (a number, or a vec/table of points evaluated in C++ at once).
returns: a number, or a vec of the same length as x
errors: x holds something that is not a number
example:
  print(smi.dist.normal{mean = 0, std = 1}:pdf{0, 1})

@ smi.dist:cdf(x) -> number | vec
The cumulative probability P(X <= x).
returns: a number, or a vec
errors: x holds something that is not a number
example:
  print(smi.dist.normal{mean = 0, std = 1}:cdf(1.644853627))

@ smi.dist:quantile(p) -> number | vec
The inverse CDF at the probabilities p.
returns: a number, or a vec
errors: a probability outside [0, 1]
example:
  print(smi.dist.normal{mean = 0, std = 1}:quantile{0.05, 0.95})

@ smi.dist:logpdf(x) -> number | vec
The natural logarithm of the density, computed in log space (finite where the pdf underflows;
-inf outside the support).
returns: a number, or a vec
errors: x holds something that is not a number
example:
  print(smi.dist.normal{mean = 0, std = 1}:logpdf(40))

@ smi.dist:logcdf(x) -> number | vec
The natural logarithm of P(X <= x), accurate far in the lower tail (no underflow to -inf).
returns: a number, or a vec
errors: x holds something that is not a number
example:
  print(smi.dist.normal{mean = 0, std = 1}:logcdf(-40))

@ smi.dist:sf(x) -> number | vec
The survival function P(X > x), computed as a complement in the upper tail (not 1 - cdf), so it
keeps its relative accuracy down to 1e-300.
returns: a number, or a vec
errors: x holds something that is not a number
example:
  print(smi.dist.truncnormal{mean = 0, std = 1, lower = 6}:sf(7))

@ smi.dist:isf(q) -> number | vec
The inverse survival function: the x with P(X > x) = q, solved on sf, so upper-tail quantiles
(q = 1e-12) are as accurate as lower-tail ones.
returns: a number, or a vec
errors: a probability outside [0, 1]
example:
  print(smi.dist.normal{mean = 0, std = 1}:isf(0.05))

@ smi.dist:sample(n, seed | rng) -> vec
n draws. The generator is explicit: an integer seed or an smi.rng (same seed, same numbers).
returns: a vec of n numbers
errors: n < 0; the third argument neither an integer nor an smi.rng
example:
  print(smi.dist.uniform{lower = 0, upper = 1}:sample(3, 42))

@ smi.dist:mean() -> number
The mean of the distribution (of a KDE: the data mean).
returns: a number
errors: none
example:
  print(smi.dist.gamma{shape = 3, scale = 2}:mean())

@ smi.dist:std() -> number
The standard deviation of the distribution.
returns: a number
errors: none
example:
  print(smi.dist.uniform{lower = 0, upper = 1}:std())

@ smi.dist:support() -> lower, upper
The interval holding all the probability (-inf/inf when unbounded).
returns: two numbers
errors: none
example:
  print(smi.dist.beta{alpha = 2, beta = 3}:support())

@ smi.dist:curve([n]) -> {x =, pdf =, cdf =}
Plot series over the bulk of the distribution: n points (default ${curve_points}) from the 1e-4 to the
1 - 1e-4 quantile (the finite ends of the support; for a KDE the data range +- 4 bandwidths).
An ECDF gives its steps {x =, cdf =} instead.
returns: a table of vecs
errors: n outside 2..1e7
example:
  local c = smi.dist.normal{mean = 0, std = 1}:curve(5)
  print(c.x, c.pdf)
)DOC", {{"curve_points", num(kDefaultCurvePoints)},
        {"normal_options", stats::normal_schema().doc()},
        {"lognormal_options", stats::lognormal_schema().doc()},
        {"uniform_options", stats::uniform_schema().doc()},
        {"truncnormal_options", stats::truncnormal_schema().doc()},
        {"weibull_options", stats::weibull_schema().doc()},
        {"gumbel_options", stats::gumbel_schema().doc()},
        {"gamma_options", stats::gamma_schema().doc()},
        {"beta_options", stats::beta_schema().doc()},
        {"triangular_options", stats::triangular_schema().doc()}})};
}

}  // namespace smi::bind
