-- SPDX-License-Identifier: MIT
--- smi-column-fe as the study drives it: decks written from the spec's inputs, per-point runs
-- through smi.model.command (one deck and one .f06 per point, as with Nastran) and many points
-- per process through smi.model.batch (`smi-column-fe --batch`). Every run goes through the
-- evaluation store, so a rerun of the study reuses them (smi.improve counts them).
local inputs = require "steering_column.inputs"

local M = {}

--- Deck text: airbag variant, every input at its nominal value except `vary` (placeholders
-- {{name:%.17g}} for smi.model.command) and `fixed` ({name = value}).
function M.deck(airbag, vary, fixed)
  local placeholder = {}
  for _, n in ipairs(vary or {}) do placeholder[n] = true end
  fixed = fixed or {}
  local lines = { "# steering column analog, written by scripts/steering_column.lua", "airbag_model = " .. airbag }
  local names = {}
  for i, n in ipairs(inputs.names) do names[i] = n end
  if airbag == "spring" then names[#names + 1] = "airbag_stiffness" end
  for _, n in ipairs(names) do
    if placeholder[n] then
      lines[#lines + 1] = ("%s = {{%s:%%.17g}}"):format(n, n)
    else
      lines[#lines + 1] = ("%s = %.17g"):format(n, fixed[n] or inputs.nominal[n])
    end
  end
  return table.concat(lines, "\n") .. "\n"
end

--- A per-point model: inputs `vary`, outputs mode1, mode2, mode4 (paper modes, Hz).
-- opts: solver (path), airbag, vary, fixed, name, concurrency.
function M.command(opts)
  local m = smi.model.command{
    name = opts.name, inputs = opts.vary, outputs = { "mode1", "mode2", "mode4" },
    template_string = M.deck(opts.airbag, opts.vary, opts.fixed), deck = "column.deck",
    command = { opts.solver, "{deck}", "-o", "column.f06" },
    parse = function(dir, h)
      local r = h.f06("column.f06")
      return { mode1 = r.paper_hz[1], mode2 = r.paper_hz[2], mode4 = r.paper_hz[4] }
    end,
    concurrency = opts.concurrency or 2, on_failure = "stop",
  }
  return m
end

--- A batch model over `vary` (any of the 46 inputs, airbag_stiffness): the base deck holds the
-- rest. opts: solver, airbag, vary, name, base (path of the base deck, written by the caller
-- under the output folder), batch_size, concurrency.
function M.batch(opts)
  local m = smi.model.batch{
    name = opts.name, inputs = opts.vary, outputs = { "mode1", "mode2", "mode4" },
    input_file = "points.csv", files = { opts.base },
    command = { opts.solver, "--batch", "{deck}", "--base", opts.base:match("[^/]+$"), "-o", "modes.csv" },
    parse = function(dir, h, n)
      return { mode1 = h.csv("modes.csv", "mode1_hz"), mode2 = h.csv("modes.csv", "mode2_hz"),
               mode4 = h.csv("modes.csv", "mode4_hz") }
    end,
    batch_size = opts.batch_size or 0, concurrency = opts.concurrency or 2, on_failure = "stop",
  }
  return m
end

--- Writes a base deck (all inputs nominal, `fixed` overrides) to `path`; returns path.
function M.write_deck(path, airbag, fixed)
  local f = assert(io.open(path, "wb"))
  f:write(M.deck(airbag, {}, fixed))
  f:close()
  return path
end

return M
