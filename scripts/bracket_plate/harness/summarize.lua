-- SPDX-License-Identifier: MIT
-- Summary of a harness run (run.sh): per experiment the truth, the trials (what each applied and
-- its verdicts), the calibrated means against the truth and the ccx runs; then the confusion
-- table (truth form x what the last trial applied). With --check: exit 1 unless every experiment
-- meets the issue's conclusion for its truth:
--   clamped: one trial, valid on the calibrated responses, no refinement;
--   joint_sensor: trial 1 invalid, the last trial applies the joint and is valid on the calibrated
--     responses, mode3 never "invalid";
--   joint: the last trial applies the joint and not the sensor.
-- arg: experiments.csv, the harness output folder, the set (ci|full|all) [, --check]
local table_path, out, set, check = arg[1], arg[2], arg[3], arg[4] == "--check"
local E0, RHO0 = 69000, 2.70e-9

local rows = {}
for line in io.lines(table_path) do
  local id, eset, truth, noise, seed, E, rho, t, kw = line:match("^(%d+),([^,]*),([^,]*),([^,]*),([^,]*),([^,]*),([^,]*),([^,]*),([^,]*)")
  if id and (set == "all" or eset == set) then
    local function mean(s) return tonumber(s:match("^([^:]+)")) end
    rows[#rows + 1] = {id = id, truth = truth, E = mean(E), rho = mean(rho), t = mean(t), kw = mean(kw)}
  end
end

local function has(list, name) for _, v in ipairs(list or {}) do if v == name then return true end end return false end

-- Whether conclusion `c` is the issue's for `truth`. "The validation response is never invalid"
-- is read on the last trial (trial 1's clamped model may well fail mode 3 on a jointed specimen).
local function meets(truth, c)
  local trials, last = c.trials, c.trials[#c.trials]
  local cal_valid = last.responses.mode1 == "valid" and last.responses.mode2 == "valid"
  if truth == "clamped" then return #trials == 1 and cal_valid end
  local joint = has(last.applied, "compliant joint")
  if truth == "joint" then return joint and not has(last.applied, "sensor mass") end
  local first_invalid = trials[1].responses.mode1 == "invalid" or trials[1].responses.mode2 == "invalid"
  return #trials > 1 and first_invalid and joint and cal_valid and last.responses.mode3 ~= "invalid"
end

local confusion, ok_all = {}, true
print(("%-4s %-13s %-46s %-22s %-22s %s"):format("exp", "truth", "trials (applied: mode1/mode2/mode3)",
                                                "t_eff cal (truth)", "log10_kw cal (truth)", "ccx runs"))
for _, r in ipairs(rows) do
  local f = io.open(out .. "/exp" .. r.id .. "/study/results.json")
  local res = f and smi.json.decode(f:read("a"))
  if f then f:close() end
  local c = res and res.conclusion
  if not c then
    print(("%-4s %-13s the study wrote no conclusion"):format(r.id, r.truth))
    ok_all = false
  else
    local parts = {}
    for i, tr in ipairs(c.trials) do
      local a = #tr.applied > 0 and table.concat(tr.applied, "+") or "initial"
      local v = tr.responses
      parts[#parts + 1] = ("%d:%s %s/%s/%s"):format(i, a, (v.mode1 or "-"):sub(1, 3), (v.mode2 or "-"):sub(1, 3),
                                                   (v.mode3 or "-"):sub(1, 3))
    end
    local last = c.trials[#c.trials]
    local m = last.calibration and last.calibration.means or {}
    local t_truth = r.t * math.sqrt(r.E / r.rho) / math.sqrt(E0 / RHO0)
    local cal_t = m.t and ("%.4f (%.4f)"):format(m.t, t_truth) or "-"
    local cal_k = m.log10_kw and ("%.3f (%s)"):format(m.log10_kw, r.truth == "clamped" and "-" or ("%.3f"):format(r.kw)) or "-"
    local runs = res.cost and res.cost.solver_runs or "?"
    print(("%-4s %-13s %-46s %-22s %-22s %s"):format(r.id, r.truth, table.concat(parts, "; "), cal_t, cal_k, tostring(runs)))
    local good = meets(r.truth, c)
    if not good then ok_all = false end
    local applied = #last.applied > 0 and table.concat(last.applied, " + ") or "initial model"
    confusion[r.truth] = confusion[r.truth] or {}
    confusion[r.truth][applied] = (confusion[r.truth][applied] or 0) + 1
    print(("     -> %s: %s"):format(c.verdict, good and "meets the issue's conclusion for this truth" or "DOES NOT meet it"))
  end
end
print("\nconfusion (truth -> what the last trial applied):")
local function sorted(t) -- name order: pairs() order changes from run to run
  local k = {}
  for n in pairs(t) do k[#k + 1] = n end
  table.sort(k)
  return k
end
for _, truth in ipairs(sorted(confusion)) do
  for _, applied in ipairs(sorted(confusion[truth])) do
    print(("  %-13s -> %-32s %d"):format(truth, applied, confusion[truth][applied]))
  end
end
if check and not ok_all then os.exit(1) end
