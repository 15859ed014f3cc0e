-- SPDX-License-Identifier: MIT
--- smi.doc.cli: `smi-lua doc` (host/cli/commands_doc.cpp calls main with the words after "doc").
local doc = require "smi.doc"

local M = {}

function M.main(words)
  if words[1] == "--html" then
    local dir = words[2]
    local guides = {}  -- --guide <file>, one Markdown guide each (commands_doc.cpp lists the folder)
    for i = 3, #words - 1 do if words[i] == "--guide" then guides[#guides + 1] = words[i + 1] end end
    local pages, examples = require("smi.doc.html").write(dir, guides)
    print(("%s/index.html: %d pages, %d entries, %d examples run"):format(dir, pages, #doc.list(), examples))
    return 0
  end
  if words[1] == "--missing" or words[1] == "--check" then
    local missing, stale = doc.missing()
    for _, n in ipairs(missing) do io.stderr:write("no doc text: ", n, "\n") end
    for _, n in ipairs(stale) do io.stderr:write("doc text for a name that does not exist: ", n, "\n") end
    local bad = #missing + #stale
    if words[1] == "--missing" then
      print(("%d public names, %d without a complete doc text, %d stale texts"):format(#doc.walk(), #missing, #stale))
      return bad > 0 and 1 or 0
    end
    local failed, n = doc.check_examples(false)
    -- the examples called the functions: compare the options they read with the documented ones
    local drift = doc.check_options()
    for _, p in ipairs(drift) do io.stderr:write("option list: ", p, "\n") end
    print(("%d public names documented (%d missing, %d stale); %d examples run, %d failed; %d option lists differ from the code"):format(
      #doc.walk() - #missing, #missing, #stale, n, failed, #drift))
    return (bad + failed + #drift) > 0 and 1 or 0
  end
  local text, none = doc.help_text(words[1] and table.concat(words, " ") or nil)
  if none then
    -- nothing named so and nothing mentions it: the closest names, and a usage status
    io.stderr:write(text, "\n")
    return 2
  end
  print(text)
  return 0
end

return M
