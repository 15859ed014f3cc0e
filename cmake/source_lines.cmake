# SPDX-License-Identifier: MIT
# smi_source_lines(<text> <out>): the text of a source file as a CMake list of its lines, for the
# layout checks (check_includes, check_namespaces, check_file_names). CMake lists split on ';' and
# treat [ ] specially, so those are neutralised first (the checks match includes and namespace
# openings, which never need them); backslashes become '/'. Line k of the file is element k - 1.
function(smi_source_lines text out)
  string(REPLACE ";" "," text "${text}")
  string(REPLACE "[" "(" text "${text}")
  string(REPLACE "]" ")" text "${text}")
  string(REPLACE "\\" "/" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()
