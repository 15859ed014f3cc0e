# SPDX-License-Identifier: MIT
# Lists every C++ and Lua function longer than `limit` lines (default 80) and says which ones
# carry no comment explaining why they must be long. Run through long_functions.sh, which picks
# the files; POSIX awk only (Debian's default mawk), so CI needs nothing beyond the base system.
#
# A function's length runs from the line of its signature (C++: the line where its declaration
# starts; Lua: the line holding `function`) to its closing `}` / `end`, both included.
# The reason is a comment `// long: <reason>` (C++) or `-- long: <reason>` (Lua), in the comment
# block directly above the function or in its first `head` lines.
#
# Output, one line per long function (sorted by the caller):
#   missing  path:line  name  N lines
#   reasoned path:line  name  N lines
#
# What the scanner understands. C++: comments, "strings", 'chars', digit separators, raw
# strings R"d(...)d", preprocessor lines; a `{` opens a function body when it appears at
# namespace/class scope after a parenthesised parameter list (constructor initialiser lists
# included); lambdas and blocks inside a function belong to that function. Lua: comments, short
# and long strings, long comments; `function`, `do`, `if`, `repeat` open a block, `end` and
# `until` close one; nested functions are listed on their own as well as inside their parent.

BEGIN {
  if (limit == "") limit = 80
  if (head == "") head = 5
}

FNR == 1 { start_file() }

{
  raw[FNR] = $0
  if (lang == "cpp") cpp_line($0)
  else lua_line($0)
}

END { if (NR > 0) start_file() }

function start_file() {
  # Called at the first line of each file (and at the end): report what the last one left open.
  # Nothing is ever left open in a well-formed file, so nothing is reported here.
  delete raw
  path = FILENAME
  lang = (path ~ /\.lua$/) ? "lua" : "cpp"
  # C++ state
  cin_comment = 0; craw = ""; cdepth = 0; header = ""; header_line = 0; in_pp = 0
  # Lua state
  lin_long = 0; lclose = ""; ldepth = 0
}

# ---------------------------------------------------------------- the marker

function is_comment_line(s) {
  sub(/^[ \t]+/, "", s)
  if (lang == "cpp") return (s ~ /^(\/\/|\/\*|\*)/)
  return (s ~ /^--/)
}

function has_marker(s,    i, rest) {
  i = index(s, "long:")
  if (i == 0) return 0
  if (lang == "cpp" && substr(s, 1, i - 1) !~ /(\/\/|\/\*|\*)[ \t]*$/) return 0
  if (lang == "lua" && substr(s, 1, i - 1) !~ /--[ \t]*$/) return 0
  rest = substr(s, i + 5)
  gsub(/^[ \t]+|[ \t]+$/, "", rest)
  return length(rest) >= 10          # a reason, not just the word
}

function report(name, first, last,    n, ok, i) {
  n = last - first + 1
  if (n <= limit) return
  ok = 0
  for (i = first - 1; i >= 1 && i >= first - 20 && is_comment_line(raw[i]); i--)
    if (has_marker(raw[i])) ok = 1
  for (i = first; i <= first + head && i <= last; i++)
    if (has_marker(raw[i])) ok = 1
  printf "%s %s:%d %s %d\n", (ok ? "reasoned" : "missing"), path, first, name, n
}

# ---------------------------------------------------------------- C++

