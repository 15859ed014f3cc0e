-- SPDX-License-Identifier: MIT
--- smi.options: a study declares its command-line options (name, default, meaning, check), as
-- sysbench scripts do; `smi-lua study.lua --help` lists them and a wrong value is refused with
-- the option's name and what it accepts.
--
--   local options = require "smi.options"
--   local opt = options.parse(arg, {
--     name = "my_study", summary = "Calibrates the bracket model against the shaker tests.",
--     { name = "data", type = "path", default = "data/tests.csv", meaning = "measurements (CSV)" },
--     { name = "metric", type = "string", default = "pr", allowed = { "pr", "loglik" }, meaning = "calibration metric" },
--     { name = "starts", type = "integer", default = 1, min = 1, meaning = "optimizer starts" },
--     { name = "quick", type = "flag", meaning = "the reduced run CI uses" },
--     options.study_steps,                -- --only, --from, --quiet, --force for smi.study's s:run(opt)
--   })
--   -- opt.data, opt.metric, opt.starts, opt.quick, opt.only, ...
--
-- Values: --name VALUE or --name=VALUE; a flag takes no value (--quick) and is true when given,
-- else its default (nil unless declared). Types: flag, string,
-- path, number, integer, list (comma-separated, repeatable: --only a,b --only c -> {"a","b","c"}).
-- Checks: allowed = {...} (every element for a list), min, max, input = true (a path that must
-- name a readable file, opened at parse), and check = function(v) that
-- returns true, or false/nil and why. Arguments not starting with "--" are refused unless the
-- spec says args = "<meaning>" (then they are kept in opt.args); with rest = true, every argument
-- the spec does not declare is kept, in order, in opt.rest (smi.study.parse_args: the steps'
-- options here, the study's own for its parser). needs = "a step name" words a missing value. smi-lua's own options (--out,
-- --seed, ...) go before the script; given after it, one the study did not declare is refused
-- with "smi-lua's own option --out goes before the script: smi-lua --out DIR study.lua ...".
local doc = require "smi.doc"
doc.add[==[
@ module smi.options
Command-line options a study declares (name, type, default, meaning, check), as sysbench scripts
do: `smi-lua study.lua --help` lists them, and a wrong value names the option and what it accepts.
]==]
local M = {}

local TYPES = { flag = true, string = true, path = true, number = true, integer = true, list = true }

-- smi-lua's own options (host/cli/args.cpp; tests/cli checks this list against `smi-lua --help`)
-- with the placeholder of their value (nil: a flag). They act before the script starts (the
-- sandbox, the output folder, the seed), so they go before the script's name; after it, an
-- option the study did not declare itself is refused with the command line that works. A study
-- may declare an option of the same name (--dry-run, --quiet): after the script, it is the study's.
M.host_options = {
  ["allow-read"] = "PATH", ["allow-write"] = "PATH", ["allow-exec"] = "PROG", ["allow-env"] = "NAME",
  lib = "DIR", ["stdlib-dir"] = "DIR", out = "DIR", seed = "N", ["max-memory"] = "MB", timeout = "SECONDS",
  store = "PATH", executor = "KIND", ["slurm-opt"] = "K=V", quiet = false, ["dry-run"] = false, detach = false,
  pdf = false, traceback = false,
}

-- The refusal of smi-lua's own option given after the script.
local function host_option_message(name, argv)
  local value = M.host_options[name]
  local script = argv and argv[0] or "study.lua"
  return ("smi-lua's own option --%s goes before the script: smi-lua --%s%s %s ..."):format(
    name, name, value and (" " .. value) or "", tostring(script))
end

--- --only, --from and --quiet as smi.study's s:run(opt) reads them (splice into a spec's list).
M.study_steps = {
  { name = "only", type = "list", needs = "a step name", meaning = "run only these steps (comma-separated); the others' results are read from results.json" },
  { name = "from", type = "string", needs = "a step name", meaning = "run this step and every later one; earlier results are read from results.json" },
  { name = "quiet", type = "flag", meaning = "no progress lines (also automatic when output is not a terminal)" },
  { name = "force", type = "flag", meaning = "run every step again (a whole run otherwise reuses the saved steps whose inputs are unchanged)" },
}

