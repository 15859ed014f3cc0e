-- SPDX-License-Identifier: MIT
-- Data mistakes caught before the solver runs. A ';' or tab separated file, or one with
-- decimal commas, says what it uses and what to pass; decimal = ',' reads it. A missing input
-- file names the option that gave it. A solver path that does not exist is refused when the
-- model is declared.
local T = require "smi.testing"

local function write(name, text)
  local p = smi.out(name)
  local f = assert(io.open(p, "wb"))
  f:write(text)
  f:close()
  return p
end

T.case("a ';' file says so", function()
  local p = write("semi.csv", "specimen;wheel;mode1_hz\n1;A;31.84\n2;B;32.10\n")
  T.raises(function() smi.csv.read(p) end, "the file uses ';' between fields: pass sep = ';' or save as CSV")
  local d = smi.csv.read(p, { sep = ";" })
  T.near(d.mode1_hz[2], 32.10, 1e-12, "read with sep = ';'")
end)

T.case("a tab file says so", function()
  local p = write("tab.csv", "specimen\tmode1_hz\n1\t31.84\n")
  T.raises(function() smi.csv.read(p) end, "the file uses a tab between fields: pass sep = '\\t'")
end)

T.case("decimal commas are named, and read with decimal = ','", function()
  local p = write("comma.csv", "specimen;mode1_hz;mode2_hz\n1;31,84;58,2\n2;32,1;57,9\n")
  T.raises(function() smi.csv.read(p) end, "the file uses ';' between fields and ',' as the decimal mark: pass sep = ';', decimal = ','")
  T.raises(function() smi.csv.read(p, { sep = ";" }) end, "'31,84' is written with a decimal comma: pass decimal = ','")
  local d = smi.csv.read(p, { sep = ";", decimal = "," })
  T.near(d.mode1_hz[1], 31.84, 1e-12, "31,84")
  T.near(d.mode2_hz[2], 57.9, 1e-12, "57,9")
  T.raises(function() smi.csv.read(p, { decimal = "," }) end, "decimal = ',' needs another separator")
end)

T.case("a missing input file names its option", function()
  local options = require "smi.options"
  local spec = { name = "s", { name = "data", type = "path", input = true, default = smi.out("nope.csv"), meaning = "measurements (CSV)" } }
  local opt, err = options.check({}, spec)
  T.eq(opt, nil, "refused")
  T.truthy(err:find("--data (its default): cannot read '" .. smi.out("nope.csv") .. "'", 1, true), err)
  T.truthy(err:find("give the measurements (CSV) with --data PATH", 1, true), err)
  opt, err = options.check({ "--data", smi.out("also-missing.csv") }, spec)
  T.truthy(err:find("--data: cannot read", 1, true), tostring(err))
  local p = write("here.csv", "a\n1\n")
  T.eq(options.check({ "--data", p }, spec).data, p, "an existing file passes")
end)

T.case("a solver path that does not exist is refused when the model is declared", function()
  T.raises(function()
    smi.model.command{ name = "typo", inputs = { "x" }, outputs = { "y" }, command = { smi.out("no-such-solver"), "{deck}" },
                       template_string = "x = {{x}}\n", parse = function() return { y = 1 } end }
  end, "does not exist")
  local p = write("not-exec.sh", "#!/bin/sh\necho y = 1\n")
  T.raises(function()
    smi.model.command{ name = "noexec", inputs = { "x" }, outputs = { "y" }, command = { p, "{deck}" },
                       template_string = "x = {{x}}\n", parse = function() return { y = 1 } end }
  end, "not an executable file")
end)

T.case("csv: a data row is named by its line in the file (notes.lines), a quoted field over two lines counted", function()
  local p = smi.out("lines.csv")
  local f = assert(io.open(p, "wb"))
  -- line 1 header, line 2 row 1, lines 3-4 row 2 (a quoted newline), line 5 row 3
  f:write('id,hz\na,29.6\n"b\nc",30.1\nd,nan\n')
  f:close()
  local d, _, notes = smi.csv.read(p)
  T.eq(#notes.lines, 3)
  T.eq(notes.lines[1], 2) T.eq(notes.lines[2], 3) T.eq(notes.lines[3], 5)
  T.truthy(d.hz[3] ~= d.hz[3], "nan reads as NaN, for the study to name by its line")
end)

T.finish()
