-- SPDX-License-Identifier: MIT
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
  -- CSS is held to an allow-list of properties, values and functions: every spelling of a fetch is refused
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: image-set("https://evil.example/a.png" 1x) }</style></svg>', "image-set()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: -webkit-image-set(url(https://evil.example/a.png) 1x) }</style></svg>', "-webkit-image-set()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: image(&quot;https://evil.example/a.png&quot;)"/></svg>', "image()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: cross-fade(url(#a), url(#b))"/></svg>', "cross-fade()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: element(#a)"/></svg>', "element()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: expression(alert(1))"/></svg>', "expression()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect fill="image-set(&quot;https://evil.example/a.png&quot; 1x)"/></svg>', "attribute fill"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect stroke="URL(https://evil.example/p)"/></svg>', "only url(#id)"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: URL( "https://evil.example/p" ) }</style></svg>', "only url(#id)"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: url(#a), url(https://evil.example/p) }</style></svg>', "only url(#id)"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { mask: url(https://evil.example/m.svg#m) }</style></svg>', "only url(#id)"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: \\75 rl(https://evil.example/p) }</style></svg>', "escape"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: u/**/rl(https://evil.example/p) }</style></svg>', "comment"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>@IMPORT "https://evil.example/c.css";</style></svg>', "at-rule"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>@font-face { font-family: x; src: url(https://evil.example/f.woff) }</style></svg>', "at-rule"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>@namespace x url(https://evil.example/);</style></svg>', "at-rule"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="--a: url(https://evil.example/p); fill: var(--a)"/></svg>', "property '--a'"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: var(--a)"/></svg>', "var()"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="background-image: linear-gradient(red, blue)"/></svg>', "property 'background-image'"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="cursor: url(https://evil.example/c.cur), auto"/></svg>', "property 'cursor'"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="content: url(https://evil.example/p)"/></svg>', "property 'content'"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="-moz-binding: url(https://evil.example/x.xml)"/></svg>', "property '-moz-binding'"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: red; } @import x; rect {"/></svg>', "at-rule"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><rect style="fill: javascript:alert(1)"/></svg>', "character ':'"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: red; { stroke: url(https://evil.example/p) } }</style></svg>', "nested block"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>rect { fill: red }<g/>image { }</style></svg>', "text only"},
  {'<svg xmlns="http://www.w3.org/2000/svg"><style>&lt;!-- rect { fill: red } --&gt;</style></svg>', "<!--"},
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
  -- CSS within the allow-list: rules, selectors, colours, fonts, transforms, url(#id)
  report.new{title = "t"}:figure('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><style>'
    .. '.a > rect:not(.b), g#c text[data-x="1"] { fill: rgba(0, 0, 255, .5) !important; stroke: #0000ff }'
    .. ' text { font: italic 12px/1.2 "DejaVu Sans", sans-serif; text-anchor: middle }</style>'
    .. '<rect width="10" height="10" style="fill: url( \'#g\' ) red; stroke-dasharray: 4 2; '
    .. 'transform: translate(1px, -2.5e-1px) rotate(-90deg)" clip-path="url(#g)" stroke="#abc"/></svg>', "ok")
end)

T.finish()
