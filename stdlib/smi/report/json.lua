--- smi.report.json: results.json for reports and studies.
-- Uses smi.json.encode/decode when the host provides them; otherwise (and always through
-- M.lua_encode / M.lua_decode) a small encoder/decoder written here.
--   * numbers: integers as integers, floats with %.17g (they read back bit for bit);
--     NaN becomes null, +/-inf becomes 1e999/-1e999 (valid JSON that parsers read as inf)
--   * smi.vec becomes an array, smi.mat an array of rows
--   * keys are sorted, so the same results give the same file
--   * a value JSON cannot hold (function, other userdata) is an error naming its path, or,
--     with opts.skip = true, is left out and its path added to opts.skipped
local doc = require "smi.doc"
doc.add[==[
@ module smi.report.json
JSON for results files: floats with %.17g (they read back bit for bit), NaN as null, infinities as
1e999, vecs as arrays, mats as arrays of rows, keys sorted (the same results give the same file).
]==]
local M = {}

local function typename(v)
  local mt = getmetatable(v)
  return type(mt) == "table" and mt.__name or type(v)
end

local function is_array(t)
  local n = #t
  local count = 0
  for k in pairs(t) do
    if math.type(k) ~= "integer" or k < 1 or k > n then return false end
    count = count + 1
  end
  return count == n
end

local escapes = { ['"'] = '\\"', ["\\"] = "\\\\", ["\b"] = "\\b", ["\f"] = "\\f", ["\n"] = "\\n", ["\r"] = "\\r", ["\t"] = "\\t" }
local function quote(s)
  return '"' .. s:gsub('[%c"\\]', function(c) return escapes[c] or ("\\u%04x"):format(c:byte()) end) .. '"'
end

local function number(x)
  if x ~= x then return "null" end
  if x == math.huge then return "1e999" end
  if x == -math.huge then return "-1e999" end
  if math.type(x) == "integer" then return ("%d"):format(x) end
  return ("%.17g"):format(x)
end

