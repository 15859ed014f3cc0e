-- SPDX-License-Identifier: MIT
--- smi.report.draw: the drawing primitives shared by the chart kinds of smi.report.svg:
-- colours, dashes, markers, text, number formatting of coordinates, the <svg> opening tag.
local xml = require "smi.report.xml"

local M = {}

-- Okabe-Ito colours (distinguishable with the common colour-vision deficiencies), then dashes.
M.palette = { "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442" }
M.dashes = { nil, "6 3", "2 2", "8 3 2 3" }
M.markers = { "circle", "square", "triangle", "diamond" }
M.FONT = "DejaVu Sans, Liberation Sans, Helvetica, Arial, sans-serif"
M.INK, M.NOTE = "#1f2933", "#7b4f00"

--- A pixel coordinate as text (two decimals are below what a screen shows).
-- Points far outside the plot (clipped anyway) are pulled in to +/-1e6 px to keep the text short.
function M.n2(x)
  if x > 1e6 then x = 1e6 elseif x < -1e6 then x = -1e6 end
  return ("%.2f"):format(x)
end
local n2 = M.n2

--- Approximate width in px of `s` at `size` px (DejaVu Sans averages ~0.6 em per character).
function M.text_width(s, size)
  s = tostring(s)
  return (utf8.len(s) or #s) * size * 0.6
end

--- The length of a series (smi.vec or table), or an error naming `what`.
function M.check_series(v, what, level)
  local t = type(v)
  if t ~= "table" and not (t == "userdata" and getmetatable(v) and getmetatable(v).__len) then
    error(("%s: expected a smi.vec or a table of numbers, got %s"):format(what, t), (level or 2) + 1)
  end
  return #v
end

--- <text> at (x, y) with escaped content.
function M.text(x, y, s, attrs)
  attrs = attrs or {}
  attrs.x, attrs.y = n2(x), n2(y)
  return xml.el("text", attrs, s)
end

--- A note line under a chart (skipped points, remarks).
function M.note(x, y, s)
  return M.text(x, y, "Note: " .. s, { ["font-size"] = 10, ["font-style"] = "italic", fill = M.NOTE, class = "note" })
end

--- The opening <svg> tag, its <title> and a white background.
function M.open(W, H, title)
  return ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d" role="img" aria-label="%s" font-family="%s" font-size="11">')
    :format(W, H, W, H, xml.escape(title), M.FONT) .. "\n" .. xml.el("title", nil, title) .. "\n"
    .. xml.el("rect", { x = 0, y = 0, width = W, height = H, fill = "#ffffff" })
end

--- A centred bold chart title that fits the chart: a long one gets smaller type (down to 9 px),
-- and past that is squeezed to the width (textLength) rather than clipped at the edges.
function M.title(W, s)
  local room, size = W - 16, 14
  local w = M.text_width(s, size) * 1.05 -- bold runs ~5 % wider
  local attrs = { ["text-anchor"] = "middle", ["font-size"] = size, ["font-weight"] = "bold", fill = M.INK, class = "title" }
  if w > room then
    size = math.max(9, math.floor(size * room / w * 10) / 10)
    attrs["font-size"] = size
    if M.text_width(s, size) * 1.05 > room then
      attrs.textLength, attrs.lengthAdjust = n2(room), "spacingAndGlyphs"
    end
  end
  return M.text(W / 2, 22, s, attrs)
end

function M.marker(kind, x, y, r, color)
  if kind == "square" then
    return xml.el("rect", { x = n2(x - r), y = n2(y - r), width = n2(2 * r), height = n2(2 * r), fill = color })
  elseif kind == "triangle" then
    return xml.el("path", { d = ("M%s,%sL%s,%sL%s,%sZ"):format(n2(x), n2(y - 1.2 * r), n2(x + 1.1 * r), n2(y + 0.8 * r), n2(x - 1.1 * r), n2(y + 0.8 * r)), fill = color })
  elseif kind == "diamond" then
    return xml.el("path", { d = ("M%s,%sL%s,%sL%s,%sL%s,%sZ"):format(n2(x), n2(y - 1.3 * r), n2(x + 1.3 * r), n2(y), n2(x), n2(y + 1.3 * r), n2(x - 1.3 * r), n2(y)), fill = color })
  end
  return xml.el("circle", { cx = n2(x), cy = n2(y), r = n2(r), fill = color })
end

return M
