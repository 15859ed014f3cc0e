--- The study's stand-in for smi.calibrate's r.near_optimal (CONTRACT.md, calibration issue 11
-- item 3): calibrations that fit the calibration responses as well as the optimum, within a
-- tolerance, spread along the directions those responses leave undetermined. trial.lua uses it
-- only when smi.calibrate does not return r.near_optimal itself.
--
-- How: at the optimum, the Jacobian J of the calibration responses' summaries (mean and std of
-- modes 1 and 4, in units of the data's std) with respect to the scaled parameters (0..1 over
-- their bounds) spans what the data determine. The directions along which a validation
-- response's summaries change most while J's are unchanged are the gradients of those
-- summaries projected out of J's row space: the weak directions that matter for the prediction.
-- Along each, both ways, points at 1/10, 1/4, 1/2, 3/4 and all of the way to the bounds, each
-- pulled back onto the optimum's calibration summaries by Gauss-Newton steps (the valley curves), kept while the objective stays within `tolerance` of the optimum's. Cost: 2·P + 4
-- propagations for the Jacobians, up to 4·(2·P + 1) + 1 per point (no calibration is rerun).
local M = {}

local function dot(a, b)
  local s = 0
  for i = 1, #a do s = s + a[i] * b[i] end
  return s
end

-- Solves the small symmetric system A x = b (Gaussian elimination, partial pivoting).
local function solve(A, b)
  local n = #b
  local a, x = {}, {}
  for i = 1, n do
    a[i] = {}
    for j = 1, n do a[i][j] = A[i][j] end
    a[i][n + 1] = b[i]
  end
  for c = 1, n do
    local p = c
    for r = c + 1, n do if math.abs(a[r][c]) > math.abs(a[p][c]) then p = r end end
    a[c], a[p] = a[p], a[c]
    for r = c + 1, n do
      local f = a[r][c] / a[c][c]
      for j = c, n + 1 do a[r][j] = a[r][j] - f * a[c][j] end
    end
  end
  for i = n, 1, -1 do
    local s = a[i][n + 1]
    for j = i + 1, n do s = s - a[i][j] * x[j] end
    x[i] = s / a[i][i]
  end
  return x
end

