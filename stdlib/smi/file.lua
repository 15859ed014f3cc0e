-- SPDX-License-Identifier: MIT
--- smi.file: writing a results file so that it is never torn or shortened.
--
--   require("smi.file").write(path, text, "study 'beam'")
--
-- Inside smi-lua this is smi.write_file (temporary file beside the target, every write checked,
-- fsync, rename over the target): a full disk or a crash leaves the previous file as it was and
-- raises an error naming the file and the reason. Outside smi-lua (plain Lua), the same steps
-- without fsync, every result checked.
local M = {}

-- A file that cannot be written is the run's environment, not its code: one line (smi.fail).
local function fail(msg)
  if type(smi) == "table" and type(smi.fail) == "function" then smi.fail(msg) end
  error(msg, 0)
end

function M.write(path, text, who)
  if type(smi) == "table" and type(smi.write_file) == "function" then
    local ok, err = pcall(smi.write_file, path, text)
    if not ok then fail(("%s: %s"):format(who, (tostring(err):gsub("^smi%.write_file: ", "")))) end
    return path
  end
  local tmp = path .. ".tmp"
  local f, err = io.open(tmp, "wb")
  if not f then fail(("%s: cannot write '%s': %s (does the folder exist and is it under --out?)"):format(who, path, tostring(err))) end
  local ok, werr = f:write(text)
  if ok then ok, werr = f:flush() end
  local closed, cerr = f:close()
  if not ok or not closed then
    os.remove(tmp)
    fail(("%s: cannot write '%s': %s; the previous file is unchanged"):format(who, path, tostring(werr or cerr)))
  end
  local renamed, rerr = os.rename(tmp, path)
  if not renamed then
    os.remove(tmp)
    fail(("%s: cannot write '%s': %s; the previous file is unchanged"):format(who, path, tostring(rerr)))
  end
  return path
end

return M
