-- SPDX-License-Identifier: MIT
--- The analyst's prior knowledge (--prior FILE.lua): a Lua file returning prior entries
-- {param = "input.mean", mean =, std = [, dist = "normal"|"lognormal"]}, checked here so that a
-- mistake names the file and the entry. Each is a density on that parameter in the trials'
-- Bayesian calibration (evidence.lua), beside the priors the declaration gives its unknowns. No
-- file: no prior (a study uses the data file alone by default).
local M = {}

local SHAPE = '{param = "input.mean", mean = m, std = s [, dist = "normal"|"lognormal"]} or'
  .. ' {name = "label", fn = function(theta) ... end, mean = m, std = s}'

local function fail(path, fmt, ...)
  error(("--prior %s%s"):format(path, fmt:format(...)), 0)
end

local function valid_entry(e)
  local what = type(e) == "table" and (e.param or e.name)
  return type(e) == "table" and type(what) == "string" and not (e.name and type(e.fn) ~= "function")
    and (e.dist == nil or e.dist == "normal" or e.dist == "lognormal")
    and type(e.mean) == "number" and type(e.std) == "number" and e.std > 0, what
end

--- {entries = the list or nil, labels = {"name ~ N(mean, std)", ...}} of the file at path (nil: none).
function M.load(path)
  local prior = { labels = {} }
  if not path then return prior end
  local chunk, err = loadfile(path)
  if not chunk then fail(path, ": %s", tostring(err)) end
  local ok, list = pcall(chunk)
  if not ok or type(list) ~= "table" then
    fail(path, " must return a list of prior entries (%s); %s", SHAPE,
      ok and ("it returned a " .. type(list)) or tostring(list))
  end
  for i, e in ipairs(list) do
    local good, what = valid_entry(e)
    if not good then
      fail(path, ", entry %d: needs param = \"<parameter>\" (or name = \"<label>\" with fn = function(theta)), a"
        .. " number mean, a std > 0 and dist (if given) \"normal\" or \"lognormal\"", i)
    end
    prior.labels[i] = ("%s ~ %s(%.6g, %.6g)"):format(what, e.dist or "normal", e.mean, e.std)
  end
  prior.entries = list
  return prior
end

return M
