-- SPDX-License-Identifier: MIT
--- smi.improve.stream(seed, label [, k]) -> seed: the integer seed of the study's random stream
-- named `label` (of trial k, for a trial's streams; of response k for "experimental pdf"). Every
-- random step of a study takes its seed here, by name, so no two steps share a sequence by a
-- coincidence of offsets picked at the call sites. The offsets are the ones the study has always
-- used: the same seed gives the same numbers as the results already published
-- (docs/steering-column-study.md, docs/benchmarks-plate.md).
local OFFSET = {
  ["experimental pdf"] = 0, screening = 20,
  ["trial design"] = 0, ["trial calibration"] = 10, ["trial validation"] = 30,
  ["trial evidence"] = 40, ["trial cost"] = 50,
  ["test points"] = 1000, ["sequential candidates"] = 2000, ["added design points"] = 3000,
  tolerance = 11, bootstrap = 7,
  ["u-pooling"] = 3, ["near-optimal predictions"] = 5, ["solver check points"] = 7, ["before after"] = 60,
}
local PER_TRIAL = 100

return function(seed, label, k)
  local o = OFFSET[label]
  if o == nil then error(("smi.improve.stream: no stream named '%s'"):format(tostring(label)), 2) end
  if label:match("^trial ") then return seed + PER_TRIAL * k + o end
  return seed + o + (k or 0)
end
