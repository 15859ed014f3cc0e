--- smi.improve.declare: checks a study's declaration (IMPROVE_API.md, docs/new-product.md) and
-- fills its defaults, so that every later step reads plain, complete data. A mistake is an error
-- that names the field and the response, unknown or candidate it belongs to, with the fix
-- (a misspelt field gets the closest known name).
local M = {}

local TOP = { name = true, title = true, subtitle = true, author = true, data = true, responses = true,
              unknowns = true, form = true, design = true, model = true, candidates = true, weights = true,
              criteria = true, limits = true, screening = true, sections = true, trial_fields = true,
              accept_units = true, options = true }
local RESPONSE = { name = true, column = true, unit = true, role = true, title = true, plausible = true,
                   grid_margin = true }
local UNKNOWN = { name = true, dist = true, mean = true, std = true, unit = true }
local CANDIDATE = { name = true, short = true, implement_minutes = true, why = true, revision = true }
local REVISION = { form = true, unknowns = true, fixed = true, n_design = true, trend = true }
local DESIGN = { n = true, trend = true, test_points = true, solver_check = true }
local LIMITS = { refinements = true, runs = true }
local SCREENING = { inputs = true, runs = true, n = true, rule = true, note = true }
local WEIGHTS = { correctness = true, robustness = true, computational = true, implementation = true }

