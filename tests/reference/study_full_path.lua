-- SPDX-License-Identifier: MIT
--- The full path's conclusions on the committed data, for tests/study/check_budget.lua:
-- reads the results.json of `scripts/steering_column.lua --screening full --design fixed
-- --test-points 50 --solver-check 300` (the study before the surrogate screening: eq.-3 screening on smi-column-fe
-- itself, (46 + 1) x 200 runs) and writes tests/reference/study_full_path.json: the screening's
-- ranks per mode (top four, N_e of each input), each trial's candidate and verdicts, the
-- refinements, the conclusion and the solver runs. Made by tests/reference/study_full_path.sh
-- (which runs that study, about 5 minutes on 2 cores), so CI never pays the 9,400 runs.
-- usage: smi-lua --allow-read DIR --allow-write OUTDIR tests/reference/study_full_path.lua RESULTS.json OUT.json
local R = smi.json.read((assert(arg[1], "usage: study_full_path.lua RESULTS.json OUT.json")))  -- one argument: assert returns two
local out_file = assert(arg[2], "usage: study_full_path.lua RESULTS.json OUT.json")
local S = R.steps
local sc = S.screening.result
assert(sc.method == "full" and sc.n == 200, "study_full_path.lua: the results are not of --screening full (n = 200)")
local ref = { made_by = "tests/reference/study_full_path.sh: scripts/steering_column.lua --screening full --design fixed --test-points 50 --solver-check 300 on the committed data, seed " .. tostring(S.summary.result.seed),
              screening = {}, trials = {}, refinements = R.conclusion.refinements, verdict = R.conclusion.verdict,
              solver_runs = R.cost.solver_runs }
for _, m in ipairs{ "mode1", "mode2", "mode4" } do
  local ne = {}
  for _, row in ipairs((sc.responses or sc.modes)[m].rows) do ne[row.input] = row.ne end
  ref.screening[m] = { top = (sc.responses or sc.modes)[m].top, ne = ne }
end
for k, t in ipairs(R.conclusion.trials) do
  ref.trials[k] = { candidate = t.candidate, airbag = t.airbag, modes = t.modes, means = t.calibration.means }
  local b = S["trial" .. k .. "_calibration"].result.bootstrap
  if b and b.lower then
    ref.trials[k].mean_intervals = {}
    for name in pairs(t.calibration.means) do ref.trials[k].mean_intervals[name] = { b.lower[name .. ".mean"], b.upper[name .. ".mean"] } end
  end
end
smi.json.write(out_file, ref, { indent = 2 })
print("wrote " .. out_file)
