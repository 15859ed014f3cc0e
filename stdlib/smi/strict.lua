-- SPDX-License-Identifier: MIT
--- smi.strict: an opt-in strict mode for a study. After require("smi.strict").on(), reading a
-- global that does not exist is an error naming it (and the closest global that does), instead
-- of a silent nil: a misspelt `smi.sed` is a field and stays nil, but a misspelt `improv.run` or
-- a forgotten `local` is caught where it happens. Globals may still be assigned; a global set to
-- nil on purpose is read as nil.
local doc = require "smi.doc"
doc.add[==[
@ module smi.strict
An opt-in strict mode for studies: reading an undefined global becomes an error naming it.

@ smi.strict.on([env]) -> env
Makes reading an undefined global of env (default: the calling script's globals, _G) an error
that names the global, the closest defined one and where it was read. Assigning globals stays
allowed; a name assigned once (even to nil) reads without error afterwards.
returns: env
errors: env already has a metatable that is not smi.strict's ("smi.strict: the globals already
  have a metatable")
example:
  local strict = require "smi.strict"
  local env = strict.on(setmetatable({}, nil))
  env.x = 1
  print(env.x, pcall(function() return env.y end))
]==]
local M = {}

local MARK = {}

function M.on(env)
  env = env or _G
  local mt = getmetatable(env)
  if mt and mt[MARK] then return env end
  if mt ~= nil then error("smi.strict: the globals already have a metatable", 2) end
  local declared = {}
  setmetatable(env, {
    [MARK] = true,
    __newindex = function(t, k, v) declared[k] = true rawset(t, k, v) end,
    __index = function(t, k)
      if declared[k] then return nil end
      local names = {}
      for name in pairs(t) do if type(name) == "string" then names[#names + 1] = name end end
      table.sort(names)
      local near = type(k) == "string" and smi and smi._closest and smi._closest(k, names, 1) or {}
      error(("undefined global '%s'%s (smi.strict: declare it with local, or assign it first)"):format(
        tostring(k), near[1] and (" (did you mean '" .. near[1] .. "'?)") or ""), 2)
    end,
  })
  return env
end

return M
