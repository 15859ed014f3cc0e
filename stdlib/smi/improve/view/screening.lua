-- SPDX-License-Identifier: MIT
--- The report's screening section: the normalized area metrics per response and the unknowns
-- the declared rule chose (the screening step's result `out`).
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"

return function(run, r, out)
  local D = run.D
  local chosen, figures = {}, {}
  for _, n in ipairs(out.unknowns) do chosen[n] = true end
  for _, m in ipairs(D.names) do
    figures[#figures + 1] = { figs.screening(D.by_name[m], out.responses[m].rows, chosen), D.by_name[m].title
      .. ": the ten largest normalized area metrics; highlighted: the trial-1 unknowns." }
  end
  r:section("Variable screening")
  r:text(text.screening_intro(D, out))
  r:figures(figures)
  local rows = {}
  for _, m in ipairs(D.names) do
    local t = out.responses[m].rows
    rows[#rows + 1] = { D.by_name[m].title }
    for i = 1, 4 do rows[#rows][i + 1] = t[i] and ("%s %.3f"):format(t[i].input, t[i].ne) or "" end
  end
  r:table{ caption = "The four most influential inputs per response (normalized area metric).",
           columns = { "Response", "1st", "2nd", "3rd", "4th" }, rows = rows }
  local note = D.screening.note
  if note then local w, kind = note(out) if w then r:callout(w, kind or "info") end end
  r:text(("Trial 1's unknowns (the declaration's screening rule): %s."):format(table.concat(out.unknowns, ", ")))
end
