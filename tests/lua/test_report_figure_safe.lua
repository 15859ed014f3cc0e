-- Report figures are held to an allow-list of static SVG: the report
-- promises no scripts and no network, and a figure is embedded in the page as it is. The old
-- check only asked for well-formed XML, so each hostile figure below went into report.html.
local T = require "smi.testing"
local report = require "smi.report"

local hostile = {
  {'<svg xmlns="http://www.w3.org/2000/svg"><script>alert(1)</script></svg>', "<script>"},
  {'<svg xmlns="http://www.w3.org/2000/svg" onload="alert(1)"></svg>', "onload"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect width="1" height="1" onclick="x()"/></svg>', "onclick"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><g ONMOUSEOVER="x()"/></svg>', "ONMOUSEOVER"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><image href="http://evil.example/x.png"/></svg>', "<image>"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><use href="http://evil.example/s.svg#a"/></svg>', "href"},
  {'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"><use xlink:href="file:///etc/passwd#a"/></svg>', "xlink:href"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><foreignObject><iframe src="http://evil.example"></iframe></foreignObject></svg>', "<foreignObject>"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><iframe src="x"></iframe></svg>', "<iframe>"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><a href="javascript:alert(1)"><text>x</text></a></svg>', "<a>"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><set attributeName="href" to="javascript:alert(1)"/></svg>', "<set>"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><animate attributeName="x" values="1"/></svg>', "<animate>"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: url(http://evil.example/p)"/></svg>', "url("},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect fill="url(https://evil.example/p#g)"/></svg>', "url("},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>@import "http://evil.example/c.css";</style></svg>', "@import"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: u\\72l(http://x) }</style></svg>', "escape"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><!-- a --!><script>alert(1)</script> --></svg>', "comments"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><? x ><script>alert(1)</script> ?></svg>', "processing"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><![CDATA[<script>alert(1)</script>]]></svg>', "CDATA"},
}

T.case("every hostile figure is refused, naming what", function()
  for i, h in ipairs(hostile) do
    local ok, err = pcall(function() report.new{title = "t"}:figure(h[1], "c") end)
    T.eq(ok, false, "case " .. i)
    T.truthy(tostring(err):find(h[2], 1, true), "case " .. i .. ": " .. tostring(err))
    local ok2 = pcall(function() report.new{title = "t"}:figures{{h[1], "c"}} end)
    T.eq(ok2, false, "figures, case " .. i)
  end
end)

T.case("static figures pass: the charts of smi.report.svg and hand-made SVG with internal references", function()
  local c = report.svg.chart{title = "Line"}
  c:line({0, 1, 2}, {0, 1, 4})
  report.new{title = "t"}:figure(c, "y = x^2")
  report.new{title = "t"}:figure('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><defs>'
    .. '<linearGradient id="g"><stop offset="0" stop-color="red"/></linearGradient></defs>'
    .. '<rect width="10" height="10" fill="url(#g)" style="stroke: black"/><use href="#g"/>'
    .. '<text x="1" y="5" aria-label="Expression level">a &lt; b</text></svg>', "ok")
end)

T.finish()
