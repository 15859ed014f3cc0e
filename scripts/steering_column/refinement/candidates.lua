--- The three candidate sources of invalid modelling of Son et al. (2020, §4.1.5), as revisions
-- of the open model. Each candidate says how the revised model is run (its base deck), how many
-- new input variables the revision brings (robustness) and the analyst's estimate of the time
-- to implement it (minutes). The revised model is run by the criteria (criteria.lua).
--
-- 1. material properties per part: the column assembly's five steel parts (jacket, shaft, ECU
--    bracket, tilt bracket, hub) get their own E instead of the shared column_frame_E: five new
--    inputs. At the mean of the initial unknowns every part takes the common mean, so the revised
--    model runs as the current (rigid airbag) model.
-- 2. airbag location: the airbag mass moves to its true centre of gravity (10 mm behind and
--    20 mm below the hub centre) and stays rigidly tied to the hub: no new input. Run as the
--    spring variant with a mount stiffness 10⁴ times the nominal (the rigid limit: 1e7 N/mm
--    moves mode 4 by less than 0.01 Hz from 1e8 N/mm).
-- 3. airbag modelling type: the rigid airbag becomes a mass on spring elements (the spring
--    variant, spec §6) with one new input, airbag_stiffness, at its nominal 1000 N/mm.
return {
  {
    name = "material properties per part",
    short = "materials",
    airbag = "rigid", fixed = {},
    new_inputs = 5, implement_minutes = 240,
    why = "five parts' moduli to source and assign; the model's mass and stiffness layout stays",
  },
  {
    name = "airbag location",
    short = "location",
    airbag = "spring", fixed = { airbag_stiffness = 1e7 },
    new_inputs = 0, implement_minutes = 30,
    why = "move the lumped mass to the measured CG; no new parameter",
  },
  {
    name = "airbag modelling type",
    short = "airbag spring",
    airbag = "spring", fixed = { airbag_stiffness = 1000 },
    new_inputs = 1, implement_minutes = 60,
    why = "replace the rigid tie by three spring mounts; one new parameter (airbag_stiffness)",
  },
}
