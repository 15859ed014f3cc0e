-- SPDX-License-Identifier: MIT
-- The study of the slurm tests: n runs of the test solver, the last of which sleeps past the
-- model's 3 s timeout, and a second model whose one run exits with status 3 (failures are
-- results too), printed so that a run on the local executor and one on Slurm compare line by line.
-- arg[1] = solver, arg[2] = launch log, arg[3] = seconds per run, arg[4] = n, arg[5] = timeout,
-- arg[6] = words: "nohang" (no run hangs), "first" (the first run hangs, not the last), "stop"
-- (on_failure = "stop" instead of "skip")
local solver, log, sleep, n = arg[1], arg[2], tonumber(arg[3] or "0.2"), tonumber(arg[4] or "10")
local timeout = tonumber(arg[5] or "3")
local opts = arg[6] or ""
local hang = not opts:find("nohang")
local hang_row = opts:find("first") and 1 or n
local on_failure = opts:find("stop") and "stop" or "skip"
local function model(name, mode)
  return smi.model.command{
    name = name, inputs = {"x1", "x2", "sleep"}, outputs = {"f", "g"},
    template_string = "x1 = {{x1}}\nx2 = {{x2}}\nmode = {{mode}}\nexit_code = 3\nsleep = {{sleep}}\nlog = {{log}}\n",
    constants = {log = log, mode = mode},
    deck = "run.deck", version = "slurm-test-1", timeout = timeout, on_failure = on_failure, concurrency = 4,
    command = {solver, "{deck}", "-o", "out.txt"},
    parse = function(dir, h)
      return {f = h.regex("out.txt", "f = (\\S+)"), g = h.regex("out.txt", "g = (\\S+)")}
    end,
  }
end
local X = {}
for i = 1, n do X[i] = {i * 0.25, 1 - i * 0.125, (hang and i == hang_row) and timeout + 27 or sleep} end
local Y, info = model("arr", "ok"):evaluate(X)
for i = 1, n do
  print(("row %d %s f=%.17g g=%.17g %s"):format(i, info.status[i], Y.f[i], Y.g[i], info.reason[i] or ""))
end
local Y2, info2 = model("bad", "exit"):evaluate({{7, 2, 0}})
print(("bad %s %s"):format(info2.status[1], info2.reason[1]))
print(("launched=%d reused=%d"):format(info.launched + info2.launched, math.floor(info.reused:sum() + info2.reused:sum())))
