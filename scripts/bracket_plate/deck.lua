-- SPDX-License-Identifier: MIT
-- The bracket plate's CalculiX deck (docs/spec/bracket-plate.md §2-3): an aluminium plate
-- 200 x 50 mm of S8R shells of size h, clamped at x = 0 or resting on the compliant joint (a
-- Winkler strip x in [-10, 0] of SPRING1 elements in z, each node's stiffness k_w times its
-- tributary area), with or without the 3 g sensor (a MASS element at the node nearest (190, 40)).
-- Pure: it computes the deck text from the point, so it runs as a deck function (no I/O).
-- Units: N, mm, tonne, s.
local M = {}

M.L, M.B, M.STRIP = 200, 50, 10       -- free length, width, clamped strip under the bar (mm)
M.NU = 0.33
M.SENSOR = {x = 190, y = 40, mass = 3.0e-6}
M.MODES = 6

local fmt = string.format

-- Nodes on a grid of half the element size (S8R: corners and mid-sides, no centre node).
-- Node (i, j), 0-based, i along x from x0, j along y; number j * ni + i + 1.
local function grid(x0, h)
  local nx, ny = math.floor((M.L - x0) / h + 0.5), math.floor(M.B / h + 0.5)
  assert(math.abs(nx * h - (M.L - x0)) < 1e-9 and math.abs(ny * h - M.B) < 1e-9 and
         math.abs(M.STRIP / h - math.floor(M.STRIP / h + 0.5)) < 1e-9,
         fmt("element size h = %g must divide %g, %g and %g mm", h, M.L, M.B, M.STRIP))
  local ni = 2 * nx + 1
  return {x0 = x0, h = h, nx = nx, ny = ny, ni = ni, nj = 2 * ny + 1,
          id = function(i, j) return j * ni + i + 1 end,
          x = function(i) return x0 + i * h / 2 end, y = function(j) return j * h / 2 end}
end

local function node_lines(g, out)
  out[#out + 1] = "*NODE, NSET=NALL"
  for j = 0, g.nj - 1 do
    for i = 0, g.ni - 1 do
      if not (i % 2 == 1 and j % 2 == 1) then out[#out + 1] = fmt("%d, %.6f, %.6f, 0.0", g.id(i, j), g.x(i), g.y(j)) end
    end
  end
end

-- S8R connectivity (corners counter-clockwise, then mid-sides 1-2, 2-3, 3-4, 4-1; normal +z) and
-- the tributary areas of the strip's nodes: 1/12 of an element's area per corner, 1/6 per mid-side.
local function element_lines(g, out)
  out[#out + 1] = "*ELEMENT, TYPE=S8R, ELSET=PLATE"
  local area, e = {}, 0
  for ey = 0, g.ny - 1 do
    for ex = 0, g.nx - 1 do
      local i, j = 2 * ex, 2 * ey
      local c = {g.id(i, j), g.id(i + 2, j), g.id(i + 2, j + 2), g.id(i, j + 2)}
      local m = {g.id(i + 1, j), g.id(i + 2, j + 1), g.id(i + 1, j + 2), g.id(i, j + 1)}
      e = e + 1
      out[#out + 1] = fmt("%d, %d, %d, %d, %d, %d, %d, %d, %d", e, c[1], c[2], c[3], c[4], m[1], m[2], m[3], m[4])
      if g.x(i + 2) <= 1e-9 then  -- an element of the strip under the clamp bar
        for _, n in ipairs(c) do area[n] = (area[n] or 0) + g.h * g.h / 12 end
        for _, n in ipairs(m) do area[n] = (area[n] or 0) + g.h * g.h / 6 end
      end
    end
  end
  return e, area
end

local function sorted_keys(t)
  local k = {}
  for n in pairs(t) do k[#k + 1] = n end
  table.sort(k)
  return k
end

-- The deck text. p: E (MPa), rho (t/mm^3), t (mm), log10_kw (joint only); form: joint =
-- "clamped" | "winkler", sensor = "none" | "mass"; h: element size (mm, default 10).
function M.write(p, form, h)
  h = h or 10
  local joint = form.joint == "winkler"
  assert(joint or form.joint == nil or form.joint == "clamped", "form.joint must be 'clamped' or 'winkler'")
  local g = grid(joint and -M.STRIP or 0, h)
  local out = {"*HEADING", fmt("bracket plate: joint %s, sensor %s, h %g mm", joint and "winkler" or "clamped",
                                form.sensor == "mass" and "mass" or "none", h)}
  node_lines(g, out)
  local e, area = element_lines(g, out)
  out[#out + 1] = "*MATERIAL, NAME=AL"
  out[#out + 1] = "*ELASTIC"
  out[#out + 1] = fmt("%.10e, %.4f", p.E, M.NU)
  out[#out + 1] = "*DENSITY"
  out[#out + 1] = fmt("%.10e", p.rho)
  out[#out + 1] = "*SHELL SECTION, ELSET=PLATE, MATERIAL=AL"
  out[#out + 1] = fmt("%.10e", p.t)
  if not joint then
    out[#out + 1] = "*NSET, NSET=CLAMP"
    for j = 0, g.nj - 1 do out[#out + 1] = fmt("%d,", g.id(0, j)) end
    out[#out + 1] = "*BOUNDARY"
    out[#out + 1] = "CLAMP, 1, 6"
  else
    assert(p.log10_kw, "the compliant joint needs log10_kw")
    local kw = 10 ^ p.log10_kw
    local nodes = sorted_keys(area)
    out[#out + 1] = "*NSET, NSET=STRIP"
    for _, n in ipairs(nodes) do out[#out + 1] = fmt("%d,", n) end
    out[#out + 1] = "*BOUNDARY"
    out[#out + 1] = "STRIP, 1, 2"
    for _, n in ipairs(nodes) do  -- one SPRING1 per node; %.10e: a value without '.' reads as a dof
      e = e + 1
      out[#out + 1] = fmt("*ELEMENT, TYPE=SPRING1, ELSET=K%d", n)
      out[#out + 1] = fmt("%d, %d", e, n)
      out[#out + 1] = fmt("*SPRING, ELSET=K%d", n)
      out[#out + 1] = "3"
      out[#out + 1] = fmt("%.10e", kw * area[n])
    end
  end
  if form.sensor == "mass" then
    local best, bd = nil, math.huge
    for j = 0, g.nj - 1 do
      for i = 0, g.ni - 1 do
        local d = (g.x(i) - M.SENSOR.x) ^ 2 + (g.y(j) - M.SENSOR.y) ^ 2
        if not (i % 2 == 1 and j % 2 == 1) and d < bd then best, bd = g.id(i, j), d end
      end
    end
    out[#out + 1] = "*ELEMENT, TYPE=MASS, ELSET=SENSOR"
    out[#out + 1] = fmt("%d, %d", e + 1, best)
    out[#out + 1] = "*MASS, ELSET=SENSOR"
    out[#out + 1] = fmt("%.10e", M.SENSOR.mass)
  end
  out[#out + 1] = "*STEP"
  out[#out + 1] = "*FREQUENCY"
  out[#out + 1] = tostring(M.MODES)
  out[#out + 1] = "*END STEP"
  return table.concat(out, "\n") .. "\n"
end

return M
