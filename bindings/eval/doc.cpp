// SPDX-License-Identifier: MIT
// Reference texts of smi.model.* and the model methods (this folder). The option lists come from
// the schemas (solver_options.cpp, lua_model_options.cpp), whose defaults are the structs'. The
// examples run /bin/sh as their "solver" (smi-lua doc allows it for them), so they run anywhere.
#include "bindings/doc.hpp"
#include "bindings/eval/lua_model_options.hpp"
#include "bindings/eval/solver_options.hpp"

namespace smi::bind {
namespace {

const char* const kText = R"DOC(
@ module smi.model
Models behind one interface (m.inputs, m.outputs, Y, info = m:evaluate(X), m:plan(X)): external
solvers run per point (smi.model.command) or per batch (smi.model.batch), Lua functions
(smi.model.lua); a Kriging model fits the same slots. Output parsers get the helpers of
smi.model.parse bound to their run's folder.

@ smi.model.command{...} -> model
An external solver run once per point: the deck is made from a template ({{name}} placeholders
take the point's inputs and the constants), the program runs in its own work folder without a
shell, and parse(dir, h) reads its outputs. Runs go through an SQLite evaluation store keyed by
deck, program and version: a rerun (or a resumed study) reuses every finished point.
template may also be a Lua function(p) returning the deck text, p = {input = value, constant =
value}: a deck that computes (per-node stiffnesses, 10^x of a log-scaled input). It runs without
I/O: the model keeps a copy of it that sees only string, math, table, utf8 and the pure base
functions (another global is an error naming it), with its other upvalues copied when the model
is made; and while it runs the sandbox refuses every file and program, also to the helpers it
calls. The deck text is the store key, as a rendered template's is.
options:
${command_options}
returns: a model (smi.model) with m.name, m.kind = "command", m.inputs, m.outputs, m.version
errors: a missing or mistyped option (named); both or neither template; a program path that does
  not exist or is not an executable file (refused here, not at the first run); the sandbox refuses
  the program (--allow-exec), the template (--allow-read) or the runs folder; a bad template
  placeholder (file and line); version_args given and the program prints nothing on stdout or
  takes more than 10 s; a deck function that uses another global, tries I/O or returns no string
  (raised by m:evaluate, naming it)
example:
  local m = smi.model.command{
    name = "doc-square", inputs = {"x"}, outputs = {"y"}, version = "doc-1",
    template_string = "{{x}}\n",
    command = {"/bin/sh", "-c", "read x < {deck}; echo \"y = $((x * x))\" > out.txt"},
    parse = function(dir, h) return {y = h.regex("out.txt", "y = (\\S+)")} end,
  }
  local Y, info = m:evaluate{{2}, {3}}
  print(Y.y, info.failed)

@ smi.model.batch{...} -> model
An external solver that takes many points per run: the points are written as CSV (a header of
input names) to input_file, and parse(dir, h, n) returns n values per output. Options as
smi.model.command, without template/template_string/deck/constants, plus:
options:
${batch_options}
returns: a model (smi.model, kind "batch")
errors: as smi.model.command; parse returning the wrong number of values (named with the output)
example:
  local m = smi.model.batch{
    name = "doc-batch", inputs = {"x"}, outputs = {"y"}, version = "doc-1",
    command = {"/bin/sh", "-c", "tail -n +2 {deck} | while read x; do echo $((x + 1)); done > out.txt"},
    parse = function(dir, h, n) return {y = h.regex_all("out.txt", "(\\d+)")} end,
  }
  print(m:evaluate{{1}, {2}, {3}}.y)

@ smi.model.lua{name =, inputs =, outputs =, fn =} -> model
A model computed by a Lua function of the whole design matrix (one call per evaluation, never
one per point), returning {output = vec}.
options:
${lua_model_options}
returns: a model (smi.model, kind "lua")
errors: no inputs or outputs; fn not a function; fn returning the wrong lengths (at evaluate)
example:
  local m = smi.model.lua{inputs = {"a", "b"}, outputs = {"s"}, fn = function(X) return {s = X:col(1) + X:col(2)} end}
  print(m:evaluate{{1, 2}, {3, 4}}.s)

@ smi.model.planned() -> {runs =, points =, reused =, eta =}
The totals of what --dry-run planned so far (solver runs that would be launched, points, points
found in the store, estimated seconds).
returns: a table of counts (zeros when nothing was planned)
errors: none
example:
  print(smi.model.planned().runs)

@ smi.model:evaluate(X) -> Y, info
Evaluates the model at the rows of X (a mat, a table of rows, or named columns {x = vec, ...}).
Y holds one value per row in row order whatever the concurrency; rows that failed hold NaN.
returns: Y = {output = vec}, info = {status = {"ok" | "failed" | "not run", ...}, ok = vec of 1/0,
  reason = {...}, failures = {{row =, reason =}}, failed =, launched =, reused = vec, duration = vec,
  stopped =}
errors: X with the wrong columns (a missing or unknown input named); on_failure = "stop" and a run
  failed (the reason and the run folder are named); --timeout or Ctrl-C
example:
  local m = smi.model.lua{inputs = {"x"}, outputs = {"y"}, fn = function(X) return {y = X:col(1) * 10} end}
  local Y, info = m:evaluate{x = smi.vec{1, 2}}
  print(Y.y, info.status[1])

@ smi.model:plan(X) -> {points =, unique =, reused =, runs =, eta =, mean_seconds =}
What evaluate(X) would launch, launching nothing (the evaluation store is read).
returns: a table of counts, the estimated seconds (eta) and the stored mean seconds of one run
  (mean_seconds), each when the store has timings of this program and version
errors: as evaluate, for X
example:
  local m = smi.model.lua{inputs = {"x"}, outputs = {"y"}, fn = function(X) return {y = X:col(1)} end}
  print(m:plan{{1}, {2}}.points)

@ module smi.model.parse
Output parser helpers, the same functions a parser receives as h (bound to its run's folder);
here they take any path the sandbox allows.

@ smi.model.parse.read(file) -> string
The whole text of a file.
returns: a string
errors: the sandbox refuses the path; the file cannot be read
example:
  local p = smi.out("doc_read.txt")
  local f = io.open(p, "w"); f:write("hello\n"); f:close()
  print(smi.model.parse.read(p))

@ smi.model.parse.exists(file) -> boolean
Whether the file exists (a solver that writes a file only on success).
returns: true or false
errors: the sandbox refuses the path
example:
  print(smi.model.parse.exists(smi.out("no_such_file.txt")))

@ smi.model.parse.regex(file, pattern) -> number
The first capture of an ECMAScript regular expression in the file, as a number.
returns: a number
errors: no match (file and pattern named); the capture is not a number; a bad pattern
example:
  local p = smi.out("doc_out.txt")
  local f = io.open(p, "w"); f:write("freq = 30.25 Hz\n"); f:close()
  print(smi.model.parse.regex(p, "freq = (\\S+)"))

@ smi.model.parse.regex_all(file, pattern) -> vec
The first capture of every match, as numbers.
returns: a vec (empty when nothing matches)
errors: a capture that is not a number; a bad pattern
example:
  local p = smi.out("doc_all.txt")
  local f = io.open(p, "w"); f:write("f1 = 1.5\nf2 = 2.5\n"); f:close()
  print(smi.model.parse.regex_all(p, "= (\\S+)"))

@ smi.model.parse.csv(file, column) -> vec
One numeric column of a CSV file with a header row.
returns: a vec
errors: no such column (the header is listed); a cell that is not a number (line named)
example:
  local p = smi.out("doc_cols.csv")
  smi.csv.write(p, {y = smi.vec{1, 2}})
  print(smi.model.parse.csv(p, "y"))

@ smi.model.parse.f06(file) -> table
The real eigenvalue table (and mode labels, when present) of a Nastran-style .f06 file.
returns: {mode, order, eigenvalue, radians, cycles, mass, stiffness = vecs, labels = {...},
  direction = {...}, paper = {[n] = {mode, direction, hz}}, paper_hz = vec}
errors: no eigenvalue table in the file; a malformed row (line named)
example:
  local p = smi.out("doc.f06")
  local f = io.open(p, "w")
  f:write("                                              R E A L   E I G E N V A L U E S\n",
          "   MODE    EXTRACTION      EIGENVALUE            RADIANS             CYCLES            GENERALIZED         GENERALIZED\n",
          "    NO.       ORDER                                                                       MASS              STIFFNESS\n",
          "        1         1        3.467649E+04        1.862162E+02        2.963724E+01        1.000000E+00        3.467649E+04\n",
          "        2         2        4.455839E+04        2.110886E+02        3.359579E+01        1.000000E+00        4.455839E+04\n")
  f:close()
  print(smi.model.parse.f06(p).cycles)

@ smi.model.parse.ccx_dat(file) -> table
A CalculiX (ccx 2.20) .dat results file: the "E I G E N V A L U E   O U T P U T" table of a
*FREQUENCY step (columns: mode, eigenvalue, rad/time, cycles/time = Hz, imaginary part), and the
blocks *NODE PRINT and *EL PRINT write ("displacements (vx,vy,vz) for set TIP and time ...").
A block's columns are the header's names made into keys ("integ.pnt." -> integ_pnt), with
"node" first for node blocks; in a *FREQUENCY step each block has the mode it was printed under.
The participation-factor and effective-mass tables are skipped. In a parser, h.ccx_dat("job.dat").
returns: {mode, eigenvalue, radians, cycles, imaginary = vecs (cycles in Hz), blocks = {{name,
  set, time, mode, columns = {names}, rows = mat, [column name] = vec}, ...}}
errors: a file with neither an eigenvalue table nor a result block (a run that stopped early);
  a row with the wrong number of fields (file and line named)
example:
  local p = smi.out("doc.dat")
  local f = io.open(p, "w")
  f:write("     E I G E N V A L U E   O U T P U T\n\n",
          " MODE NO    EIGENVALUE                       FREQUENCY\n",
          "                                     REAL PART            IMAGINARY PART\n",
          "                           (RAD/TIME)      (CYCLES/TIME     (RAD/TIME)\n\n",
          "      1   0.1554390E+06   0.3942575E+03   0.6274803E+02   0.0000000E+00\n",
          "      2   0.6069984E+07   0.2463734E+04   0.3921154E+03   0.0000000E+00\n\n",
          " displacements (vx,vy,vz) for set TIP and time  0.1000000E+01\n\n",
          "        43  2.389716E-11  1.139152E-10 -2.079296E+02\n\n")
  f:close()
  local r = smi.model.parse.ccx_dat(p)
  print(r.cycles, r.blocks[1].vz)   -- 62.748, 392.115 Hz; the tip's vz
)DOC";

}  // namespace

DocText doc_eval() {
  const auto& batch = bind::eval::solver_schema(true);
  return {"bindings/eval/doc.cpp",
          fill(kText, {{"lua_model_options", bind::eval::lua_model_schema().doc()},
                       {"command_options", bind::eval::solver_schema(false).doc()},
                       {"batch_options", batch.doc({"input_file", "batch_size"})}})};
}

}  // namespace smi::bind
