-- SPDX-License-Identifier: MIT
-- smi.model.parse.ccx_dat (h.ccx_dat in a parser) on real CalculiX 2.20 output
-- (tests/solver/fixtures/README.md). arg[2] = the fixtures folder.
local T = require "smi.testing"
local fixtures = arg[2]

T.case("the eigenvalue table: modes, eigenvalues, rad/time, Hz", function()
  local r = smi.model.parse.ccx_dat(fixtures .. "/ccx_clamped.dat")
  T.eq(#r.mode, 6); T.eq(r.mode[6], 6)
  T.eq(r.cycles[1], 62.74803)                 -- the spec's 62.75 Hz for the nominal clamped plate
  T.eq(r.eigenvalue[3], 0.9462964E+07)
  T.eq(r.radians[2], 0.2463734E+04)
  T.eq(r.imaginary[1], 0)
  T.near(r.radians[1] / (2 * math.pi), r.cycles[1], 1e-4)
  T.eq(#r.blocks, 0)
end)

T.case("displacement and stress blocks as tables with their mode, set and columns", function()
  local r = smi.model.parse.ccx_dat(fixtures .. "/ccx_joint_sensor.dat")
  T.eq(r.cycles[1], 56.32674)
  T.eq(#r.blocks, 12)
  local u, s = r.blocks[1], r.blocks[2]
  T.eq(u.name, "displacements"); T.eq(u.set, "TIP"); T.eq(u.mode, 1); T.eq(u.time, 1)
  T.eq(table.concat(u.columns, ","), "node,vx,vy,vz")
  T.eq(u.node[2], 473); T.eq(u.vz[2], -2.088246E+02); T.eq(u.rows:get(1, 4), -2.079296E+02)
  T.eq(s.name, "stresses"); T.eq(s.set, "ROOT")
  T.eq(table.concat(s.columns, ","), "elem,integ_pnt,sxx,syy,szz,sxy,sxz,syz")
  T.eq(#s.sxx, 8); T.eq(s.sxx[4], -6.913694E+02); T.eq(s.integ_pnt[8], 8)
  T.eq(r.blocks[12].mode, 6)
end)

T.case("a file that holds no results is an error naming it", function()
  local p = smi.out("empty.dat")
  local f = assert(io.open(p, "w")); f:write("\n"); f:close()
  T.raises(function() smi.model.parse.ccx_dat(p) end, "has no E I G E N V A L U E   O U T P U T table")
  T.raises(function() smi.model.parse.ccx_dat(smi.out("missing.dat")) end, "is missing or unreadable")
end)

T.finish()
