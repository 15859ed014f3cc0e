-- SPDX-License-Identifier: MIT
--- The points of the validation's solver check: n points of the calibrated
-- distributions, stratified: a maximin Latin hypercube in probability space mapped through each
-- input's quantile function. Every input's marginal is covered evenly, tails included, so 40
-- such points check the Kriging where the calibrated model puts its mass about as well as a few
-- hundred plain Monte Carlo draws (the sample the check used before).
-- dists: {{name, smi.dist}, ...} (trial.distributions); returns an n x #dists smi.mat.
return function(dists, n, seed)
  local box = {}
  for i = 1, #dists do box[i] = { 0, 1 } end
  local U = smi.doe.lhs(n, box, { seed = seed, criterion = "maximin" })
  local X = smi.mat.zeros(n, #dists)
  for j, d in ipairs(dists) do X:set_col(j, d[2]:quantile(U:col(j))) end
  return X
end
