--- smi.report.svgsafe: the figure sanitiser. A report promises no scripts and no network, and
-- a figure's SVG is embedded in the page as it is, so it is held to an allow-list:
-- elements and attributes of static vector graphics only; no script, foreignObject, iframe,
-- image, animation or link element; no on* handler; href only to "#id" inside the figure;
-- styles without url(...) (but url(#id)), @import, expression() or CSS escapes; and no
-- comment, CDATA, processing instruction or DOCTYPE, which an HTML parser reads differently
-- from an XML one (`<!-- --!>` ends an HTML comment early, `<? >` is a bogus comment that ends
-- at the first '>'), so what was checked would not be what the browser runs.
--
--   local ok, err = svgsafe.check(svg)   -- err names the element or attribute refused
local xmlcheck = require "smi.report.xmlcheck"

local M = {}

local function set(list)
  local s = {}
  for _, v in ipairs(list) do s[v] = true end
  return s
end

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

-- CSS (a style attribute or a <style> element) that can fetch or run something.
local function css_refusal(css)
  local low = css:lower()
  if low:find("\\", 1, true) then return "a CSS escape ('\\')" end
  if low:find("@import", 1, true) then return "@import" end
  if low:find("expression", 1, true) then return "expression()" end
  if low:find("javascript:", 1, true) then return "javascript:" end
  for arg in low:gmatch("url%s*%(%s*([^%)]*)") do
    if not arg:match("^[\"']?#") then return "url(" .. arg .. ") (only url(#id) inside the figure)" end
  end
  return nil
end

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
    -- A style is CSS; any other value that names a url() (fill, clip-path, marker-end ...) may
    -- only point inside the figure.
    local why = name == "style" and css_refusal(value) or nil
    for arg in value:lower():gmatch("url%s*%(%s*([^%)]*)") do
      if not arg:match("^[\"']?#") then why = why or ("url(" .. arg .. ") (only url(#id) inside the figure)") end
    end
    if why then return ("attribute %s on <%s>: %s is not allowed in a figure"):format(name, el.name, why) end
  end
  if el.name == "style" then
    local why = css_refusal(el.text or "")
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