-- The declarations in order, with the study_steps group (or any nested list) expanded.
local function declarations(spec)
  local out, by = {}, {}
  local function add(d, where)
    if type(d) ~= "table" then error(("smi.options: %s must be a table {name =, type =, default =, meaning =}, got %s"):format(where, type(d)), 3) end
    if d.name == nil and d[1] ~= nil and type(d[1]) == "table" then
      for i, e in ipairs(d) do add(e, where .. "[" .. i .. "]") end
      return
    end
    if type(d.name) ~= "string" or not d.name:match("^[%a][%w_%-]*$") then
      error(("smi.options: %s.name must be a word such as \"data\", got %s"):format(where, tostring(d.name)), 3)
    end
    local t = d.type or (type(d.default) == "number" and "number") or (type(d.default) == "boolean" and "flag") or "string"
    if not TYPES[t] then
      error(("smi.options: option '%s': type must be flag, string, path, number, integer or list, got %s"):format(d.name, tostring(t)), 3)
    end
    if type(d.meaning) ~= "string" or d.meaning == "" then
      error(("smi.options: option '%s' has no meaning: say what it does (meaning = \"...\")"):format(d.name), 3)
    end
    if by[d.name] then error(("smi.options: option '%s' is declared twice"):format(d.name), 3) end
    local e = setmetatable({ type = t }, { __index = d })
    by[d.name] = e
    out[#out + 1] = e
  end
  for i, d in ipairs(spec) do add(d, "spec[" .. i .. "]") end
  return out, by
end

--- Why a file cannot be read (nil when it can): missing, a folder, or refused by the sandbox.
local function unreadable(path)
  local ok, f, err = pcall(io.open, path, "rb")
  if not ok then return (tostring(f):gsub("^[^:]*: ", "")) end
  if not f then return (tostring(err):gsub("^" .. path:gsub("%p", "%%%0") .. ": ", "")) end
  local okr, chunk, rerr = pcall(f.read, f, 0)
  f:close()
  if not okr or (chunk == nil and rerr) then return "it is not a readable file (a folder?)" end
  return nil
end

local function show(v)
  if type(v) == "table" then return table.concat(v, ",") end
  return tostring(v)
end

-- What an option accepts, in words ("pr|loglik", "a whole number >= 1", ...).
local function accepts(d)
  local parts = {}
  if d.allowed then parts[#parts + 1] = "one of " .. table.concat((function()
    local t = {}
    for i, a in ipairs(d.allowed) do t[i] = tostring(a) end
    return t
  end)(), ", ") end
  if d.type == "integer" then parts[#parts + 1] = "a whole number"
  elseif d.type == "number" then parts[#parts + 1] = "a number" end
  if d.min ~= nil then parts[#parts + 1] = ">= " .. tostring(d.min) end
  if d.max ~= nil then parts[#parts + 1] = "<= " .. tostring(d.max) end
  if d.type == "list" and #parts > 0 then table.insert(parts, 1, "comma-separated values, each") end
  return table.concat(parts, " ")
end

local function placeholder(d)
  if d.type == "flag" then return "" end
  if d.allowed then
    local t = {}
    for i, a in ipairs(d.allowed) do t[i] = tostring(a) end
    return "=" .. table.concat(t, "|") .. (d.type == "list" and "[,...]" or "")
  end
  return "=" .. ({ string = "TEXT", path = "PATH", number = "X", integer = "N", list = "A[,B...]" })[d.type]
end

doc.add[==[
@ smi.options.help(spec) -> string
The --help text of a spec: the study's name and summary, the usage line, then every option with
its placeholder (--metric=pr|loglik, --starts=N), meaning, default and accepted values.
returns: a string ending in a newline
errors: a bad declaration (as smi.options.check)
example:
  local options = require "smi.options"
  print(options.help{name = "demo", summary = "a demo",
    {name = "metric", default = "pr", allowed = {"pr", "loglik"}, meaning = "calibration metric"}})
]==]
--- The --help text of a spec (what options.parse prints for --help).
function M.help(spec)
  local all = declarations(spec)
  local decl = {}
  for _, d in ipairs(all) do if d.applies ~= false then decl[#decl + 1] = d end end
  local lines = {}
  local script = M.script_name(spec)
  lines[#lines + 1] = script .. (spec.summary and (": " .. spec.summary) or "")
  -- a function usage is asked only here: what it says may cost a look at the study (its model)
  local usage = spec.usage
  if type(usage) == "function" then usage = usage() end
  lines[#lines + 1] = "usage: " .. (usage and usage:gsub("{script}", (script:gsub("%%", "%%%%")))
    or ("smi-lua [smi-lua options] " .. script .. " [options]"))
  lines[#lines + 1] = ""
  lines[#lines + 1] = "options:"
  local heads, width = {}, 0
  for i, d in ipairs(decl) do
    heads[i] = "  --" .. d.name .. placeholder(d)
    width = math.max(width, #heads[i])
  end
  width = math.min(width, 34)
  for i, d in ipairs(decl) do
    local text = d.meaning
    if d.default ~= nil and d.type ~= "flag" then text = text .. " [default: " .. show(d.default) .. "]" end
    local acc = accepts(d)
    if acc ~= "" and not d.allowed then text = text .. " (" .. acc .. ")" end
    if #heads[i] > width then
      lines[#lines + 1] = heads[i]
      lines[#lines + 1] = (" "):rep(width + 2) .. text
    else
      lines[#lines + 1] = heads[i] .. (" "):rep(width - #heads[i] + 2) .. text
    end
  end
  lines[#lines + 1] = "  --help" .. (" "):rep(math.max(2, width - 8 + 2)) .. "this list"
  if spec.args then lines[#lines + 1] = "arguments: " .. spec.args end
  lines[#lines + 1] = ""
  lines[#lines + 1] = "smi-lua's own options (--out DIR, --seed N, --quiet, --timeout SECONDS, --pdf, ...;"
  lines[#lines + 1] = "smi-lua --help lists them) go before the script: smi-lua --out DIR " .. script .. " [options]"
  if spec.epilog then lines[#lines + 1] = ""; lines[#lines + 1] = spec.epilog end
  return table.concat(lines, "\n") .. "\n"
end

doc.add[==[
@ smi.options.script_name(spec) -> string
The script as the user ran it (arg[0], "scripts/frame.lua"), else the spec's name with ".lua": what
--help and the option errors name, and what "{script}" in the spec's usage becomes.
returns: a string
errors: none
example:
  local options = require "smi.options"
  print(options.script_name{name = "demo"} ~= "")
]==]
function M.script_name(spec)
  if type(arg) == "table" and type(arg[0]) == "string" and arg[0] ~= "" then return arg[0] end
  return (type(spec) == "table" and spec.name or "study") .. ".lua"
end

-- Converts and checks one value; returns it or nil, message.
local function convert(d, raw)
  local function bad(why) return nil, ("--%s: %s (%s)"):format(d.name, why, accepts(d) ~= "" and ("expects " .. accepts(d)) or d.meaning) end
  local function one(s)
    local v = s
    if d.type == "number" or d.type == "integer" then
      v = tonumber(s)
      if v == nil or v ~= v then return bad(("'%s' is not a number"):format(s)) end
      if d.type == "integer" and v ~= math.floor(v) then return bad(("'%s' is not a whole number"):format(s)) end
      if d.type == "integer" then v = math.tointeger(v) or v end
      if d.min ~= nil and v < d.min then return bad(("%s is below the minimum %s"):format(s, tostring(d.min))) end
      if d.max ~= nil and v > d.max then return bad(("%s is above the maximum %s"):format(s, tostring(d.max))) end
    end
    if d.allowed then
      local ok = false
      for _, a in ipairs(d.allowed) do if tostring(a) == tostring(v) then ok = true break end end
      if not ok then
        local t = {}
        for i, a in ipairs(d.allowed) do t[i] = tostring(a) end
        return nil, ("--%s: '%s' is not allowed; allowed values: %s"):format(d.name, tostring(s), table.concat(t, ", "))
      end
    end
    if d.check then
      local ok, why = d.check(v)
      if not ok then return bad(("'%s' %s"):format(tostring(s), why or "fails the option's check")) end
    end
    return v
  end
  if d.type == "list" then
    local out = {}
    for item in tostring(raw):gmatch("[^,]+") do
      local v, err = one(item)
      if v == nil then return nil, err end
      out[#out + 1] = v
    end
    if #out == 0 then return bad("needs at least one value") end
    return out
  end
  return one(raw)
end

local function suggest(by, name)
  if type(smi) == "table" and type(smi._closest) == "function" then  -- the one suggestion logic
    local names = {}
    for n in pairs(by) do names[#names + 1] = n end
    table.sort(names)
    return smi._closest(name, names)[1]
  end
  local best, bestd
  for n in pairs(by) do
    -- a cheap closeness: common prefix length, then length difference
    local p = 0
    while p < #n and p < #name and n:sub(p + 1, p + 1) == name:sub(p + 1, p + 1) do p = p + 1 end
    local dist = math.max(#n, #name) - p
    -- equally close: the first in name order (pairs() order changes from run to run)
    if p >= 2 and (bestd == nil or dist < bestd or (dist == bestd and n < best)) then best, bestd = n, dist end
  end
  return best
end

doc.add[==[
@ smi.options.check(argv, spec) -> opt | nil, message
Parses argv (--name VALUE, --name=VALUE, flags alone) against the declared options without
ending the run. The spec is a list of declarations plus name, summary, usage ("{script}" stands for the script as
it was run; a function returning that string is called only when --help is printed), epilog and args;
with rest = true, every argument the spec does not declare is kept, in order, in opt.rest (for
another parser: smi.study.parse_args is check(argv, {rest = true, options.study_steps})).
options:
  name = (required)     -- a declaration's option name: --name on the command line, opt.name in Lua
                        -- (dashes become underscores)
  type = "string"       -- flag, string, path, number, integer or list (comma-separated, repeatable);
                        -- inferred from a number or boolean default
  default = nil         -- the value when the option is not given (flags: nil unless declared)
  meaning = (required)  -- what the option does (shown by --help)
  allowed = nil         -- the allowed values (every element, for a list)
  min = nil             -- the smallest number allowed
  max = nil             -- the largest number allowed
  check = nil           -- function(v) returning true, or false and why
  input = nil           -- (path) true: the file must exist and be readable; checked at parse,
                        -- so a missing one is named by its option before anything runs
  needs = nil           -- how a missing value is named: "--only needs a step name"
  applies = true        -- false: the option does not apply to this study (a solver option for a Lua
                        -- model): left out of --help, and refused when given, with why_not
  why_not = nil         -- the reason given when an option that does not apply is given
returns: the options table (with opt.help = true when --help was given, opt.args for the spec's
  positional arguments), or nil and a message naming the option and the allowed values; one of
  smi-lua's own options (--out, --seed, --quiet, --timeout, ...) that the spec does not declare is
  refused with "smi-lua's own option --out goes before the script: smi-lua --out DIR study.lua ..."
errors: a bad declaration: a missing meaning, an unknown type, an option declared twice
example:
  local options = require "smi.options"
  local spec = {name = "demo", {name = "metric", default = "pr", allowed = {"pr", "loglik"}, meaning = "metric"},
                {name = "starts", type = "integer", default = 1, min = 1, meaning = "optimizer starts"}}
  print(options.check({"--starts=4"}, spec).starts)
  print(options.check({"--metric", "rmse"}, spec))
]==]
-- After the arguments: the declared defaults of what was not given, and the input files opened
-- (a missing one names the option). Returns nil, or the message.
local function finish(decl, opt, given)
  for _, d in ipairs(decl) do
    local key = d.name:gsub("%-", "_")
    if not given[key] then
      -- a flag not given keeps its declared default (nil when none: smi.study's --quiet must
      -- stay unset so that smi-lua's own --quiet still applies)
      if d.default ~= nil then opt[key] = d.default end
    end
  end
  -- input files are opened now, before the study spends anything: a missing one names the option
  if not opt.help then
    for _, d in ipairs(decl) do
      local key = d.name:gsub("%-", "_")
      if d.input and d.type == "path" and type(opt[key]) == "string" then
        local why = unreadable(opt[key])
        if why then
          return ("--%s%s: cannot read '%s': %s (give the %s with --%s PATH)"):format(d.name,
            given[key] and "" or " (its default)", opt[key], why, d.meaning, d.name)
        end
      end
    end
  end
end

--- Parses argv against spec without exiting: returns opt, or nil and a message naming the
-- option and what it accepts; opt.help is true when --help was given.
function M.check(argv, spec)
  if type(spec) ~= "table" then error("smi.options: spec must be a table of option declarations", 2) end
  local decl, by = declarations(spec)
  local opt, given = { rest = spec.rest and {} or nil }, {}
  argv = argv or {}
  local i = 1
  while i <= #argv do
    local a = tostring(argv[i])
    local name, value = a:match("^%-%-([^=]+)=(.*)$")
    name = name or a:sub(3)
    if spec.rest and not (a:sub(1, 2) == "--" and by[name]) then
      -- spec.rest: what the spec does not declare is kept, in order, for another parser
      opt.rest[#opt.rest + 1] = a
      i = i + 1
    elseif a == "--help" or a == "-h" then
      opt.help = true
      i = i + 1
    elseif a:sub(1, 2) == "--" then
      local d = by[name]
      if not d and M.host_options[name] ~= nil then return nil, host_option_message(name, argv) end
      if d and d.applies == false then
        return nil, ("--%s does not apply to this study%s"):format(name, d.why_not and (": " .. d.why_not) or "")
      end
      if not d then
        local names, shown = {}, {}
        for _, e in ipairs(decl) do
          if e.applies ~= false then names[#names + 1] = "--" .. e.name; shown[e.name] = true end
        end
        local s = suggest(shown, name)
        local h = not s and suggest(M.host_options, name)
        if h then
          return nil, ("unknown option '%s' (did you mean smi-lua's own --%s? %s)"):format(a, h, host_option_message(h, argv))
        end
        return nil, ("unknown option '%s'%s; options: %s (--help explains them)"):format(a, s and (" (did you mean --" .. s .. "?)") or "", table.concat(names, ", "))
      end
      if d.type == "flag" then
        if value ~= nil then
          if value == "true" or value == "1" then value = true elseif value == "false" or value == "0" then value = false
          else return nil, ("--%s is a flag: give it alone (or =true/=false), got '%s'"):format(d.name, value) end
        else value = true end
        i = i + 1
      else
        if value == nil then
          value = argv[i + 1]
          if value == nil or tostring(value):sub(1, 2) == "--" then
            if d.needs then return nil, ("--%s needs %s"):format(d.name, d.needs) end
            return nil, ("--%s needs a value (%s)"):format(d.name, accepts(d) ~= "" and accepts(d) or d.meaning)
          end
          i = i + 2
        else
          i = i + 1
        end
        local v, err = convert(d, value)
        if v == nil then return nil, err end
        value = v
      end
      local key = d.name:gsub("%-", "_")
      if d.type == "list" and type(opt[key]) == "table" and given[key] then
        for _, v in ipairs(value) do opt[key][#opt[key] + 1] = v end
      else
        opt[key] = value
      end
      given[key] = true
    elseif spec.args then
      opt.args = opt.args or {}
      opt.args[#opt.args + 1] = a
      i = i + 1
    else
      return nil, ("unexpected argument '%s': options start with -- (--help lists them)"):format(a)
    end
  end
  local err = finish(decl, opt, given)
  if err then return nil, err end
  return opt
end

doc.add[==[
@ smi.options.parse(argv, spec) -> opt
Parses the script's arguments (arg) against the declared options, as smi.options.check; --help
prints the list and ends the run with status 0, and a wrong value or an unknown option prints
"<study>: --metric: 'rmse' is not allowed; allowed values: pr, loglik" and ends it with status 2.
returns: the options table, defaults filled in
errors: a bad declaration (as smi.options.check); the run ends (os.exit) on --help or a bad value
example:
  local options = require "smi.options"
  local opt = options.parse({"--quick"}, {name = "demo",
    {name = "quick", type = "flag", default = false, meaning = "the reduced run"},
    options.study_steps})
  print(opt.quick, opt.only)
]==]
--- Parses argv (the script's `arg`) against the declared options. --help prints the list and
-- ends the run (exit status 0); a wrong value or an unknown option prints what is wrong, naming
-- the option and its allowed values, and ends the run with status 2 (a usage error).
function M.parse(argv, spec)
  local opt, err = M.check(argv, spec)
  local name = M.script_name(spec)
  if not opt then
    io.stderr:write(name, ": ", err, "\n")
    io.stderr:flush()
    os.exit(2)
  end
  if opt.help then
    io.stdout:write(M.help(spec))
    io.stdout:flush()
    os.exit(0)
  end
  return opt
end

return M
