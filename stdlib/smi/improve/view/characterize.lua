-- SPDX-License-Identifier: MIT
--- The report's characterization section: KDE against KDE-ebd per response (the step's result
-- `out`, the curves it drew and the number of data).
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"

return function(run, r, out, curves, n)
  local D = run.D
  local figures, rows = {}, {}
  for _, m in ipairs(D.names) do
    local resp, o = D.by_name[m], out[m]
    figures[#figures + 1] = { figs.kde_vs_ebd(resp, curves[m]),
                              resp.title .. ": KDE of the data and KDE with estimated bounded data." }
    rows[#rows + 1] = { resp.title, o.mean, o.std, o.kde_bandwidth, o.ebd_bandwidth, o.ebd_lower, o.ebd_upper, o.ebd_added }
  end
  r:section("Uncertainty characterization (KDE vs KDE-ebd)")
  r:text(text.characterize_intro(n))
  r:figures(figures)
  r:table{ caption = "Data summary and bandwidths.", rows = rows,
           columns = { "Response", "Mean", "Std", "h KDE", "h KDE-ebd", "ebd lower", "ebd upper",
                       { title = "Points added", format = "%d" } } }
end