function cpp_line(line,    code, i, c, n, j, d) {
  # Preprocessor lines (and their continuations) never hold a function.
  if (!cin_comment && craw == "" && (in_pp || line ~ /^[ \t]*#/)) {
    in_pp = (line ~ /\\$/)
    return
  }
  n = length(line)
  i = 1
  while (i <= n) {
    c = substr(line, i, 1)
    if (cin_comment) {
      j = index(substr(line, i), "*/")
      if (j == 0) return
      cin_comment = 0; i += j + 1; continue
    }
    if (craw != "") {
      j = index(substr(line, i), craw)
      if (j == 0) return
      i += j - 1 + length(craw); craw = ""; continue
    }
    if (c == "/" && substr(line, i + 1, 1) == "/") return
    if (c == "/" && substr(line, i + 1, 1) == "*") { cin_comment = 1; i += 2; continue }
    if (c == "\"") {
      if (i > 1 && substr(line, i - 1, 1) == "R") {          # raw string R"delim( ... )delim"
        d = substr(line, i + 1)
        j = index(d, "(")
        craw = ")" substr(d, 1, j - 1) "\""
        i += j + 1
        continue
      }
      i = skip_quoted(line, i, "\""); cpp_char(" "); continue
    }
    if (c == "'") {
      if (i > 1 && substr(line, i - 1, 1) ~ /[0-9]/) { i++; continue }   # 1'000'000
      i = skip_quoted(line, i, "'"); cpp_char(" "); continue
    }
    cpp_char(c)
    i++
  }
  cpp_char(" ")
}

# Index just past the closing quote of the literal opened at i (same line; escapes skipped).
function skip_quoted(line, i, q,    n, c) {
  n = length(line)
  i++
  while (i <= n) {
    c = substr(line, i, 1)
    if (c == "\\") { i += 2; continue }
    if (c == q) return i + 1
    i++
  }
  return i
}

# One character of code (comments and literals already removed).
function cpp_char(c,    kind) {
  if (c == "{") {
    if (cdepth > 0 && infn[cdepth] ) { cdepth++; stack[cdepth] = "b"; infn[cdepth] = 1; return }
    kind = brace_kind()
    cdepth++
    stack[cdepth] = kind
    infn[cdepth] = (kind == "f" || kind == "b")
    if (kind == "f") { fstart[cdepth] = header_line; fname[cdepth] = function_name(header) }
    if (kind != "m") { header = ""; header_line = 0 }
    return
  }
  if (c == "}") {
    if (cdepth == 0) return
    if (stack[cdepth] == "f") report(fname[cdepth], fstart[cdepth], FNR)
    kind = stack[cdepth]
    cdepth--
    if (!(cdepth > 0 && infn[cdepth])) {
      if (kind == "m") header = header "}"
      else { header = ""; header_line = 0 }
    }
    return
  }
  if (cdepth > 0 && infn[cdepth]) return
  if (c == ";") { header = ""; header_line = 0; return }
  if (header_line == 0 && c != " " && c != "\t") header_line = FNR
  if (header_line) header = header c
}

# What a `{` at namespace/class scope opens: "s" a scope (namespace, class, extern "C"),
# "f" a function body, "m" a brace initialiser in a constructor's initialiser list,
# "b" anything else (an initialiser list, a table): not a function, nothing inside is one.
function brace_kind(    h, pre, p, last) {
  h = header
  gsub(/[ \t]+$/, "", h)
  while (gsub(/<[^<>]*>/, "", h) > 0) ;                    # template arguments
  p = index(h, "(")
  pre = (p > 0) ? substr(h, 1, p - 1) : h
  if (pre ~ /(^|[^A-Za-z0-9_])(namespace|class|struct|union|enum|extern)([^A-Za-z0-9_]|$)/) return "s"
  if (p == 0) return "b"
  if (h ~ /=$/) return "b"
  last = substr(h, length(h), 1)
  h2 = h; gsub(/::/, "", h2)
  if (h2 ~ /\)[^;]*:/ && last ~ /[A-Za-z0-9_]/) return "m"
  return "f"
}

function function_name(h,    p, pre, m) {
  gsub(/[ \t]+/, " ", h)
  p = index(h, "(")
  pre = substr(h, 1, p - 1)
  sub(/ +$/, "", pre)
  if (pre ~ /\]$/) {                                        # auto f = [..](...) {
    sub(/ *= *\[[^]]*\]$/, "", pre)
  }
  if (match(pre, /[A-Za-z_~][A-Za-z0-9_:~]*$/)) return substr(pre, RSTART, RLENGTH)
  return "<anonymous>"
}

# ---------------------------------------------------------------- Lua

function lua_line(line,    n, i, c, j, rest, word) {
  n = length(line)
  i = 1
  while (i <= n) {
    if (lin_long) {
      j = index(substr(line, i), lclose)
      if (j == 0) return
      lin_long = 0; i += j - 1 + length(lclose); continue
    }
    c = substr(line, i, 1)
    if (c == "-" && substr(line, i + 1, 1) == "-") {
      rest = substr(line, i + 2)
      if (match(rest, /^\[=*\[/)) { open_long(RLENGTH - 2); i += 2 + RLENGTH; continue }
      return
    }
    if (c == "[" && match(substr(line, i), /^\[=*\[/)) { open_long(RLENGTH - 2); i += RLENGTH; continue }
    if (c == "\"" || c == "'") { i = skip_quoted(line, i, c); continue }
    if (c ~ /[A-Za-z_]/) {
      match(substr(line, i), /^[A-Za-z_][A-Za-z0-9_]*/)
      word = substr(line, i, RLENGTH)
      # after `.` or `:` a word is a field or method name, never a keyword
      if (!(i > 1 && substr(line, i - 1, 1) ~ /[.:]/)) lua_word(word, line, i)
      i += length(word)
      continue
    }
    if (c ~ /[0-9]/) { match(substr(line, i), /^[0-9A-Fa-fxX._]+/); i += RLENGTH; continue }
    i++
  }
}

function open_long(level) {
  lin_long = 1
  lclose = "]"
  while (level-- > 0) lclose = lclose "="
  lclose = lclose "]"
}

function lua_word(w, line, i,    name, before) {
  if (w == "function") {
    ldepth++
    lkind[ldepth] = "F"
    lstart[ldepth] = FNR
    name = substr(line, i + 8)
    if (match(name, /^[ \t]*[A-Za-z_][A-Za-z0-9_.:]*/)) {
      name = substr(name, RSTART, RLENGTH); gsub(/[ \t]/, "", name)
    } else {
      before = substr(line, 1, i - 1)
      if (match(before, /[A-Za-z_][A-Za-z0-9_.:\]\["']*[ \t]*=[ \t]*$/)) {
        name = substr(before, RSTART, RLENGTH); sub(/[ \t]*=[ \t]*$/, "", name)
      } else name = "<anonymous>"
    }
    lname[ldepth] = name
    return
  }
  if (w == "do" || w == "if" || w == "repeat") { ldepth++; lkind[ldepth] = "B"; return }
  if (w == "end" || w == "until") {
    if (ldepth == 0) return
    if (lkind[ldepth] == "F") report(lname[ldepth], lstart[ldepth], FNR)
    ldepth--
  }
}