--- t: params ({name, lower, upper} list), optimum ({name = value}), value (objective at the
-- optimum, without prior), objective(th) -> value, predicted(th, modes) -> {mode = vec},
-- tolerance, calibration_modes, validation_modes, data ({mode = vec}).
-- Returns {source, tolerance, points = {optimum, ...}, objectives = {...}, directions = {...}}.
function M.by_weak_directions(t)
  local P = #t.params
  local z0 = {}
  for i, q in ipairs(t.params) do z0[i] = (t.optimum[q.name] - q.lower) / (q.upper - q.lower) end
  local function theta(z)
    local th = {}
    for i, q in ipairs(t.params) do th[q.name] = q.lower + math.min(1, math.max(0, z[i])) * (q.upper - q.lower) end
    return th
  end
  local function summaries(z, modes)
    local Y = t.predicted(theta(z), modes)
    local s = {}
    for _, m in ipairs(modes) do
      local sd = t.data[m]:std()
      s[#s + 1] = Y[m]:mean() / sd
      s[#s + 1] = Y[m]:std() / sd
    end
    return s
  end
  -- Jacobians of the calibration and validation summaries (central differences, one-sided at a bound).
  local all = {}
  for _, m in ipairs(t.calibration_modes) do all[#all + 1] = m end
  for _, m in ipairs(t.validation_modes) do all[#all + 1] = m end
  local nc = 2 * #t.calibration_modes
  local s0 = summaries(z0, all)
  local J = {}
  for r = 1, #s0 do J[r] = {} end
  local h = 0.01
  for j = 1, P do
    local up, dn = {}, {}
    for i = 1, P do up[i], dn[i] = z0[i], z0[i] end
    up[j], dn[j] = math.min(1, z0[j] + h), math.max(0, z0[j] - h)
    local su, sd = summaries(up, all), summaries(dn, all)
    for r = 1, #s0 do J[r][j] = (su[r] - sd[r]) / (up[j] - dn[j]) end
  end
  -- Orthonormal basis of what the calibration responses determine (Gram-Schmidt on J's rows).
  local basis = {}
  for r = 1, nc do
    local v = {}
    for j = 1, P do v[j] = J[r][j] end
    for _, b in ipairs(basis) do local c = dot(v, b) for j = 1, P do v[j] = v[j] - c * b[j] end end
    local n = math.sqrt(dot(v, v))
    if n > 1e-8 * math.sqrt(dot(J[r], J[r])) and n > 0 then for j = 1, P do v[j] = v[j] / n end basis[#basis + 1] = v end
  end
  local directions = {}
  for r = nc + 1, #s0 do
    local v = {}
    for j = 1, P do v[j] = J[r][j] end
    local n0 = math.sqrt(dot(v, v))
    for _, b in ipairs(basis) do local c = dot(v, b) for j = 1, P do v[j] = v[j] - c * b[j] end end
    local n = math.sqrt(dot(v, v))
    if n0 > 0 and n > 1e-3 * n0 then
      for j = 1, P do v[j] = v[j] / n end
      basis[#basis + 1] = v -- the next direction is orthogonal to this one too
      directions[#directions + 1] = { v = v, summary = r, free_share = n / n0 }
    end
  end
  -- Pull a point back onto the optimum's calibration summaries: Gauss-Newton steps
-- z -= Jc^T (Jc Jc^T + mu I)^-1 r with Jc re-evaluated at the current point (the valley curves:
  -- the bracket's stiffness goes with its thickness cubed), up to 4 steps.
  local function jac_calib(z)
    local Jc = {}
    for a = 1, nc do Jc[a] = {} end
    for j = 1, P do
      local up, dn = {}, {}
      for i = 1, P do up[i], dn[i] = z[i], z[i] end
      up[j], dn[j] = math.min(1, z[j] + h), math.max(0, z[j] - h)
      local su, sd = summaries(up, t.calibration_modes), summaries(dn, t.calibration_modes)
      for a = 1, nc do Jc[a][j] = (su[a] - sd[a]) / (up[j] - dn[j]) end
    end
    return Jc
  end
  local function correct(z)
    for _ = 1, 4 do
      local s = summaries(z, t.calibration_modes)
      local res, size = {}, 0
      for a = 1, nc do res[a] = s[a] - s0[a]; size = math.max(size, math.abs(res[a])) end
      if size < 0.02 then break end -- within 2 % of the data's std
      local Jc = jac_calib(z)
      local JJ, tr = {}, 0
      for a = 1, nc do
        JJ[a] = {}
        for b = 1, nc do JJ[a][b] = dot(Jc[a], Jc[b]) end
        tr = tr + JJ[a][a]
      end
      for a = 1, nc do JJ[a][a] = JJ[a][a] + 1e-8 * tr end
      local y = solve(JJ, res)
      for j = 1, P do
        local d = 0
        for a = 1, nc do d = d + Jc[a][j] * y[a] end
        z[j] = math.min(1, math.max(0, z[j] - d))
      end
    end
    return z
  end
  local points, objectives = { t.optimum }, { t.value }
  local out_dirs = {}
  for _, d in ipairs(directions) do
    local loadings = {}
    for j, q in ipairs(t.params) do loadings[q.name] = d.v[j] end
    local reach = {}
    for _, sign in ipairs{ 1, -1 } do
      -- the direction with the components that would push a parameter sitting on its bound
      -- out of the box dropped (else the walk could not start), then the distance to the box
      local v = {}
      for j = 1, P do
        v[j] = sign * d.v[j]
        if (z0[j] >= 1 - 1e-9 and v[j] > 0) or (z0[j] <= 1e-9 and v[j] < 0) then v[j] = 0 end
      end
      local tmax = math.huge
      for j = 1, P do
        if v[j] > 1e-12 then tmax = math.min(tmax, (1 - z0[j]) / v[j]) elseif v[j] < -1e-12 then tmax = math.min(tmax, -z0[j] / v[j]) end
      end
      if tmax == math.huge then tmax = 0 end
      local kept = 0
      for _, frac in ipairs(tmax > 0 and { 0.1, 0.25, 0.5, 0.75, 1 } or {}) do
        local z = {}
        for j = 1, P do z[j] = z0[j] + frac * tmax * v[j] end
        z = correct(z)
        local th = theta(z)
        local f = t.objective(th)
        if f - t.value > t.tolerance then break end
        points[#points + 1], objectives[#objectives + 1] = th, f
        kept = frac
      end
      reach[#reach + 1] = kept
    end
    out_dirs[#out_dirs + 1] = { loadings = loadings, free_share = d.free_share, reached = reach,
                                drives = (d.summary - nc) % 2 == 1 and "mean" or "std" }
  end
  return { source = "study stand-in (near_optimal.lua): points along the weak directions, corrected onto the calibration summaries",
           tolerance = t.tolerance, points = points, objectives = objectives, directions = out_dirs }
end

return M