local function encode(v, path, opts, out, indent, depth)
  local t = type(v)
  if t == "number" then out[#out + 1] = number(v); return true end
  if t == "string" then out[#out + 1] = quote(v); return true end
  if t == "boolean" then out[#out + 1] = tostring(v); return true end
  local name = typename(v)
  if name == "smi.vec" then
    local parts = {}
    for i = 1, #v do parts[i] = number(v[i]) end
    out[#out + 1] = "[" .. table.concat(parts, ",") .. "]"
    return true
  end
  if name == "smi.mat" then
    return encode(v:totable(), path, opts, out, indent, depth)
  end
  if t ~= "table" then
    if opts.skip then
      opts.skipped[#opts.skipped + 1] = path .. " (" .. name .. ")"
      return false
    end
    error(("json: %s is a %s, which JSON cannot hold (convert it to numbers or a table, or leave it out)"):format(path, name), 0)
  end
  if depth > 100 then error("json: " .. path .. " nests deeper than 100 levels (a cycle?)", 0) end
  local nl = indent and ("\n" .. string.rep(indent, depth + 1)) or ""
  local close = indent and ("\n" .. string.rep(indent, depth)) or ""
  if next(v) == nil then out[#out + 1] = "[]"; return true end
  if is_array(v) then
    out[#out + 1] = "["
    for i = 1, #v do
      if i > 1 then out[#out + 1] = "," end
      out[#out + 1] = nl
      if not encode(v[i], ("%s[%d]"):format(path, i), opts, out, indent, depth + 1) then out[#out + 1] = "null" end
    end
    out[#out + 1] = close .. "]"
    return true
  end
  local keys = {}
  for k in pairs(v) do
    if type(k) ~= "string" and math.type(k) ~= "integer" then
      error(("json: %s has a key of type %s; JSON keys are strings"):format(path, type(k)), 0)
    end
    keys[#keys + 1] = k
  end
  table.sort(keys, function(a, b)
    if type(a) == type(b) then return a < b end
    return type(a) == "number"
  end)
  out[#out + 1] = "{"
  local first = true
  for _, k in ipairs(keys) do
    local mark = #out
    out[#out + 1] = (first and "" or ",") .. nl .. quote(tostring(k)) .. (indent and ": " or ":")
    local sub = type(k) == "string" and k:match("^[%a_][%w_]*$") and (path .. "." .. k) or ("%s[%q]"):format(path, k)
    if encode(v[k], sub, opts, out, indent, depth + 1) then
      first = false
    else
      for i = #out, mark + 1, -1 do out[i] = nil end
    end
  end
  out[#out + 1] = close .. "}"
  return true
end

doc.add[==[
@ smi.report.json.lua_encode(v [, opts]) -> string
JSON text of v by the encoder written in Lua (what smi.report.json.encode uses for skip and root).
options:
  indent = nil    -- a string per level, e.g. "  " (default: one line)
  skip = false    -- leave out what JSON cannot hold; its paths are appended to opts.skipped
  root = "value"  -- the name used in error paths
returns: a string
errors: a value JSON cannot hold (a function, a userdata), named by its path, unless skip
example:
  local j = require("smi.report").json
  local o = {skip = true, skipped = {}}
  print(j.lua_encode({a = 1, f = print}, o), o.skipped[1])
]==]
--- JSON text of `v`. opts: indent (string, e.g. "  "), skip (leave out what JSON cannot hold;
-- the paths are appended to opts.skipped), root (name used in error paths, "value").
function M.lua_encode(v, opts)
  opts = opts or {}
  opts.skipped = opts.skipped or {}
  local out = {}
  if not encode(v, opts.root or "value", opts, out, opts.indent, 0) then out[#out + 1] = "null" end
  return table.concat(out)
end

-- ---------------------------------------------------------------------------------------------
local function decode_error(s, i, what)
  local line = 1
  for _ in s:sub(1, i - 1):gmatch("\n") do line = line + 1 end
  error(("json: %s at line %d (byte %d)"):format(what, line, i), 0)
end

local parse_value

local function skip_ws(s, i)
  return s:find("[^ \t\r\n]", i) or #s + 1
end

local function parse_string(s, i)
  local out, j = {}, i + 1
  while true do
    local c = s:sub(j, j)
    if c == "" then decode_error(s, i, "unterminated string") end
    if c == '"' then return table.concat(out), j + 1 end
    if c == "\\" then
      local e = s:sub(j + 1, j + 1)
      local map = { b = "\b", f = "\f", n = "\n", r = "\r", t = "\t", ['"'] = '"', ["\\"] = "\\", ["/"] = "/" }
      if map[e] then
        out[#out + 1] = map[e]; j = j + 2
      elseif e == "u" then
        local hex = s:sub(j + 2, j + 5)
        if not hex:match("^%x%x%x%x$") then decode_error(s, j, "bad \\u escape") end
        local cp = tonumber(hex, 16)
        j = j + 6
        if cp >= 0xD800 and cp <= 0xDBFF and s:sub(j, j + 1) == "\\u" then
          local lo = tonumber(s:sub(j + 2, j + 5), 16)
          if lo and lo >= 0xDC00 and lo <= 0xDFFF then
            cp = 0x10000 + (cp - 0xD800) * 0x400 + (lo - 0xDC00)
            j = j + 6
          end
        end
        out[#out + 1] = utf8.char(cp)
      else
        decode_error(s, j, "bad escape \\" .. e)
      end
    else
      local k = s:find('["\\]', j) or #s + 1
      out[#out + 1] = s:sub(j, k - 1)
      j = k
    end
  end
end

function parse_value(s, i)
  i = skip_ws(s, i)
  local c = s:sub(i, i)
  if c == "{" then
    local t = {}
    i = skip_ws(s, i + 1)
    if s:sub(i, i) == "}" then return t, i + 1 end
    while true do
      i = skip_ws(s, i)
      if s:sub(i, i) ~= '"' then decode_error(s, i, "expected a key string") end
      local k
      k, i = parse_string(s, i)
      i = skip_ws(s, i)
      if s:sub(i, i) ~= ":" then decode_error(s, i, "expected ':'") end
      t[k], i = parse_value(s, i + 1)
      i = skip_ws(s, i)
      local d = s:sub(i, i)
      if d == "}" then return t, i + 1 end
      if d ~= "," then decode_error(s, i, "expected ',' or '}'") end
      i = i + 1
    end
  elseif c == "[" then
    local t, n = {}, 0
    i = skip_ws(s, i + 1)
    if s:sub(i, i) == "]" then return t, i + 1 end
    while true do
      n = n + 1
      t[n], i = parse_value(s, i)
      i = skip_ws(s, i)
      local d = s:sub(i, i)
      if d == "]" then return t, i + 1 end
      if d ~= "," then decode_error(s, i, "expected ',' or ']'") end
      i = i + 1
    end
  elseif c == '"' then
    return parse_string(s, i)
  elseif s:sub(i, i + 3) == "true" then return true, i + 4
  elseif s:sub(i, i + 4) == "false" then return false, i + 5
  elseif s:sub(i, i + 3) == "null" then return 0 / 0, i + 4 -- null only ever stands for NaN here
  else
    local num = s:match("^-?%d+%.?%d*[eE]?[-+]?%d*", i)
    local v = num and tonumber(num)
    if not v then decode_error(s, i, "unexpected " .. (c == "" and "end of text" or ("'" .. c .. "'"))) end
    return v, i + #num
  end
end

doc.add[==[
@ smi.report.json.lua_decode(s) -> value
The Lua value of JSON text by the decoder written in Lua (null reads as NaN).
returns: the value
errors: invalid JSON, with the position
example:
  local j = require("smi.report").json
  print(j.lua_decode('{"x": [1, 2.5]}').x[2])
]==]
--- The Lua value of JSON text `s` (null reads as NaN: this module writes NaN as null).
function M.lua_decode(s)
  local v, i = parse_value(s, 1)
  i = skip_ws(s, i)
  if i <= #s then decode_error(s, i, "trailing text") end
  return v
end

local host = type(smi) == "table" and type(smi.json) == "table" and smi.json or nil

doc.add[==[
@ smi.report.json.encode(v [, opts]) -> string
JSON text of v: the host's smi.json.encode when opts need nothing only the Lua encoder does, else
smi.report.json.lua_encode (same options).
options:
  indent = nil    -- a string per level, e.g. "  "
  skip = false    -- as lua_encode
  root = "value"  -- as lua_encode
returns: a string
errors: as lua_encode
example:
  local j = require("smi.report").json
  print(j.encode({b = 2, a = smi.vec{1, 2}}))
]==]
--- Encode with the host's smi.json when present (unless opts ask for what only ours does).
function M.encode(v, opts)
  if host and host.encode and not (opts and (opts.skip or opts.indent)) then return host.encode(v) end
  return M.lua_encode(v, opts)
end

doc.add[==[
@ smi.report.json.decode(s) -> value
The Lua value of JSON text (null reads as NaN, as this module writes NaN as null).
returns: the value
errors: invalid JSON
example:
  local j = require("smi.report").json
  local t = j.decode('{"u": null}')
  print(t.u ~= t.u)
]==]
function M.decode(s)
  if host and host.decode then return host.decode(s) end
  return M.lua_decode(s)
end

return M
