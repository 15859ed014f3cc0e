-- SPDX-License-Identifier: MIT
--- What each step of a smi.study used, so that a partial run (--only, --from) never
-- mixes old and new inputs without saying so. A step's inputs, saved beside its result in
-- results.json:
--   inputs = {
--     options = {seed =, arguments = {...}},  -- the study's arguments (--only/--from/--quiet/--force left out)
--     files   = {[path] = {kind =, hash =, size =}},  -- data files read before the steps and while it ran
--     results = {[step] = "sha256:..."},       -- the saved results of earlier steps it read, hashed
--   }
--   result_hash = "sha256:..."                 -- its own saved result, hashed
-- A saved step is current when its options equal this run's, its files hash the same now, and the
-- steps it read are current with the results it read. Otherwise it is stale, and why is said.
-- Lua code (the script, modules) is not a step input of a partial run: `smi-lua verify` checks it,
-- and a whole run compares it before reusing a step (smi.study_reuse; docs/provenance.md).
local json = require "smi.report.json"

local M = {}

-- The host's record of files read (internal functions: the stdlib searcher passes them to
-- stdlib modules only, never to scripts). Taken from `...` by syntax and never handed to a
-- global function: a script may have replaced `select` or `type` before this module loads.
local _, _, internal = ...
local host = internal ~= nil

--- The keys of t (nil: none), sorted: a loop whose first hit becomes a message walks them so,
-- since pairs() order changes from process to process (Lua seeds its string hashes per state).
function M.sorted_keys(t)
  local keys = {}
  for k in pairs(t or {}) do keys[#keys + 1] = k end
  table.sort(keys)
  return keys
end

--- True when the host records inputs (smi-lua); outside it every step counts as current.
function M.available() return host end

-- What is not a step input: the script and the stdlib (checked by verify with the build), and
-- Lua files loaded before the steps ran (the study's own modules: editing one and rerunning a step
-- is the usual way to work; verify names them). A Lua file a step loads itself (a prior read with
-- dofile, a module required inside the step) is an input of that step like a data file.
local SKIP_ALWAYS = { stdlib = true, script = true }

local function pick(files, skip_lua)
  local out = {}
  for path, d in pairs(files or {}) do
    if not SKIP_ALWAYS[d.kind] and not (skip_lua and d.kind == "lua") then
      out[path] = { kind = d.kind, hash = d.hash, size = d.size, large = d.large, mtime = d.mtime }
    end
  end
  return out
end

--- The read counter now (files read after it are the next step's).
function M.mark() return host and internal.inputs(math.maxinteger).seq or 0 end

--- Files a step read after `seq` (data and Lua files it loaded itself).
function M.files_since(seq)
  if not host then return {} end
  return pick(internal.inputs(seq).files, false)
end

--- Data files read before the steps (the script's top level): an input of every step.
function M.preamble()
  if not host then return {} end
  return pick(internal.inputs(0).files, true)
end

--- SHA-256 of a JSON-able value (keys sorted by the encoder, so the same value hashes the same).
function M.hash(v)
  local text = json.encode(v, { root = "hash" })
  if host then return internal.sha256(text) end
  return text -- outside smi-lua: the text itself compares the same way
end

-- The study's own arguments, without the options that only choose which steps run.
local function study_arguments()
  local p = type(smi) == "table" and type(smi.provenance) == "function" and smi.provenance{ files = false } or {}
  local args, out, i = p.arguments or {}, {}, 1
  while i <= #args do
    local a = args[i]
    if a == "--only" or a == "--from" then i = i + 2
    elseif a:match("^%-%-only=") or a:match("^%-%-from=") or a == "--quiet" or a == "--force" then i = i + 1
    else out[#out + 1] = a; i = i + 1 end
  end
  return out, p.command, p.cwd
end

--- This run's options as a step records them: {seed =, arguments = {...}}.
function M.options(seed)
  local args = study_arguments()
  return { seed = seed ~= nil and tostring(seed) or nil, arguments = args }
end

local function words(list) return #list == 0 and "(none)" or table.concat(list, " ") end

--- What differs between two recorded option sets, as a sentence ("" when none).
function M.options_change(old, new)
  old, new = old or {}, new or {}
  local parts = {}
  if tostring(old.seed) ~= tostring(new.seed) then
    parts[#parts + 1] = ("the seed was %s, now %s"):format(tostring(old.seed), tostring(new.seed))
  end
  if M.hash(old.arguments or {}) ~= M.hash(new.arguments or {}) then
    parts[#parts + 1] = ("the study's arguments were '%s', now '%s'"):format(words(old.arguments or {}), words(new.arguments or {}))
  end
  return table.concat(parts, "; ")
end

--- Why the recorded files differ from the files now (nil when they hash the same). cache (optional):
-- a table of digests by path, filled as files are hashed, so a file several steps recorded is
-- hashed once per run.
function M.files_change(files, cache)
  for _, path in ipairs(M.sorted_keys(files)) do -- the first change named is the same every run
    local rec = files[path]
    if host then
      local now, why
      if cache and cache[path] then now, why = table.unpack(cache[path]) else
        now, why = internal.digest(path, rec.kind)
        if cache then cache[path] = { now, why } end
      end
      if not now then return ("file %s, which is no longer readable (%s)"):format(path, tostring(why)) end
      local same = (rec.large or now.large) and (rec.large == now.large and rec.size == now.size and rec.mtime == now.mtime)
        or (not rec.large and not now.large and rec.hash == now.hash)
      if not same then
        return ("file %s, which changed since (recorded %s, now %s)"):format(path, tostring(rec.hash or ("size " .. tostring(rec.size))),
          tostring(now.hash or ("size " .. tostring(now.size))))
      end
    end
  end
  return nil
end

local function shell_word(w)
  if w ~= "" and not w:find("[^%w%-_./=:,+@%%]") then return w end
  return "'" .. w:gsub("'", "'\\''") .. "'"
end

--- The command line that reruns this study from step `name` (this run's own command with
-- --only/--from replaced; the whole study when name is nil), or a hint when the command is not known.
function M.rerun_command(name)
  local _, command = study_arguments()
  if not command or #command == 0 then return name and ("run the study with --from %s"):format(name) or "run the whole study" end
  local out, i = {}, 1
  while i <= #command do
    local a = command[i]
    if a == "--only" or a == "--from" then i = i + 2
    elseif a:match("^%-%-only=") or a:match("^%-%-from=") then i = i + 1
    else out[#out + 1] = shell_word(a); i = i + 1 end
  end
  if name then
    out[#out + 1] = "--from"
    out[#out + 1] = shell_word(name)
  end
  return table.concat(out, " ")
end

return M
