-- SPDX-License-Identifier: MIT
--- smi.report.json: results.json for reports and studies, a thin layer over smi.json (the one
-- JSON codec, host/platform/core/json.hpp). What it adds is the results-file rule:
--   * non-finite numbers are kept, in the codec's documented encoding: +/-inf as 1e999/-1e999
--     (valid JSON that every IEEE reader reads as inf), NaN as null, which decode reads back as NaN
--   * indent is a string per level ("  "); root names the value in error paths ("value")
--   * skip = true leaves out what JSON cannot hold (a function, other userdata) and appends its
--     path to opts.skipped; without skip such a value is an error naming its path
-- Numbers read back bit for bit, smi.vec becomes an array, smi.mat an array of rows, keys are
-- sorted (the same results give the same file).
local doc = require "smi.doc"
doc.add[==[
@ module smi.report.json
JSON for results files, over smi.json: numbers read back bit for bit, NaN as null (read back as
NaN), infinities as 1e999, vecs as arrays, mats as arrays of rows, keys sorted (the same results
give the same file).
]==]
local M = {}

local host = smi.json
local NaN = 0 / 0

doc.add[==[
@ smi.report.json.encode(v [, opts]) -> string
JSON text of v by smi.json.encode with the results-file rule for NaN and infinities.
options:
  indent = nil    -- a string per level, e.g. "  " (default: one line)
  skip = false    -- leave out what JSON cannot hold; its paths are appended to opts.skipped
  root = "value"  -- the name used in error paths
returns: a string
errors: a value JSON cannot hold (a function, a userdata), named by its path, unless skip
example:
  local j = require("smi.report").json
  local o = {skip = true, skipped = {}}
  print(j.encode({a = 1, f = print}, o), o.skipped[1])
]==]
function M.encode(v, opts)
  opts = opts or {}
  local text, skipped = host.encode(v, { indent = opts.indent and #opts.indent or 0, nonfinite = "encode",
                                         skip = opts.skip or false, root = opts.root or "value" })
  if skipped and #skipped > 0 then
    opts.skipped = opts.skipped or {}
    for _, p in ipairs(skipped) do opts.skipped[#opts.skipped + 1] = p end
  end
  return text
end

doc.add[==[
@ smi.report.json.decode(s) -> value
The Lua value of JSON text, by smi.json.decode; null reads as NaN (this module writes NaN as null).
returns: the value
errors: invalid JSON, with the line and column
example:
  local j = require("smi.report").json
  local t = j.decode('{"u": null}')
  print(t.u ~= t.u)
]==]
function M.decode(s)
  return host.decode(s, { null = NaN })
end

return M
