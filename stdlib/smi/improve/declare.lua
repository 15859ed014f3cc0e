-- SPDX-License-Identifier: MIT
--- smi.improve.declare: the declaration schema of a study and its check. One table (FIELDS) holds
-- every field of every part of a declaration: its type, its default and the line that documents
-- it. The check, the defaults, the "did you mean" of a misspelt field (smi._closest, the one
-- routine the C++ option schemas use too) and the reference (`smi-lua doc
-- smi.improve.declaration`) all come from it, so a new field is one row here.
-- Beyond the table: the few checks that relate fields (bounds, roles, a revision's unknowns).
local doc = require "smi.doc"

local M = {}

-- Each part: an ordered list of {key, type, default, doc}. type: a Lua type name, "bounds"
-- ({lower, upper, start}), "pair" ({lower, upper}), "list" (a table read as a list) or "any".
-- A default that is a function is called with the part's checked fields (and the declaration).
local FIELDS = {
  declaration = {
    { "name", "string", nil, "the study's name: its output folder and file names (required)" },
    { "title", "string", nil, "the report's title (default: the name)" },
    { "subtitle", "string", "", "the report's subtitle" },
    { "author", "string", "smi.improve", "the report's author line" },
    { "data", "string", nil, "the measurements' CSV file (the default of --data)" },
    { "responses", "list", nil, "the measured responses (required; see response)" },
    { "unknowns", "list", nil, "the unknowns whose distribution parameters are calibrated (required; see unknown)" },
    { "form", "table", {}, "the initial model's form switches, handed to the model factory" },
    { "design", "table", {}, "the trials' Kriging designs (see design)" },
    { "model", "function", nil, "the model factory: function(applied, unknowns, ctx) -> smi.model (required)" },
    { "candidates", "list", {}, "the refinement candidates (see candidate)" },
    { "weights", "table", {}, "the decision matrix's weights (see weights)" },
    { "criteria", "function", nil, "function(opts) -> criteria for smi.refine.decision_matrix (default: the paper's four)" },
    { "limits", "table", {}, "the study's limits (see limits)" },
    { "screening", "table", nil, "the optional screening step (see screening)" },
    { "sections", "table", {}, "hooks {data, calibration, summary} adding to a step's result and report section" },
    { "trial_fields", "function", nil, "function(model, responses) -> more keys of each conclusion.trials entry" },
    { "accept_units", "boolean", false, "go on when the data's magnitudes look like a units mistake" },
    { "options", "list", {}, "the study's own command-line options (smi.options declarations)" },
    { "evidence", "table", {}, "the comparison of the tried forms by their Bayes factors (see evidence)" },
  },
  response = {
    { "name", "string", nil, "the response's name: a model output (required)" },
    { "column", "string", function(r) return r.name end, "the data file's column (default: the name)" },
    { "unit", "string", "", "the unit, for tables and axes" },
    { "role", "string", "calibrate", "\"calibrate\" (used by the calibration) or \"validate\" (kept for validation)" },
    { "title", "string", function(r) return r.name end, "the response's name in words (default: the name)" },
    { "plausible", "pair", nil, "{lower, upper}: data outside it stop the study as a likely units mistake" },
    { "grid_margin", "number", nil, "the probability residual's grid: the data's range ± this (default 10 data stds)" },
  },
  unknown = {
    { "name", "string", nil, "the unknown's name: a model input (required)" },
    { "dist", "string", nil, "its smi.dist family (required)" },
    { "mean", "bounds", nil, "{lower, upper, start} of its mean (required)" },
    { "std", "bounds", nil, "{lower, upper, start} of its standard deviation (required)" },
    { "unit", "string", "", "the unit, for tables" },
    { "prior", "table", nil, "prior knowledge of its distribution parameters: {mean = P, std = P} with each"
      .. " P = {dist = \"normal\"|\"lognormal\", mean =, std =} (default: uniform on the range)" },
  },
  prior = {
    { "dist", "string", "normal", "\"normal\" or \"lognormal\" (of the parameter itself)" },
    { "mean", "number", nil, "the prior's mean (required)" },
    { "std", "number", nil, "the prior's standard deviation, > 0 (required)" },
  },
  candidate = {
    { "name", "string", nil, "the candidate's name (required)" },
    { "short", "string", function(c) return c.name end, "a short name for file names (default: the name)" },
    { "implement_minutes", "number", nil, "the analyst's estimate of the time to implement it (required)" },
    { "why", "string", nil, "why it is a candidate, for the report" },
    { "revision", "table", {}, "what it changes (see revision)" },
  },
  revision = {
    { "form", "table", {}, "form switches it sets" },
    { "unknowns", "list", {}, "unknowns it adds (each as an unknown)" },
    { "fixed", "table", {}, "inputs it fixes {input = value}" },
    { "n_design", "number", nil, "the Kriging design's size of its trials" },
    { "trend", "string", nil, "the Kriging trend of its trials" },
  },
  design = {
    { "n", "number", function(_, d) return 10 * #d.unknowns end, "points of a trial's Kriging design (default 10 per unknown)" },
    { "trend", "string", "linear", "the Kriging trend" },
    { "test_points", "number", 20, "independent test points of each Kriging" },
    { "solver_check", "number", 40, "points of the validation's solver check" },
  },
  limits = {
    { "refinements", "number", nil, "how many refinements (revised trials) to try after a trial that is not valid,"
      .. " or that an alternative form beats (default: one more than the candidates, so that every candidate can"
      .. " be tried and one applied too early taken back)" },
    { "runs", "number", nil, "the most solver runs the plan may need" },
  },
  screening = {
    { "inputs", "list", nil, "the screened inputs: smi.screen's inputs list (required)" },
    { "runs", "number", 300, "solver runs of the surrogate screening" },
    { "n", "number", nil, "unused by the study; kept for the screening's own use" },
    { "rule", "function", nil, "function(screening result) -> the unknowns of trial 1" },
    { "note", "function", nil, "function(screening result) -> words, kind: a callout in the report" },
  },
  weights = {
    { "correctness", "number", 0.4, "weight of correctness (eq. 13)" },
    { "robustness", "number", 0.2, "weight of robustness (new unknowns)" },
    { "computational", "number", 0.2, "weight of computational cost" },
    { "implementation", "number", 0.2, "weight of implementation cost" },
  },
  evidence = {
    { "margin", "number", 3, "the Bayes factor by which the chosen form must beat every other tried form"
      .. " (3: \"positive\" evidence, Kass & Raftery 1995)" },
    { "alternatives", "boolean", true, "after a trial that fits, compare it with the forms one untried candidate"
      .. " away by their evidence (a design each); false: compare only the trials run" },
    { "n", "number", 500, "propagated samples per likelihood value of a trial's evidence (smi.calibrate_bayes n)" },
    { "samples", "number", 500, "particles of the evidence's sampler (smi.calibrate_bayes samples)" },
  },
}
M.FIELDS = FIELDS

local function fail(where, fmt, ...)
  error(("smi.improve: %s: " .. fmt):format(where, ...), 0)
end

local function keys_of(part)
  local names = {}
  for i, f in ipairs(FIELDS[part]) do names[i] = f[1] end
  return names
end

--- Every string key of t must be a field of the part; else an error naming it and the closest
-- field (smi._closest). Keys in name order: of several unknown fields the one named is the same
-- every run (pairs() order changes from process to process).
local function only(t, part, where)
  local known, names = {}, keys_of(part)
  for _, n in ipairs(names) do known[n] = true end
  local keys = {}
  for k in pairs(t) do if type(k) == "string" then keys[#keys + 1] = k end end
  table.sort(keys)
  for _, k in ipairs(keys) do
    if not known[k] then
      local near = smi._closest(k, names, 1)
      table.sort(names)
      fail(where, "unknown field '%s'%s (fields: %s)", k, near[1] and (" (did you mean '" .. near[1] .. "'?)") or "",
        table.concat(names, ", "))
    end
  end
end

local function need(v, kind, where, field)
  if type(v) ~= kind then fail(where, "field '%s' must be a %s (got %s)", field, kind, type(v)) end
  return v
end

local SHAPE = {
  bounds = function(b) return type(b) == "table" and type(b[1]) == "number" and type(b[2]) == "number"
    and type(b[3]) == "number" and b[1] < b[2] and b[1] <= b[3] and b[3] <= b[2] end,
  pair = function(b) return type(b) == "table" and type(b[1]) == "number" and type(b[2]) == "number" and b[1] < b[2] end,
  list = function(v) return type(v) == "table" end,
  any = function() return true end,
}
local SHAPE_WORDS = { bounds = "{lower, upper, start} with lower <= start <= upper and lower < upper",
                      pair = "{lower, upper} with lower < upper", list = "list" }

--- The part's fields of t checked against the schema (known keys, types, required ones) and
-- completed with their defaults: a plain copy (tables by reference). top: the declaration, for
-- defaults that depend on it.
function M.part(t, part, where, top)
  need(t, "table", where, part)
  only(t, part, where)
  local out = {}
  for _, f in ipairs(FIELDS[part]) do
    local key, kind, default = f[1], f[2], f[3]
    local v = t[key]
    if v == nil then
      if f[4]:find("(required)", 1, true) then fail(where, "field '%s' must be a %s (got nil)", key, SHAPE[kind] and SHAPE_WORDS[kind] or kind) end
      if type(default) == "function" then v = default(out, top)
      elseif type(default) == "table" then v = {} else v = default end
    elseif SHAPE[kind] then
      if not SHAPE[kind](v) then fail(where, "field '%s' must be %s", key, SHAPE_WORDS[kind]) end
    elseif type(v) ~= kind then
      fail(where, "field '%s' must be a %s (got %s)", key, kind, type(v))
    end
    out[key] = v
  end
  return out
end
local part = M.part

-- A declared prior on one distribution parameter, checked ({dist, mean, std}).
local function prior_of(p, where)
  local q = part(p, "prior", where)
  if q.dist ~= "normal" and q.dist ~= "lognormal" then
    fail(where, "field 'dist' must be \"normal\" or \"lognormal\" (got %s)", tostring(q.dist))
  end
  if not (q.std > 0) then fail(where, "field 'std' must be > 0 (got %s)", tostring(q.std)) end
  if q.dist == "lognormal" and not (q.mean > 0) then fail(where, "a lognormal prior needs mean > 0 (got %s)", tostring(q.mean)) end
  return q
end

--- An unknown's declaration, checked ({name, dist, mean, std, unit, prior}); returns a plain copy
-- (prior: {mean = P, std = P} with the declared ones, nil without any).
function M.unknown(u, where)
  need(u, "table", where, "unknown")
  need(u.name, "string", where, "name")
  where = ("%s '%s'"):format(where, u.name)
  local x = part(u, "unknown", where)
  if not smi.dist[x.dist] then fail(where, "field 'dist': '%s' is not an smi.dist family", x.dist) end
  local out = { dist = x.dist, mean = { x.mean[1], x.mean[2], x.mean[3] }, std = { x.std[1], x.std[2], x.std[3] },
                unit = x.unit }
  if x.prior then
    for k in pairs(x.prior) do
      if k ~= "mean" and k ~= "std" then
        fail(where, "field 'prior': unknown key '%s'; give prior = {mean = {dist =, mean =, std =}, std = {...}}", tostring(k))
      end
    end
    out.prior = {}
    for _, k in ipairs{ "mean", "std" } do
      if x.prior[k] then out.prior[k] = prior_of(x.prior[k], where .. ", prior." .. k) end
    end
  end
  return out
end

-- The entries of a named list (responses, candidates) checked as `kind`: each entry's checked
-- fields and the words that name it; a name declared twice is an error.
local function named(list, kind)
  local out, seen = {}, {}
  for i, e in ipairs(list) do
    need(e, "table", ("%s %d"):format(kind, i), kind)
    local where = type(e.name) == "string" and ("%s '%s'"):format(kind, e.name) or ("%s %d"):format(kind, i)
    local x = part(e, kind, where)
    if seen[x.name] then fail(where, "declared twice") end
    seen[x.name] = true
    out[i] = { fields = x, where = where }
  end
  return out
end

local function responses(list)
  local out, calibrate = {}, 0
  for i, e in ipairs(named(list, "response")) do
    local x = e.fields
    if x.role ~= "calibrate" and x.role ~= "validate" then
      fail(e.where, "field 'role' must be \"calibrate\" or \"validate\" (got %s)", tostring(x.role))
    end
    if x.role == "calibrate" then calibrate = calibrate + 1 end
    out[i] = x
  end
  if calibrate == 0 then fail("declaration", "field 'responses': at least one response needs role = \"calibrate\"") end
  return out
end

local function candidates(list, specs)
  local out = {}
  for i, e in ipairs(named(list, "candidate")) do
    local x, where = e.fields, e.where
    local r = part(x.revision, "revision", where .. ", revision")
    local rev = { form = r.form, fixed = r.fixed, unknowns = {}, specs = {}, n_design = r.n_design, trend = r.trend }
    for j, u in ipairs(r.unknowns) do
      local spec = M.unknown(u, ("%s, revision.unknowns[%d]"):format(where, j))
      if specs[u.name] then fail(where, "revision.unknowns: '%s' is already an unknown of the model", u.name) end
      if rev.fixed[u.name] ~= nil then fail(where, "revision both fixes and calibrates '%s'", u.name) end
      rev.unknowns[j], rev.specs[u.name] = u.name, spec
    end
    out[i] = { name = x.name, short = x.short, implement_minutes = x.implement_minutes, why = x.why,
               revision = rev, new_inputs = #rev.unknowns }
  end
  return out
end

--- The declaration checked and completed: every field of FIELDS.declaration with its default,
-- responses (list, plus .calibrate and .validate name lists, .names and .by_name), unknowns
-- (names) and specs, candidates, design, limits, weights, evidence.
function M.check(d)
  need(d, "table", "smi.improve.run", "declaration")
  local D = part(d, "declaration", "declaration")
  D.responses = responses(D.responses)
  D.calibrate, D.validate, D.by_name, D.names = {}, {}, {}, {}
  for i, r in ipairs(D.responses) do
    D.by_name[r.name], D.names[i] = r, r.name
    local list = r.role == "calibrate" and D.calibrate or D.validate
    list[#list + 1] = r.name
  end
  local list = D.unknowns
  D.unknowns, D.specs = {}, {}
  for i, u in ipairs(list) do
    D.specs[u.name or i] = M.unknown(u, ("unknown %d"):format(i))
    D.unknowns[i] = u.name
  end
  if #D.unknowns == 0 then fail("declaration", "field 'unknowns': declare at least one unknown") end
  D.candidates = candidates(D.candidates, D.specs)
  D.design = part(D.design, "design", "declaration, design", D)
  D.limits = part(D.limits, "limits", "declaration, limits")
  D.limits.refinements = D.limits.refinements or (#D.candidates + 1)
  D.weights = part(D.weights, "weights", "declaration, weights")
  D.evidence = part(D.evidence, "evidence", "declaration, evidence")
  if not (D.evidence.margin >= 1) then
    fail("declaration, evidence", "field 'margin' must be a Bayes factor >= 1 (got %s)", tostring(D.evidence.margin))
  end
  if D.screening then D.screening = part(D.screening, "screening", "declaration, screening") end
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

--- The reference of the declaration, from FIELDS: one line per field, "part.field = default
-- -- type: meaning" (the declaration's own fields without a part).
function M.reference()
  local order = { "declaration", "response", "unknown", "prior", "candidate", "revision", "design", "limits",
                  "screening", "weights", "evidence" }
  local lines = {}
  for _, p in ipairs(order) do
    for _, f in ipairs(FIELDS[p]) do
      local default = f[3]
      local shown = type(default) == "string" and ("%q"):format(default) or type(default) == "table" and "{}"
        or type(default) == "function" and "(see meaning)" or tostring(default)
      lines[#lines + 1] = ("%s%s = %s  -- %s: %s"):format(p == "declaration" and "" or (p .. "."), f[1], shown, f[2], f[4])
    end
  end
  return table.concat(lines, "\n")
end

doc.add(([==[
@ smi.improve.declaration() -> text
The fields of a study's declaration (smi.improve.run's first argument), part by part, each with
its default, type and meaning, as the check reads them; smi.improve.run names a misspelt field
with the closest one. docs/new-product.md explains them with an example.
options:
%s
returns: the reference above as text
errors: none
example:
  local improve = require "smi.improve"
  print(improve.declaration():match("margin = 3"))
]==]):format((M.reference():gsub("([^\n]+)", "  %1"))))

return M
