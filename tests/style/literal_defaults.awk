# SPDX-License-Identifier: MIT
# Numeric literals in binding code: a default belongs in its option struct (a kernel's
# *Options, platform/core/defaults.hpp), never beside a read in bindings/. Prints
#   <file>:<line>: <literal>   <the line>
# for each literal outside the allow-list below. Comments, "strings", 'chars', raw strings
# R"d(...)d" (the reference texts and their examples) and preprocessor lines are skipped.
#
# Allowed, and why:
#   * the integers 0..9 and 0.0, 1.0, 2.0, 0.5: stack indices (-2, 3), argument positions,
#     result counts (return 2), first/second, halves: positions and counts, not settings;
#   * any integer on a line that sizes a Lua table (lua_createtable, lua_newuserdatauv) or a
#     char buffer: capacity hints, not behaviour;
#   * a line marked `// literal: <reason>` (a fixed part of a format or an algorithm, never a
#     default a user could set).
function allowed(lit, code, comment) {
  if (lit ~ /^([0-9]|0\.0|1\.0|2\.0|0\.5)$/) return 1
  if (lit ~ /^[0-9]+$/ && code ~ /(lua_createtable|lua_newuserdatauv) *\(|char [a-z_0-9]+\[/) return 1
  if (comment ~ /literal: *[^ ]/) return 1
  return 0
}
FNR == 1 { in_comment = 0; craw = "" }
{
  line = $0; code = ""; comment = ""; n = length(line); i = 1
  if (!in_comment && craw == "" && line ~ /^[ \t]*#/) next
  while (i <= n) {
    c = substr(line, i, 1)
    if (craw != "") {
      j = index(substr(line, i), craw)
      if (j == 0) { i = n + 1; break }
      i += j - 1 + length(craw); craw = ""; code = code " "; continue
    }
    if (in_comment) {
      j = index(substr(line, i), "*/")
      if (j == 0) { comment = comment substr(line, i); i = n + 1; break }
      i += j + 1; in_comment = 0; continue
    }
    two = substr(line, i, 2)
    if (two == "//") { comment = comment substr(line, i); break }
    if (two == "/*") { in_comment = 1; i += 2; continue }
    if (c == "\"") {
      if (i > 1 && substr(line, i - 1, 1) == "R") {
        d = substr(line, i + 1); j = index(d, "(")
        craw = ")" substr(d, 1, j - 1) "\""; i += j + 1; continue
      }
      for (i++; i <= n; i++) {
        c = substr(line, i, 1)
        if (c == "\\") { i++; continue }
        if (c == "\"") break
      }
      i++; code = code "\"\""; continue
    }
    if (c == "'") {
      # a char literal, or a digit separator (1'000) when a digit precedes it
      if (i > 1 && substr(line, i - 1, 1) ~ /[0-9]/) { i++; continue }
      for (i++; i <= n; i++) {
        c = substr(line, i, 1)
        if (c == "\\") { i++; continue }
        if (c == "'") break
      }
      i++; code = code "' '"; continue
    }
    code = code c; i++
  }
  rest = code
  # an identifier (x2, int64_t: skipped) or a number with its exponent and suffix (1e-300, 0.5f)
  while (match(rest, /[A-Za-z_][A-Za-z_0-9]*|[0-9][0-9.]*([eE][-+]?[0-9]+)?[A-Za-z]*|\.[0-9][0-9]*([eE][-+]?[0-9]+)?[A-Za-z]*/)) {
    tok = substr(rest, RSTART, RLENGTH)
    rest = substr(rest, RSTART + RLENGTH)
    if (tok !~ /^[0-9.]/) continue
    lit = tok; sub(/[uUlLfF]+$/, "", lit)
    if (allowed(lit, code, comment)) continue
    printf "%s:%d: %s   %s\n", FILENAME, FNR, tok, $0
    bad++
  }
}
END { exit bad > 0 ? 1 : 0 }
