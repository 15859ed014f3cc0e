#!/bin/sh
# SPDX-License-Identifier: MIT
# Writes the manual page smi-lua.1 from what the built program says about itself, so the page
# cannot drift from the options: `smi-lua --help` (every option and the command list), the
# usage line of `smi-lua doc --help`, and the version line of `smi-lua -v`.
#   man_page.sh SMI_LUA OUT.1
# The help text's layout is what this reads: a line ending in ':' at the margin starts a section
# (.SS), a line "  -x, --name ARG   meaning" an option (.TP), a deeper-indented line continues the
# meaning above it; other lines are prose.
set -eu
smi=$1
out=$2
tmp=$out.tmp

version=$("$smi" -v 2>&1 | head -n 1)
# "smi-lua 0.1.0 (Lua 5.4.4), ..." -> "0.1.0"
number=$(printf '%s\n' "$version" | awk '{ print $2 }')
doc_usage=$("$smi" doc --help 2>&1 | sed -n 's/^usage: smi-lua //p' | head -n 1)

# roff escapes: a backslash, and a leading '.' or '\'' that roff would read as a request.
esc() { sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/" -e 's/-/\\-/g'; }

{
  printf '.TH SMI\\-LUA 1 "" "smi-lua %s" "User Commands"\n' "$number"
  printf '.SH NAME\nsmi\\-lua \\- statistical model improvement in Lua: calibration, validation and refinement of computer models against test data\n'
  printf '.SH SYNOPSIS\n.B smi\\-lua\n[\\fIoptions\\fR] [\\fIscript\\fR [\\fIargs\\fR]]\n.br\n'
  printf '.B smi\\-lua\n\\fBdoc\\fR [\\fINAME\\fR|\\fIWORD\\fR]\n.br\n'
  printf '.B smi\\-lua\n\\fIcommand\\fR [\\fIargs\\fR]\n'
  printf '.SH DESCRIPTION\n'
  # --help without its usage line: prose, then sections of options.
  "$smi" --help 2>&1 | sed '1{/^usage:/d}' | esc | awk '
    function flush() { if (opt != "") { print ".TP"; print "\\fB" opt "\\fR" (arg != "" ? " \\fI" arg "\\fR" : ""); print text; in_list = 1 }; opt = ""; arg = ""; text = "" }
    /^$/ { flush(); if (!blank) print ".PP"; blank = 1; in_list = 0; next }
    { blank = 0 }
    /^[^ ].*:$/ { flush(); sub(/:$/, ""); print ".SS " $0; next }
    /^  [^ ]/ && match($0, /^  [^ ]([^ ]| [^ ])*  +/) {
      flush()
      head = substr($0, 3, RLENGTH - 2); text = substr($0, RLENGTH + 1)
      sub(/ +$/, "", head)
      # "-l mod", "--lib DIR", "-h, --help": the option words in bold, an argument in italics
      n = split(head, w, " "); opt = w[1]; arg = ""
      for (i = 2; i <= n; i++) { if (w[i] ~ /^\\-/ && arg == "") opt = opt " " w[i]; else arg = arg (arg == "" ? "" : " ") w[i] }
      next
    }
    /^    / && opt != "" { s = $0; sub(/^ +/, "", s); text = text "\n" s; next }
    # prose; after a list of options it starts a paragraph of its own
    { flush(); if (in_list) { print ".PP"; in_list = 0 }; s = $0; sub(/^ +/, "", s); print s }
    END { flush() }
  '
  printf '.SH THE REFERENCE\n.TP\n\\fBsmi\\-lua %s\\fR\n' "$(printf '%s' "$doc_usage" | esc)"
  printf 'prints the reference entry of NAME (signature, options with defaults, returns, errors, an example), the entries mentioning WORD, or the list of modules; \\fB\\-\\-html DIR\\fR writes the whole reference as pages with a search box; \\fB\\-\\-check\\fR runs every example. The REPL shows the same texts with \\fBhelp()\\fR, \\fBhelp(smi.kde)\\fR or \\fB?smi.kde\\fR.\n'
  printf '.SH FILES\n.TP\n.I /usr/share/smi\\-lua/scripts/\n'
  printf 'example studies with their data: \\fBsteering_column.lua\\fR (the study of Son et al. 2020, driving the solver \\fBcolumn\\-fe\\fR), \\fBtutorial/\\fR, \\fBcharacterize.lua\\fR.\n'
  printf '.TP\n.I /usr/share/doc/smi\\-lua/html/index.html\nthe reference as HTML pages.\n'
  printf '.TP\n.I smi\\-out/<script>/\nthe default output folder of a study: report.html, results.json, evaluations.sqlite.\n'
  printf '.SH EXAMPLES\nRun the steering-column study on its committed data, from any folder:\n.PP\n.nf\n'
  printf '  smi\\-lua \\-\\-allow\\-exec column\\-fe /usr/share/smi\\-lua/scripts/steering_column.lua \\-\\-quick\n.fi\n'
  printf '.PP\nShow the reference of the kernel density estimate:\n.PP\n.nf\n  smi\\-lua doc smi.kde\n.fi\n'
  printf '.SH VERSION\n%s\n' "$(printf '%s' "$version" | esc)"
  printf '.SH SEE ALSO\n\\fBlua\\fR(1). Son, Lee, Youn et al. (2020), Industrial issues and solutions to statistical model improvement: a case study of an automobile steering column, Structural and Multidisciplinary Optimization.\n'
} > "$tmp"
mv "$tmp" "$out"
