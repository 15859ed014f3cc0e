// Reference texts of smi.csv and smi.json (registered in csv.cpp and json.cpp).
#include "bindings/doc.hpp"

namespace smi::bind {

// long: one raw string of reference text (data, no logic), split into entries by doc.lua; cutting it
// into several functions would only scatter one module's reference page
DocText doc_csv_json() {
  return {"bindings/csv_json_doc.cpp", R"DOC(
@ module smi.csv
CSV files as columns by name: smi.csv.read and smi.csv.write (RFC 4180 quoting).

@ smi.csv.read(path [, opts]) -> columns, header
Reads a CSV file with a header row. A column whose every cell is a number becomes a vec; any
other column a table of strings. Quoted fields may hold the separator, "" and newlines.
options:
  sep = ","        -- the separator, one character other than a quote or a newline
  decimal = "."    -- the decimal mark of the numbers: "." or "," (with sep = ";" or "\t")
  strings = {}     -- names of columns to keep as text even when they look numeric (IDs)
returns: columns (a table {name = vec or {strings}}) and header (the names in file order)
errors: the sandbox refuses the path (--allow-read); the file cannot be opened; a ragged row or a
  bad number, named by file, line and column; an unknown option; a file that uses ';' or a tab
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
  sep = ","        -- the separator
  header = nil     -- the column order, a list of names (default: the names sorted)
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
  indent = 0            -- spaces per level, 0..16; 0 writes one line
  nonfinite = "refuse"  -- or "encode": inf as 1e999, -inf as -1e999, NaN as null
  skip = false          -- leave out what JSON cannot hold; their paths are the second result
  root = "$"            -- the name of the value in error paths
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
  null = smi.json.null  -- what null reads as (0/0 for files written with nonfinite = "encode")
returns: the value
errors: invalid JSON, with the line and column of the problem
example:
  local t = smi.json.decode('{"a": [1, 2, null]}')
  print(t.a[2], t.a[3] == smi.json.null)

@ smi.json.write(path, value [, opts])
Writes value as JSON to a file (with a final newline).
options:
  indent = 2            -- spaces per level, 0..16
  nonfinite = "refuse"  -- as smi.json.encode
  root = "$"            -- the name of the value in error paths
returns: nothing
errors: the sandbox refuses the path; the value cannot be encoded (as smi.json.encode)
example:
  local p = smi.out("doc.json")
  smi.json.write(p, {seed = smi.seed})
  print(smi.json.read(p).seed == smi.seed)

@ smi.json.read(path [, opts]) -> value
Reads and decodes a JSON file.
options:
  null = smi.json.null  -- what null reads as (as smi.json.decode)
returns: the value
errors: the sandbox refuses the path; the file cannot be opened; invalid JSON (file, line, column)
example:
  local p = smi.out("doc2.json")
  smi.json.write(p, {1, 2, 3})
  print(#smi.json.read(p))
)DOC"};
}

}  // namespace smi::bind
