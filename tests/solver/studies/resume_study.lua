-- SPDX-License-Identifier: MIT
-- A small study for the end-to-end CLI tests (test_cli_resume.sh): eight runs of the test
-- solver, one at a time, each logging its launch to a shared file.
-- arg[1] = solver, arg[2] = launch log, arg[3] = seconds per run, arg[4] = the solver's mode
-- (default ok; the signal tests use hang_setsid).
local solver, log, sleep, mode = arg[1], arg[2], arg[3] or "0.2", arg[4] or "ok"
local m = smi.model.command{
  name = "resume", inputs = {"x1", "x2"}, outputs = {"f"},
  template_string = "x1 = {{x1}}\nx2 = {{x2}}\nsleep = " .. sleep .. "\nlog = {{log}}\nmode = " .. mode .. "\n",
  constants = {log = log}, deck = "run.deck", version = "resume-1",
  command = {solver, "{deck}", "-o", "out.txt"},
  parse = function(dir, h) return {f = h.regex("out.txt", "f = (\\S+)")} end,
}
local X = {}
for i = 1, 8 do X[i] = {i * 0.5, 1 - i * 0.1} end
local Y, info = m:evaluate(X)
for i = 1, 8 do
  if info.status[i] ~= "not run" then  -- --dry-run fills in stored points only
    local want = X[i][1] ^ 2 + X[i][2] ^ 2
    assert(Y.f[i] == want, ("row %d: f = %.17g, expected %.17g"):format(i, Y.f[i], want))
  end
end
print(("launched=%d reused=%d"):format(info.launched, math.floor(info.reused:sum())))
