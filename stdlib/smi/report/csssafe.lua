-- SPDX-License-Identifier: MIT
--- smi.report.csssafe: the CSS of a report figure, held to an allow-list. A figure's SVG goes
-- into the page as it is, and the page promises no network: CSS can fetch through many
-- functions (url, image-set, image, cross-fade, element, paint, ...), at-rules (@import,
-- @font-face's src) and spellings that a search for "url(" misses (escapes such as \75 rl(,
-- comments inside a token such as u/**/rl(, any case). So nothing is looked for; what is
-- allowed is listed, and everything else is refused:
--   * properties of static vector graphics (fill, stroke, fonts, text layout, opacity, ...);
--   * values made of numbers (with a unit or %), #hex colours, keywords, quoted font names,
--     commas, slashes, !important, and the functions rgb(a), hsl(a), the transform functions
--     and url(#id) pointing inside the figure;
--   * in a <style> sheet: rules "selector { declarations }" only: no at-rule, no comment, no
--     escape, no nested block.
--
--   local why = csssafe.declarations("fill: red; stroke: url(#g)")  -- nil, or the reason
--   local why = csssafe.sheet("rect.a { fill: red }")
--   local why = csssafe.value("fill", "url(#g)")                    -- a presentation attribute
local M = {}

--- {[v] = true} for each v of the list (the allow-lists here and in svgsafe.lua).
function M.set(list)
  local s = {}
  for _, v in ipairs(list) do s[v] = true end
  return s
end
local set = M.set

--- The properties a figure may set (in a style, or as a presentation attribute).
M.properties = set{
  "fill", "fill-opacity", "fill-rule", "stroke", "stroke-width", "stroke-opacity", "stroke-dasharray",
  "stroke-dashoffset", "stroke-linecap", "stroke-linejoin", "stroke-miterlimit", "opacity", "color",
  "visibility", "display", "overflow", "vector-effect", "shape-rendering", "text-rendering", "paint-order",
  "clip-path", "clip-rule", "mask", "filter", "flood-color", "flood-opacity", "lighting-color",
  "color-interpolation", "color-interpolation-filters", "mix-blend-mode", "isolation",
  "marker", "marker-start", "marker-mid", "marker-end", "stop-color", "stop-opacity",
  "font", "font-family", "font-size", "font-weight", "font-style", "font-variant", "font-stretch",
  "text-anchor", "dominant-baseline", "alignment-baseline", "baseline-shift", "letter-spacing", "word-spacing",
  "text-decoration", "writing-mode", "line-height", "white-space", "pointer-events",
  "transform", "transform-origin", "transform-box",
  "width", "height", "max-width", "max-height", "x", "y", "r", "rx", "ry", "cx", "cy",
}

-- Functions a value may call; none takes a URL (url() is handled on its own: #id only).
local functions = set{
  "rgb", "rgba", "hsl", "hsla",
  "matrix", "translate", "translatex", "translatey", "scale", "scalex", "scaley", "rotate", "skewx", "skewy",
}

local function shown(s)
  s = s:gsub("%c", "?")
  return #s > 60 and s:sub(1, 57) .. "..." or s
end

-- Characters no figure CSS needs and through which CSS can be spelled around a check.
local function spelling(css)
  if css:find("\\", 1, true) then return "a CSS escape ('\\')" end
  if css:find("/*", 1, true) then return "a CSS comment ('/*')" end
  if css:find("<!--", 1, true) or css:find("-->", 1, true) then return "'<!--' or '-->' in CSS" end
  if css:find("@", 1, true) then return "an at-rule ('@import', '@font-face', ...)" end
  return nil
end

--- nil if `v` is an allowed value of property `prop`, else the reason.
function M.value(prop, v)
  local why = spelling(v)
  if why then return why end
  local i, depth = 1, 0
  while true do
    i = v:find("%S", i)
    if not i then break end
    local c = v:sub(i, i)
    local num = v:match("^[+-]?%d*%.?%d+[eE][+-]?%d+", i) or v:match("^[+-]?%d*%.?%d+", i)
    if num then
      i = i + #num
      local unit = v:match("^%a+", i) or v:match("^%%", i)
      if unit then i = i + #unit end
    elseif c == "#" then
      local hex = v:match("^#%x+", i)
      if not hex or not (#hex == 4 or #hex == 5 or #hex == 7 or #hex == 9) then
        return ("'%s' in %s (a colour is #rgb, #rgba, #rrggbb or #rrggbbaa)"):format(shown(v:sub(i, i + 9)), prop)
      end
      i = i + #hex
    elseif c:match("[%a_%-]") then
      local ident = v:match("^%-?%-?[%a_][%w_%-]*", i)
      if not ident then return ("'%s' in %s"):format(shown(v:sub(i, i + 9)), prop) end
      i = i + #ident
      if v:sub(i, i) == "(" then
        local name = ident:lower()
        if name == "url" then
          local whole = v:match("^%(%s*([\"']?)#[%w_%-%.:]+%1%s*%)", i)
          if not whole then
            return ("%s in %s (only url(#id) inside the figure)"):format(shown(v:sub(i - #ident):match("^[^)]*%)?")), prop)
          end
          i = v:find(")", i, true) + 1
        elseif functions[name] then
          depth = depth + 1
          i = i + 1
        else
          return ("the function %s() in %s (allowed: url(#id), rgb, rgba, hsl, hsla and the transform functions)")
            :format(ident, prop)
        end
      end
    elseif c == ")" then
      depth = depth - 1
      if depth < 0 then return ("an unmatched ')' in %s"):format(prop) end
      i = i + 1
    elseif c == "," or c == "/" then
      i = i + 1
    elseif c == '"' or c == "'" then
      local str = v:match(c == '"' and '^"[^"\n]*"' or "^'[^'\n]*'", i)
      if not str then return ("an unterminated string in %s"):format(prop) end
      i = i + #str
    elseif c == "!" then
      local imp = v:match("^!%s*[iI][mM][pP][oO][rR][tT][aA][nN][tT]", i)
      if not imp then return ("'!' in %s"):format(prop) end
      i = i + #imp
    else
      return ("the character '%s' in %s"):format(shown(c), prop)
    end
  end
  if depth ~= 0 then return ("an unclosed function in %s"):format(prop) end
  return nil
end

--- nil if the declarations ("prop: value; ...", a style attribute) are allowed, else the reason.
function M.declarations(css)
  local why = spelling(css)
  if why then return why end
  for decl in (css .. ";"):gmatch("([^;]*);") do
    if decl:match("%S") then
      local prop, value = decl:match("^%s*([%a%-]+)%s*:(.*)$")
      if not prop then return ("'%s' is not a declaration (property: value)"):format(shown(decl)) end
      if not M.properties[prop:lower()] then
        return ("the property '%s' (a figure may set only the properties of static graphics: fill, stroke, "
          .. "fonts, opacity, ...)"):format(shown(prop))
      end
      why = M.value(prop:lower(), value)
      if why then return why end
    end
  end
  return nil
end

-- Selectors: names, classes, ids, combinators, attribute and pseudo-class selectors.
local SELECTOR = "^[%w%s%.#,:>+~*_%-%[%]=\"'()|%^%$]*$"

--- nil if the sheet (the text of a <style> element) is allowed, else the reason.
function M.sheet(css)
  local why = spelling(css)
  if why then return why end
  local i = 1
  while true do
    local open = css:find("{", i, true)
    if not open then
      if css:find("%S", i) then return ("'%s' after the last rule"):format(shown(css:sub(i))) end
      return nil
    end
    local selector = css:sub(i, open - 1)
    if not selector:match(SELECTOR) or selector:find("}", 1, true) then
      return ("the selector '%s'"):format(shown(selector))
    end
    local close = css:find("}", open + 1, true)
    if not close then return "a rule without its closing '}'" end
    local body = css:sub(open + 1, close - 1)
    if body:find("{", 1, true) then return "a nested block ('{' inside a rule)" end
    why = M.declarations(body)
    if why then return why end
    i = close + 1
  end
end

return M
