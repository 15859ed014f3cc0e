-- SPDX-License-Identifier: MIT
--- The report's "Experimental data" section: the measurements, the data file's warnings and the
-- units check (the data step's result `out`; words: the nominal run, per response).
local text = require "smi.improve.text"

return function(run, r, out, words)
  local D = run.D
  r:section("Experimental data")
  r:text(text.data_intro(D, out.n, out.file))
  local rows, columns = {}, { "Specimen" }
  for j, rr in ipairs(D.responses) do
    columns[j + 1] = { title = rr.title .. (rr.unit ~= "" and (" (" .. rr.unit .. ")") or ""), digits = 6 }
  end
  for i = 1, out.n do
    rows[i] = { i }
    for j, rr in ipairs(D.responses) do rows[i][j + 1] = out[rr.name][i] end
  end
  r:table{ caption = "Measured responses.", rows = rows, columns = columns }
  for _, w in ipairs(out.warnings or {}) do r:callout("Data: " .. w, "warn") end
  r:text(text.units_intro(words))
  for _, p in ipairs(out.units) do r:callout(p, "warn") end
end