local function distance(a, b)
  local d = {}
  for i = 0, #a do d[i] = { [0] = i } end
  for j = 0, #b do d[0][j] = j end
  for i = 1, #a do
    for j = 1, #b do
      d[i][j] = math.min(d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a:sub(i, i) == b:sub(j, j) and 0 or 1))
    end
  end
  return d[#a][#b]
end

local function fail(where, fmt, ...)
  error(("smi.improve: %s: " .. fmt):format(where, ...), 0)
end

--- Every key of t must be in known; else an error naming it and the closest known key.
local function only(t, known, where)
  -- in name order, so that of several unknown fields (and of equally close known ones) the one
  -- named is the same every run (pairs() order changes from process to process)
  local keys = {}
  for k in pairs(t) do if type(k) == "string" then keys[#keys + 1] = k end end
  table.sort(keys)
  for _, k in ipairs(keys) do
    if not known[k] then
      local names = {}
      for name in pairs(known) do names[#names + 1] = name end
      table.sort(names)
      local best, bd = nil, math.huge
      for _, name in ipairs(names) do
        local d = distance(k, name)
        if d < bd then best, bd = name, d end
      end
      fail(where, "unknown field '%s'%s (fields: %s)", k,
        bd <= math.max(2, #k // 3) and (" (did you mean '" .. best .. "'?)") or "", table.concat(names, ", "))
    end
  end
end

local function need(v, kind, where, field)
  if type(v) ~= kind then fail(where, "field '%s' must be a %s (got %s)", field, kind, type(v)) end
  return v
end

local function bounds(b, where, field)
  if type(b) ~= "table" or type(b[1]) ~= "number" or type(b[2]) ~= "number" or type(b[3]) ~= "number"
     or not (b[1] < b[2] and b[1] <= b[3] and b[3] <= b[2]) then
    fail(where, "field '%s' must be {lower, upper, start} with lower <= start <= upper and lower < upper", field)
  end
end

--- An unknown's declaration, checked ({name, dist, mean, std, unit}); returns a plain copy.
function M.unknown(u, where)
  need(u, "table", where, "unknown")
  only(u, UNKNOWN, where)
  need(u.name, "string", where, "name")
  where = ("%s '%s'"):format(where, u.name)
  need(u.dist, "string", where, "dist")
  if not smi.dist[u.dist] then fail(where, "field 'dist': '%s' is not an smi.dist family", u.dist) end
  bounds(u.mean, where, "mean")
  bounds(u.std, where, "std")
  return { dist = u.dist, mean = { u.mean[1], u.mean[2], u.mean[3] }, std = { u.std[1], u.std[2], u.std[3] },
           unit = u.unit or "" }
end

local function responses(list)
  need(list, "table", "declaration", "responses")
  local out, seen, calibrate = {}, {}, 0
  for i, r in ipairs(list) do
    local where = ("response %d"):format(i)
    need(r, "table", where, "response")
    only(r, RESPONSE, where)
    need(r.name, "string", where, "name")
    where = ("response '%s'"):format(r.name)
    if seen[r.name] then fail(where, "declared twice") end
    seen[r.name] = true
    local role = r.role or "calibrate"
    if role ~= "calibrate" and role ~= "validate" then
      fail(where, "field 'role' must be \"calibrate\" or \"validate\" (got %s)", tostring(role))
    end
    if role == "calibrate" then calibrate = calibrate + 1 end
    if r.plausible ~= nil and (type(r.plausible) ~= "table" or not (r.plausible[1] < r.plausible[2])) then
      fail(where, "field 'plausible' must be {lower, upper} with lower < upper")
    end
    out[i] = { name = r.name, column = r.column or r.name, unit = r.unit or "", role = role,
               title = r.title or r.name, plausible = r.plausible, grid_margin = r.grid_margin }
  end
  if calibrate == 0 then fail("declaration", "field 'responses': at least one response needs role = \"calibrate\"") end
  return out
end

local function candidates(list, specs)
  local out, seen = {}, {}
  for i, c in ipairs(list or {}) do
    local where = ("candidate %d"):format(i)
    need(c, "table", where, "candidate")
    only(c, CANDIDATE, where)
    need(c.name, "string", where, "name")
    where = ("candidate '%s'"):format(c.name)
    if seen[c.name] then fail(where, "declared twice") end
    seen[c.name] = true
    need(c.implement_minutes, "number", where, "implement_minutes")
    local r = c.revision or {}
    need(r, "table", where, "revision")
    only(r, REVISION, where .. ", revision")
    local rev = { form = r.form or {}, fixed = r.fixed or {}, unknowns = {}, specs = {}, n_design = r.n_design,
                  trend = r.trend }
    for j, u in ipairs(r.unknowns or {}) do
      local spec = M.unknown(u, ("%s, revision.unknowns[%d]"):format(where, j))
      if specs[u.name] then fail(where, "revision.unknowns: '%s' is already an unknown of the model", u.name) end
      if rev.fixed[u.name] ~= nil then fail(where, "revision both fixes and calibrates '%s'", u.name) end
      rev.unknowns[j], rev.specs[u.name] = u.name, spec
    end
    out[i] = { name = c.name, short = c.short or c.name, implement_minutes = c.implement_minutes, why = c.why,
               revision = rev, new_inputs = #rev.unknowns }
  end
  return out
end

--- The declaration checked and completed: responses (list, plus .calibrate and .validate name
-- lists and .by_name), unknowns (names) and specs, candidates, design, limits, weights.
function M.check(d)
  need(d, "table", "smi.improve.run", "declaration")
  only(d, TOP, "declaration")
  need(d.name, "string", "declaration", "name")
  need(d.model, "function", "declaration", "model")
  local D = { name = d.name, title = d.title, subtitle = d.subtitle, author = d.author, data = d.data,
              model = d.model, form = d.form or {}, criteria = d.criteria, sections = d.sections or {},
              trial_fields = d.trial_fields, accept_units = d.accept_units == true, options = d.options or {} }
  D.responses = responses(d.responses)
  D.calibrate, D.validate, D.by_name, D.names = {}, {}, {}, {}
  for i, r in ipairs(D.responses) do
    D.by_name[r.name], D.names[i] = r, r.name
    local list = r.role == "calibrate" and D.calibrate or D.validate
    list[#list + 1] = r.name
  end
  need(d.unknowns, "table", "declaration", "unknowns")
  D.unknowns, D.specs = {}, {}
  for i, u in ipairs(d.unknowns) do
    D.specs[u.name or i] = M.unknown(u, ("unknown %d"):format(i))
    D.unknowns[i] = u.name
  end
  if #D.unknowns == 0 then fail("declaration", "field 'unknowns': declare at least one unknown") end
  D.candidates = candidates(d.candidates, D.specs)
  local g = d.design or {}
  only(g, DESIGN, "declaration, design")
  D.design = { n = g.n or 10 * #D.unknowns, trend = g.trend or "linear", test_points = g.test_points or 20,
               solver_check = g.solver_check or 40 }
  local l = d.limits or {}
  only(l, LIMITS, "declaration, limits")
  D.limits = { refinements = l.refinements or 2, runs = l.runs }
  local w = d.weights or {}
  only(w, WEIGHTS, "declaration, weights")
  D.weights = { correctness = w.correctness or 0.4, robustness = w.robustness or 0.2,
                computational = w.computational or 0.2, implementation = w.implementation or 0.2 }
  if d.screening then
    only(d.screening, SCREENING, "declaration, screening")
    need(d.screening.inputs, "table", "declaration, screening", "inputs")
    D.screening = d.screening
  end
  return D
end

--- The model's outputs against the declared responses: a response the model does not give is
-- an error naming it (and the factory's candidate).
function M.outputs(D, model, who)
  local have = {}
  for _, o in ipairs(model.outputs or {}) do have[o] = true end
  for _, r in ipairs(D.responses) do
    if not have[r.name] then
      fail(who, "response '%s' is declared (and in the data) but the model's outputs are {%s}: name the output"
        .. " '%s' in the factory or fix the response's name", r.name, table.concat(model.outputs or {}, ", "), r.name)
    end
  end
end

return M
