-- SPDX-License-Identifier: MIT
-- smi.options: declared study options, their checks and the --help text.
local T = require "smi.testing"
local options = require "smi.options"

local spec = {
  name = "demo", summary = "a demo study",
  { name = "data", type = "path", default = "data/tests.csv", meaning = "measurements" },
  { name = "metric", type = "string", default = "pr", allowed = { "pr", "loglik" }, meaning = "calibration metric" },
  { name = "multistart", type = "integer", default = 1, min = 1, meaning = "optimizer starts" },
  { name = "alpha", type = "number", default = 0.1, min = 0, max = 1, meaning = "significance" },
  { name = "quick", type = "flag", default = false, meaning = "reduced run" },
  { name = "even", type = "integer", default = 2, check = function(v) return v % 2 == 0, "is odd" end, meaning = "an even count" },
  options.study_steps,
}

T.case("defaults when nothing is given", function()
  local o = assert(options.check({}, spec))
  T.eq(o.data, "data/tests.csv"); T.eq(o.metric, "pr"); T.eq(o.multistart, 1); T.eq(o.quick, false)
  T.eq(o.alpha, 0.1); T.eq(o.only, nil); T.eq(o.quiet, nil)
end)

T.case("values in both spellings, flags, lists", function()
  local o = assert(options.check({ "--metric", "loglik", "--multistart=4", "--quick", "--only", "a,b", "--only=c", "--alpha", "0.05" }, spec))
  T.eq(o.metric, "loglik"); T.eq(o.multistart, 4); T.eq(math.type(o.multistart), "integer"); T.eq(o.quick, true)
  T.eq(#o.only, 3); T.eq(o.only[3], "c"); T.eq(o.alpha, 0.05)
end)

T.case("a wrong value names the option and the allowed values", function()
  local o, err = options.check({ "--metric", "rmse" }, spec)
  T.eq(o, nil)
  T.truthy(err:find("--metric", 1, true) and err:find("pr, loglik", 1, true) and err:find("rmse", 1, true), err)
  o, err = options.check({ "--multistart", "0" }, spec)
  T.truthy(err:find("--multistart", 1, true) and err:find(">= 1", 1, true), err)
  o, err = options.check({ "--multistart", "2.5" }, spec)
  T.truthy(err:find("not a whole number", 1, true), err)
  o, err = options.check({ "--alpha", "2" }, spec)
  T.truthy(err:find("above the maximum 1", 1, true), err)
  o, err = options.check({ "--even", "3" }, spec)
  T.truthy(err:find("--even", 1, true) and err:find("is odd", 1, true), err)
  o, err = options.check({ "--data" }, spec)
  T.truthy(err:find("--data needs a value", 1, true), err)
  o, err = options.check({ "--metrc", "pr" }, spec)
  T.truthy(err:find("unknown option '--metrc'", 1, true) and err:find("did you mean --metric", 1, true), err)
  o, err = options.check({ "stray" }, spec)
  T.truthy(err:find("unexpected argument 'stray'", 1, true), err)
end)

T.case("--help lists every option with its default and allowed values", function()
  local o = assert(options.check({ "--help" }, spec))
  T.eq(o.help, true)
  local h = options.help(spec)
  -- the first line names the script as it was run (arg[0]), not the declaration
  T.eq(h:match("^[^\n]*"), arg[0] .. ": a demo study")
  for _, want in ipairs { ": a demo study", "--data=PATH", "[default: data/tests.csv]", "--metric=pr|loglik", "[default: pr]",
                          "--multistart=N", "(a whole number >= 1)", "--quick", "--only=A[,B...]", "--help" } do
    T.truthy(h:find(want, 1, true), "help shows " .. want .. "\n" .. h)
  end
end)

T.case("rest = true keeps what the spec does not declare (smi.study.parse_args is this)", function()
  local o = assert(options.check({ "--data", "f.csv", "--only", "a,b", "x", "--quiet", "--only=c" }, { rest = true, options.study_steps }))
  T.eq(table.concat(o.only, ","), "a,b,c", "only, repeated and with =")
  T.eq(o.quiet, true, "quiet")
  T.eq(table.concat(o.rest, ","), "--data,f.csv,x", "the rest, in order")
  local _, err = options.check({ "--from" }, { rest = true, options.study_steps })
  T.eq(err, "--from needs a step name", "needs words the missing value")
  local study = require "smi.study"
  T.eq(table.concat(study.parse_args{ "--only", "a", "--data", "f" }.rest, ","), "--data,f", "parse_args is the same parser")
end)

T.case("a bad declaration is refused", function()
  T.raises(function() options.check({}, { { name = "x", type = "float", meaning = "m" } }) end, "type must be flag")
  T.raises(function() options.check({}, { { name = "x" } }) end, "has no meaning")
end)

T.finish()
