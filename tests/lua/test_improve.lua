-- SPDX-License-Identifier: MIT
-- smi.improve: a declaration's mistakes are errors naming the field and the response or
-- candidate, the data step's units check stops before any solver budget
--, and the whole loop runs on a small product whose truth needs one revision.
-- The product and its truth: tests/lua/small_product.lua.
local T = require "smi.testing"
local improve = require "smi.improve"

local small = require "small_product"
local product = small.model

-- 9 specimens of the truth, written where the study reads them
local data_file = smi.out("improve_data.csv")
small.write_data(data_file)

local function declaration(over) return small.declaration("improve_test", data_file, over) end

-- each study its own results.json (they share the test's output folder)
local function run(d, argv) return improve.run(d, argv, { results = smi.out(d.name .. "_results.json") }) end

local function run_error(d, argv)
  local ok, err = pcall(run, d, argv or { "--quick" })
  T.truthy(not ok, "an error")
  return tostring(err)
end

T.case("a misspelt top-level field is named, with the field it likely means", function()
  local d = declaration()
  d.respones, d.responses = d.responses, nil
  local e = run_error(d)
  T.truthy(e:find("unknown field 'respones'", 1, true) and e:find("did you mean 'responses'", 1, true), e)
end)

T.case("a missing field names it", function()
  local d = declaration()
  d.model = nil
  local e = run_error(d)
  T.truthy(e:find("field 'model' must be a function", 1, true), e)
end)

T.case("a misspelt candidate field names the candidate", function()
  local d = declaration()
  d.candidates[1].revision.unknows = d.candidates[1].revision.unknowns
  local e = run_error(d)
  T.truthy(e:find("candidate 'joint', revision: unknown field 'unknows'", 1, true)
           and e:find("did you mean 'unknowns'", 1, true), e)
end)

T.case("an unknown's bad bounds name the unknown and the field", function()
  local d = declaration()
  d.unknowns[1].mean = { 1.3, 0.8, 1.0 }
  local e = run_error(d)
  T.truthy(e:find("unknown 1 'a': field 'mean'", 1, true), e)
end)

T.case("a response in the data that the model does not give is named", function()
  local d = declaration{ name = "improve_outputs" }
  d.model = function(applied, unknowns, ctx)
    return smi.model.lua{ name = ctx.name, inputs = unknowns, outputs = { "f1", "f2" },
                          fn = function(X) return { f1 = X:col(1) * 10, f2 = X:col(1) * 20 } end }
  end
  local e = run_error(d)
  T.truthy(e:find("response 'f3' is declared", 1, true) and e:find("the initial model", 1, true), e)
end)

T.case("a response missing from the data is named with its column", function()
  local d = declaration{ name = "improve_columns" }
  d.responses[3].column = "f3_missing"
  local e = run_error(d)
  T.truthy(e:find("response 'f3': no column 'f3_missing'", 1, true), e)
end)

T.case("a revision whose factory fails names the candidate", function()
  local d = declaration()
  d.model = function(applied, unknowns, ctx)
    if ctx.form.joint == "spring" then error("no joint elements in this mesh") end
    return product(applied, unknowns, ctx)
  end
  local D = require("smi.improve.declare").check(d)
  local revise = require "smi.improve.revise"
  local T1 = revise.apply(D, revise.initial(D, D.unknowns), "joint")
  local ok, e = pcall(improve.model, D, {}, T1, { purpose = "correctness", name = "x" })
  T.truthy(not ok and tostring(e):find("candidate 'joint': the model factory failed", 1, true)
           and tostring(e):find("no joint elements", 1, true), tostring(e))
end)

T.case("a model whose inputs are not the trial's unknowns is named", function()
  local d = declaration()
  d.model = function(applied, unknowns, ctx)
    return smi.model.lua{ name = ctx.name, inputs = { "b" }, outputs = { "f1", "f2", "f3" },
                          fn = function(X) return { f1 = X:col(1), f2 = X:col(1), f3 = X:col(1) } end }
  end
  local D = require("smi.improve.declare").check(d)
  local T0 = require("smi.improve.revise").initial(D, D.unknowns)
  local ok, e = pcall(improve.model, D, {}, T0, { purpose = "design", name = "x" })
  T.truthy(not ok and tostring(e):find("takes inputs {b}, but the trial's unknowns are {a}", 1, true), tostring(e))
end)

T.case("data 1000 times the model's magnitude stop the study before its budget, unless accepted", function()
  local file = smi.out("improve_data_khz.csv")
  smi.csv.write(file, { f1 = smi.vec{ 10000, 10100, 9900 }, f2 = smi.vec{ 19500, 19600, 19400 },
                        f3 = smi.vec{ 1.5, 1.6, 1.55 } }, { header = { "f1", "f2", "f3" } })
  local e = run_error(declaration{ data = file, name = "improve_units" }, { "--quick" })
  T.truthy(e:find("likely a units error", 1, true) and e:find("response 'f1'", 1, true)
           and e:find("a factor of 1000", 1, true) and e:find("--accept-units", 1, true), e)
  -- with --accept-units the data step passes (the study then runs on: only the data step here)
  local R = run(declaration{ data = file, name = "improve_units_ok" },
                        { "--quick", "--accept-units", "--only", "data" })
  T.truthy(#R.data.units >= 2, "both calibrated responses flagged, as warnings")
end)

T.case("a plan over the declared limit on runs stops before anything runs", function()
  local d = declaration{ name = "improve_limit", limits = { refinements = 1, runs = 20 } }
  local e = run_error(d)
  -- 1 nominal + trial 1 (12 design + 10 check) + 2 decision-matrix runs + trial 2 (20 + 10) = 55,
  -- and after each trial that fits, the alternatives' designs (joint 20 + nothing 12) twice: 119
  T.truthy(e:find("the plan needs up to 119 solver runs, more than limits.runs = 20", 1, true), e)
end)

T.case("a declared plausible range the data leave stops the study", function()
  local d = declaration{ name = "improve_plausible" }
  d.responses[1].plausible = { 20, 100 }
  local e = run_error(d, { "--quick", "--only", "data" })
  T.truthy(e:find("response 'f1': the data", 1, true) and e:find("plausible range", 1, true), e)
end)

T.case("revisions combine; one that sets the same switch replaces; a worse fit is dropped", function()
  local d = declaration()
  d.candidates[3] = { name = "stiff joint", implement_minutes = 10,
                      revision = { form = { joint = "rigid" }, fixed = { k = 0 } } }
  d.candidates[4] = { name = "mass", implement_minutes = 10,
                      revision = { unknowns = { { name = "m", dist = "normal", mean = { 1, 2, 1.5 }, std = { 0.1, 0.2, 0.1 } } } } }
  local D = require("smi.improve.declare").check(d)
  local revise = require "smi.improve.revise"
  local t1 = revise.initial(D, D.unknowns)
  local t2 = revise.apply(D, t1, "joint")
  local t3 = revise.apply(D, t2, "mass")
  T.eq(table.concat(t3.applied, ","), "joint,mass", "on top of each other")
  T.eq(table.concat(t3.unknowns, ","), "a,k,m")
  T.eq(t3.form.joint, "spring")
  local t4 = revise.apply(D, t3, "stiff joint")
  T.eq(table.concat(t4.applied, ","), "mass,stiff joint", "the joint replaced")
  T.truthy(t4.dropped[1].name == "joint" and t4.dropped[1].why:find("form switch 'joint'", 1, true), "and why")
  T.eq(table.concat(t4.unknowns, ","), "a,m")
  -- evidence: trial 2 (the joint) fitted worse than trial 1 -> the joint is dropped
  local R = { trial1_calibration = { objective = 0.2 }, trial2_calibration = { objective = 0.5 },
              trial2_surrogate = { model = t2 } }
  local drop = revise.keep(R, 2)
  T.truthy(drop and drop.joint and drop.joint:find("worse", 1, true), "dropped on evidence")
  R.trial2_calibration.objective = 0.1
  T.eq(revise.keep(R, 2), nil, "kept when the fit improved")
end)

T.case("the loop: trial 1 invalid, the joint applied on top, valid; the generic conclusion", function()
  local R, C = run(declaration{ name = "improve_loop" }, { "--quick" })
  T.truthy(C ~= nil, "a conclusion")
  T.eq(C.trials[1].candidate, "initial")
  T.eq(C.trials[1].responses.f2 == "invalid" or C.trials[1].responses.f1 == "invalid", true, "trial 1 invalid")
  T.eq(C.refinements[1], "joint", "the decision matrix picks the joint")
  local last = C.trials[#C.trials]
  T.eq(table.concat(last.applied, ","), "joint")
  T.eq(table.concat(last.unknowns, ","), "a,k")
  T.eq(last.responses.f1, "valid"); T.eq(last.responses.f2, "valid")
  T.truthy(last.responses.f3 ~= "invalid", "the validation response never invalid")
  T.eq(C.verdict, "valid")
  T.near(last.calibration.means.k, 0.5, 0.1, "k near its truth")
  T.near(last.calibration.means.a, 1.05, 0.02, "a near its truth")
end)

-- trial 1's real calibration with smi.calibrate's no_overlap status forced on it (hint: a units hint or none)
local function run_forced_no_overlap(name, hint)
  local calibration = require "smi.improve.calibration"
  local real = calibration.calibrate
  calibration.calibrate = function(t)
    local out, r = real(t)
    out.converged, out.status = false, "no_overlap"
    out.message = "response 'f1': no overlap between predicted and measured"
    out.no_overlap = { { response = "f1", metric = "pr", value = 2, units_hint = hint } }
    return out, r
  end
  local ok, R, C = pcall(run, declaration{ name = name }, { "--quick" })
  calibration.calibrate = real
  T.truthy(ok, tostring(R))
  return R, C
end

T.case("no overlap a power of ten apart (a units mistake) stops the study before validation", function()
  local R, C = run_forced_no_overlap("improve_no_overlap_units",
    "the predictions are about 1000x the data: are the inputs in the units the model expects?")
  T.eq(C.verdict, "undetermined", "the data cannot decide: neither valid nor invalid")
  T.eq(#C.trials, 1, "no trial after it")
  T.eq(#C.refinements, 0)
  T.truthy(R.trial1_validation.skipped and R.trial1_validation.reason:find("no_overlap", 1, true), "validation skipped, why")
  T.truthy(R.trial1_validation.reason:find("units", 1, true), "the reason names units")
  T.eq(C.trials[1].calibration.status, "no_overlap")
end)

T.case("no overlap without a units hint (a model-form misfit) is validated and refined", function()
  local R, C = run_forced_no_overlap("improve_no_overlap_form", nil)
  T.truthy(not R.trial1_validation.skipped, "trial 1 validated")
  T.eq(C.trials[1].calibration.status, "no_overlap")
  T.truthy(#C.trials >= 1)
end)

T.finish()
