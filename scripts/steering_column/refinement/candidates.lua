--- The three candidate sources of invalid modelling of Son et al. (2020, §4.1.5), each declared as
-- a revision of the initial model (the analyst's library; the study builds the next trial from it,
-- nothing about the trials is written anywhere else):
--   revision.airbag     the column-fe model variant ("rigid" | "spring")
--   revision.fixed      deck values the revision holds fixed ({input = value})
--   revision.unknowns   the NEW unknowns it brings, each with its distribution type, the bounds and
--                       start of its mean and std ({lo, hi, start}) and unit; they are added to the
--                       initial model's unknowns (inputs.lua, Table 4)
--   revision.at_initial values of the new unknowns for the correctness run at the initial means
--   revision.trend, revision.n_design   the Kriging trend and design size of the revised trial
-- new_inputs (robustness) is the number of new unknowns; implement_minutes is the analyst's
-- estimate. Revisions are alternatives to the initial model, not cumulative: the next-ranked
-- candidate revises the initial model again.
--
-- 1. material properties per part: the steel parts keep column_frame_E, but the hub, the gear
--    housing and the wheel armature get calibrated moduli of their own (three new unknowns, bounds
--    ±50 % of nominal as Table 8 does for the others). At the initial means it runs as model A.
-- 2. airbag location: the airbag mass moves to its true centre of gravity (10 mm behind and 20 mm
--    below the hub centre) and stays rigidly tied to the hub: no new input. Run as the spring
--    variant with a mount stiffness 10⁴ times the nominal (the rigid limit: 1e7 N/mm moves mode 4
--    by less than 0.01 Hz from 1e8 N/mm).
-- 3. airbag modelling type: the rigid airbag becomes a mass on spring elements (the spring variant,
--    spec §6) with one new unknown, airbag_stiffness (Table 8).
local function E(nominal, std)
  return { dist = "normal", mean = { 0.5 * nominal, 1.5 * nominal, nominal }, std = { 0.5 * std, 1.5 * std, std },
           unit = "MPa" }
end

local list = {
  {
    name = "material properties per part",
    short = "materials",
    implement_minutes = 240,
    why = "three parts' moduli to source and assign; the model's mass and stiffness layout stays",
    revision = {
      airbag = "rigid", fixed = {}, trend = "linear", n_design = 140,
      unknowns = { { "hub_E", E(200000, 6000) }, { "housing_E", E(71000, 2500) }, { "wheel_frame_E", E(45000, 1800) } },
    },
  },
  {
    name = "airbag location",
    short = "location",
    implement_minutes = 30,
    why = "move the lumped mass to the measured CG; no new parameter",
    revision = { airbag = "spring", fixed = { airbag_stiffness = 1e7 }, trend = "linear", n_design = 80,
                 unknowns = {} },
  },
  {
    name = "airbag modelling type",
    short = "airbag spring",
    implement_minutes = 60,
    why = "replace the rigid tie by three spring mounts; one new parameter (airbag_stiffness)",
    revision = {
      airbag = "spring", fixed = {}, trend = "constant", n_design = 120,
      unknowns = { { "airbag_stiffness",
                     { dist = "normal", mean = { 500, 1500, 1000 }, std = { 15.5, 46.5, 31 }, unit = "N/mm" } } },
    },
  },
}

-- Checks the declarations once, so a mistake in the library names the candidate and the field.
for i, c in ipairs(list) do
  local where = ("refinement/candidates.lua, candidate %d (%s)"):format(i, tostring(c.name))
  local r = c.revision
  assert(type(r) == "table", where .. ": no revision")
  assert(r.airbag == "rigid" or r.airbag == "spring", where .. ": revision.airbag must be rigid or spring")
  for _, u in ipairs(r.unknowns) do
    local n, s = u[1], u[2]
    assert(type(n) == "string" and type(s) == "table", where .. ": each new unknown is {name, {dist, mean, std, unit}}")
    for _, k in ipairs{ "mean", "std" } do
      local b = s[k]
      assert(type(b) == "table" and b[1] < b[2] and b[3] >= b[1] and b[3] <= b[2],
        ("%s: unknown %s: %s must be {lower, upper, start} with lower <= start <= upper"):format(where, n, k))
    end
  end
  c.new_inputs = #r.unknowns
end

return list
