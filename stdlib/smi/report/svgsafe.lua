-- SPDX-License-Identifier: MIT
--- smi.report.svgsafe: the figure sanitiser. A report promises no scripts and no network, and
-- a figure's SVG is embedded in the page as it is, so it is held to an allow-list:
-- elements and attributes of static vector graphics only; no script, foreignObject, iframe,
-- image, animation or link element; no on* handler; href only to "#id" inside the figure;
-- CSS (style attributes, <style> sheets, presentation attributes such as fill) held to the
-- allow-list of csssafe.lua, so url() reaches only "#id" and no other function fetches; and no
-- comment, CDATA, processing instruction or DOCTYPE, which an HTML parser reads differently
-- from an XML one (`<!-- --!>` ends an HTML comment early, `<? >` is a bogus comment that ends
-- at the first '>'), so what was checked would not be what the browser runs.
--
--   local ok, err = svgsafe.check(svg)   -- err names the element or attribute refused
local csssafe = require "smi.report.csssafe"
local xmlcheck = require "smi.report.xmlcheck"

local M = {}

local set = csssafe.set

M.elements = set{
  "svg", "g", "defs", "symbol", "use", "title", "desc", "metadata", "style",
  "path", "line", "polyline", "polygon", "rect", "circle", "ellipse",
  "text", "tspan", "textPath",
  "clipPath", "mask", "marker", "pattern", "linearGradient", "radialGradient", "stop",
  "filter", "feGaussianBlur", "feOffset", "feBlend", "feFlood", "feComposite", "feMerge", "feMergeNode",
  "feColorMatrix",
}

M.attributes = set{
  "xmlns", "xmlns:xlink", "version", "id", "class", "style", "role", "lang", "xml:lang", "xml:space",
  "x", "y", "x1", "y1", "x2", "y2", "cx", "cy", "r", "rx", "ry", "dx", "dy", "width", "height",
  "d", "points", "pathLength", "transform", "viewBox", "preserveAspectRatio",
  "fill", "fill-opacity", "fill-rule", "stroke", "stroke-width", "stroke-opacity", "stroke-dasharray",
  "stroke-dashoffset", "stroke-linecap", "stroke-linejoin", "stroke-miterlimit", "opacity", "color",
  "visibility", "display", "overflow", "vector-effect", "shape-rendering", "text-rendering", "paint-order",
  "clip-path", "clip-rule", "clipPathUnits", "mask", "maskUnits", "maskContentUnits", "filter",
  "filterUnits", "primitiveUnits", "in", "in2", "result", "stdDeviation", "mode", "operator", "values",
  "type", "flood-color", "flood-opacity",
  "marker-start", "marker-mid", "marker-end", "markerWidth", "markerHeight", "markerUnits", "refX", "refY",
  "orient", "patternUnits", "patternContentUnits", "patternTransform",
  "gradientUnits", "gradientTransform", "offset", "stop-color", "stop-opacity", "spreadMethod", "fx", "fy",
  "font-family", "font-size", "font-weight", "font-style", "font-variant", "text-anchor",
  "dominant-baseline", "alignment-baseline", "baseline-shift", "letter-spacing", "word-spacing",
  "text-decoration", "writing-mode", "startOffset", "method", "spacing", "rotate", "lengthAdjust",
  "textLength", "href", "xlink:href", "xlink:title",
  "aria-label", "aria-hidden", "aria-labelledby", "aria-describedby", "tabindex", "focusable",
}

local function walk(el)
  if not M.elements[el.name] then
    return ("element <%s> is not allowed in a figure (no scripts, embedded pages, images, links or animation)")
      :format(el.name)
  end
  local names = {} -- in name order: of several refused attributes the one named is the same every run
  for name in pairs(el.attrs) do names[#names + 1] = name end
  table.sort(names)
  for _, name in ipairs(names) do
    local value = el.attrs[name]
    if name:lower():match("^on") then return ("event handler %s on <%s> is not allowed"):format(name, el.name) end
    if not M.attributes[name] and not name:match("^data%-[%w%-]+$") then
      return ("attribute %s on <%s> is not allowed in a figure"):format(name, el.name)
    end
    if (name == "href" or name == "xlink:href") and not value:match("^#[%w_%-%.:]+$") then
      return ("%s='%s' on <%s>: a figure may refer only to its own elements (\"#id\"), never to a file or the network")
        :format(name, value, el.name)
    end
    -- A style is CSS declarations, a presentation attribute (fill, clip-path, marker-end ...) a
    -- CSS value: both held to csssafe's allow-list. Any other value that names a url() may only
    -- point inside the figure.
    local why
    if name == "style" then
      why = csssafe.declarations(value)
    elseif csssafe.properties[name] then
      why = csssafe.value(name, value)
    else
      for arg in value:lower():gmatch("url%s*%(%s*([^%)]*)") do
        if not arg:match("^[\"']?#") then why = why or ("url(" .. arg .. ") (only url(#id) inside the figure)") end
      end
    end
    if why then return ("attribute %s on <%s>: %s is not allowed in a figure"):format(name, el.name, why) end
  end
  if el.name == "style" then
    for _, c in ipairs(el.children) do
      if type(c) == "table" then return ("<style> in a figure holds text only, not <%s>"):format(c.name) end
    end
    local why = csssafe.sheet(el.text or "")
    if why then return ("<style> in a figure: %s is not allowed"):format(why) end
  end
  for _, c in ipairs(el.children) do
    if type(c) == "table" then
      local why = walk(c)
      if why then return why end
    end
  end
  return nil
end

--- true, or false and the reason (which element or attribute, and why).
function M.check(svg)
  local at = svg:find("<[!?]")
  if at then
    return false, "comments, CDATA, processing instructions and DOCTYPE are not allowed in a figure (an HTML page "
      .. "reads them differently from XML)"
  end
  local ok, root = pcall(xmlcheck.parse, svg)
  if not ok then return false, "the SVG is not well-formed XML: " .. tostring(root) end
  if root.name ~= "svg" then return false, "the root element must be <svg>, got <" .. root.name .. ">" end
  local why = walk(root)
  if why then return false, why end
  return true
end

return M
