// SPDX-License-Identifier: MIT
// Reference texts of smi.csv and smi.json (registered in csv.cpp and json.cpp).
#include "bindings/csv_json_options.hpp"
#include "bindings/doc.hpp"

namespace smi::bind {

// long: one raw string of reference text (data, no logic), split into entries by doc.lua; cutting it
// into several functions would only scatter one module's reference page
DocText doc_csv_json() {
  return {"bindings/csv_json_doc.cpp", fill(R"DOC(
@ module smi.csv
CSV files as columns by name: smi.csv.read and smi.csv.write (RFC 4180 quoting).

@ smi.csv.read(path [, opts]) -> columns, header, notes
Reads a CSV file with a header row. A column whose every cell is a number becomes a vec; any
other column a table of strings. Quoted fields may hold the separator, "" and newlines.
options:
${csv_read}
returns: columns (a table {name = vec or {strings}}), header (the names in file order) and notes
  {warnings = {texts}, duplicates = {{first line, repeated line}, ...}, lines = {the file line of
  each data row}}: a message about data row i names it as "line notes.lines[i] of FILE"
errors: the sandbox refuses the path (--allow-read); the file cannot be opened; a ragged row or a
  bad number, named by line, file and column ("line 3 of bad.csv: column 2 ('y'): bad number 'abc'"); an unknown option; a file that uses ';' or a tab
  between fields, or decimal commas, says so ("the file uses ';' between fields: pass sep = ';'
  or save as CSV")
example:
  local p = smi.out("doc_read.csv")
  smi.csv.write(p, {id = {"a", "b"}, hz = smi.vec{30.1, 30.4}})
  local cols, header = smi.csv.read(p)
  print(table.concat(header, ","), cols.hz:mean(), cols.id[2])

@ smi.csv.write(path, columns [, opts])
Writes columns (a table {name = vec or table of numbers/strings}, all of one length) as CSV
with a header row; numbers are written in the shortest form that reads back exactly.
options:
${csv_write}
returns: nothing
errors: the sandbox refuses the path (--allow-write; smi.out(name) is always allowed); columns
  of different lengths; a key that is not a string; an empty table
example:
  local p = smi.out("doc_write.csv")
  smi.csv.write(p, {x = smi.vec{1, 2}, y = {0.5, 0.25}}, {header = {"x", "y"}})
  print(io.open(p):read("a"))

@ module smi.json
JSON text and files by the one JSON codec of smi-lua (the results writer and `smi-lua verify` use
it too): numbers in the shortest text that reads back exactly, smi.json.null for null, vecs
written as arrays. NaN and infinities: refused by default (JSON has none); with
nonfinite = "encode", inf is written 1e999 (read back as inf) and NaN null (read back as NaN by
decode/read with {null = 0/0}), the rule results.json follows.

@ smi.json.encode(value [, opts]) -> string [, skipped]
JSON text of a Lua value: tables with keys 1..n become arrays, other tables objects (keys sorted),
vecs arrays, smi.json.null null.
options:
${json_encode}
returns: a string (and, with skip, a list of the paths left out, in key order)
errors: a value JSON cannot hold (a function, a userdata other than vec, NaN or infinity unless
  nonfinite = "encode", a table mixing keys), named by its path in the value (the first in key
  order, the same every run); a cycle
example:
  print(smi.json.encode({name = "E", values = {1, 2.5}}))

@ smi.json.decode(text [, opts]) -> value
The Lua value of a JSON text: objects and arrays as tables, null as smi.json.null, integers as
Lua integers.
options:
${json_decode}
returns: the value
errors: invalid JSON, with the line and column of the problem
example:
  local t = smi.json.decode('{"a": [1, 2, null]}')
  print(t.a[2], t.a[3] == smi.json.null)

@ smi.json.write(path, value [, opts])
Writes value as JSON to a file (with a final newline).
options:
${json_write}
returns: nothing
errors: the sandbox refuses the path; the value cannot be encoded (as smi.json.encode)
example:
  local p = smi.out("doc.json")
  smi.json.write(p, {seed = smi.seed})
  print(smi.json.read(p).seed == smi.seed)

@ smi.json.read(path [, opts]) -> value
Reads and decodes a JSON file.
options:
${json_read}
returns: the value
errors: the sandbox refuses the path; the file cannot be opened; invalid JSON (file, line, column)
example:
  local p = smi.out("doc2.json")
  smi.json.write(p, {1, 2, 3})
  print(#smi.json.read(p))
)DOC",
                                             {{"csv_read", csv_read_schema().doc()},
                                              {"csv_write", csv_write_schema().doc()},
                                              {"json_encode", json_encode_schema().doc()},
                                              {"json_decode", json_decode_schema(false).doc()},
                                              {"json_write", json_write_schema().doc()},
                                              {"json_read", json_decode_schema(true).doc()}})};
}

}  // namespace smi::bind
