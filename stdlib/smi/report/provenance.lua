-- SPDX-License-Identifier: MIT
--- The report's last section: what produced these numbers. The script, the data
-- and other files read, the solver programs, the libraries, the versions of smi-lua and what it
-- was built with, and the command line that reproduces the run, from smi.provenance().
--
--   local section = require("smi.report.provenance").begin(report)  -- after the story
--   section:fill(smi.provenance(), {study = "beam", results = path})  -- once the run has read all
--
-- begin() places the section and its table where the report stands (smi.study: last, after the
-- steps and before the run details); fill() writes their rows. smi.study does both for any study
-- that has a report. The same table goes
-- into the report's JSON (r:data().tables) like any other.
local M = {}

local function short(h) return type(h) == "string" and h:gsub("^sha256:", ""):sub(1, 16) or "" end

local function shell_word(w)
  w = tostring(w)
  if w ~= "" and not w:find("[^%w%-_./=:,+@%%]") then return w end
  return "'" .. w:gsub("'", "'\\''") .. "'"
end

--- The command line that reproduces a run: cd to where it ran, then the same argv.
function M.command_line(p)
  if type(p) ~= "table" or type(p.command) ~= "table" or #p.command == 0 then return nil end
  local words = {}
  for i, w in ipairs(p.command) do words[i] = shell_word(w) end
  local cmd = table.concat(words, " ")
  if p.cwd and p.cwd ~= "" then cmd = "cd " .. shell_word(p.cwd) .. " && " .. cmd end
  return cmd
end

local function file_digest(d)
  if d.large then return ("size %s, mtime %s (over 1 GB, not hashed)"):format(tostring(d.size), tostring(d.mtime)) end
  return short(d.hash)
end

-- What a file is, for the table's first column.
local KIND = { script = "script", lua = "Lua module", stdlib = "stdlib (embedded)", data = "data file" }

--- Rows {what, name, detail, digest} of the provenance table, in a fixed order: the script, data
-- files, Lua modules, programs, libraries, options, versions. Embedded stdlib modules are
-- summed up in one row (their versions follow smi-lua's).
function M.rows(p, extra)
  local rows = {}
  local function add(what, name, detail, digest) rows[#rows + 1] = { what, name, detail or "", digest or "" } end
  extra = extra or {}
  if extra.study then add("study", extra.study, extra.results and ("results: " .. extra.results) or "", "") end
  if p.script then add("script", p.script.path, "", short(p.script.hash)) end
  local files, embedded = {}, 0
  for path, d in pairs(p.files or {}) do
    if d.kind == "stdlib" then embedded = embedded + 1
    elseif d.kind ~= "script" and d.kind ~= "program" then files[#files + 1] = { path = path, d = d } end
  end
  local order = { data = 1, lua = 2 }
  table.sort(files, function(a, b)
    local ka, kb = order[a.d.kind] or 3, order[b.d.kind] or 3
    if ka ~= kb then return ka < kb end
    return a.path < b.path
  end)
  for _, f in ipairs(files) do
    add(KIND[f.d.kind] or f.d.kind or "file", f.path,
      (f.d.changed_during_run and "changed while the run read it; " or "") .. (f.d.size and (tostring(f.d.size) .. " bytes") or ""),
      file_digest(f.d))
  end
  if embedded > 0 then add("stdlib", ("%d module%s embedded in smi-lua"):format(embedded, embedded == 1 and "" or "s"), "", "") end
  for _, pr in ipairs(p.programs or {}) do
    local detail = {}
    if pr.name and pr.name ~= pr.path then detail[#detail + 1] = "run as " .. pr.name end
    if pr.version then detail[#detail + 1] = "version " .. pr.version end
    if pr.version_line then detail[#detail + 1] = "says: " .. pr.version_line end
    add("solver", pr.path, table.concat(detail, ", "),
      file_digest(pr))
  end
  if not p.libraries or #p.libraries == 0 then add("libraries", "none (no --lib, no SMI_PATH)", "", "") end
  for _, l in ipairs(p.libraries or {}) do
    add("library", l.name .. " " .. tostring(l.version),
      (l.commit and ("commit " .. l.commit:sub(1, 12) .. ", ") or "") .. tostring(l.path), short(l.hash))
  end
  local opts = {}
  for k, v in pairs(p.options or {}) do
    opts[#opts + 1] = k .. " " .. (type(v) == "table" and table.concat(v, " ") or tostring(v))
  end
  table.sort(opts)
  if #opts > 0 then add("options", table.concat(opts, "; "), "", "") end
  if p.arguments then add("arguments", #p.arguments > 0 and table.concat(p.arguments, " ") or "(none)", "", "") end
  local b = p.build or {}
  add("smi-lua", tostring(p.smi_lua or b["smi-lua"] or "?"), tostring(b.build or ""), "")
  local versions = {}
  for _, k in ipairs({ "compiler", "lua", "eigen", "nlopt", "sqlite", "re2", "nettle", "fmt" }) do
    if b[k] then versions[#versions + 1] = k .. " " .. b[k] end
  end
  if #versions > 0 then add("built with", table.concat(versions, "; "), "", "") end
  return rows
end

local Section = {}
Section.__index = Section

--- Places the provenance section in `report` where it stands (a study: last) and returns a handle whose :fill(p, extra) writes its rows at the end of the run.
function M.begin(report)
  report:section("Provenance")
  report:text("What produced these numbers: filled in when the run ends.")
  local text_item = report.items[#report.items]
  report:table{ caption = "Every input of this run with its SHA-256 (first 16 hex digits); `smi-lua verify results.json` checks them all again.",
                columns = { "What", "Name", "Detail", "SHA-256" }, rows = {} }
  local table_item = report.items[#report.items]
  return setmetatable({ text = text_item, table = table_item }, Section)
end

--- Fills the section from a provenance table (smi.provenance()); extra = {study =, results =}.
function Section:fill(p, extra)
  if type(p) ~= "table" then
    self.text.text = "No provenance was recorded (run outside smi-lua)."
    return self
  end
  local rows = M.rows(p, extra)
  for i = #self.table.rows, 1, -1 do self.table.rows[i] = nil end
  for i, r in ipairs(rows) do self.table.rows[i] = r end
  local cmd = M.command_line(p)
  self.text.text = cmd and ("To reproduce this run: " .. cmd) or "The command line of this run was not recorded."
  return self
end

return M
