# Fails on a kernel file that opens a namespace outside its area's (cmake -DROOT=<source dir> -P this).
#
# The rule (README, Layout): each kernel area lives in the namespace named after its folder,
# smi::stats, smi::surrogate, smi::eval, smi::improve, nested ones inside it allowed
# (smi::surrogate::kriging, smi::stats::detail); core is the shared vocabulary in smi and its
# components (smi::cancel, smi::pool, ...), and opens no other area's namespace. Run by the test
# layout.namespace_check (tests/layout/). Each violation: "<file>:<line>: namespace <name> -- <rule>".

cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/source_lines.cmake)

set(_areas stats surrogate eval improve)
if(NOT ROOT)
  message(FATAL_ERROR "check_namespaces.cmake: pass -DROOT=<source dir>")
endif()

file(GLOB_RECURSE _files RELATIVE ${ROOT} LIST_DIRECTORIES false ${ROOT}/host/kernels/*)
set(_violations "")
set(_count 0)
foreach(rel IN LISTS _files)
  if(NOT rel MATCHES "^host/kernels/([^/]+)/.*\\.(cpp|hpp|h|inc|cc|hh)$")
    continue()
  endif()
  set(area "${CMAKE_MATCH_1}")
  file(READ ${ROOT}/${rel} text)
  smi_source_lines("${text}" lines)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    if(NOT line MATCHES "^[ \t]*namespace[ \t]+(smi[A-Za-z0-9_:]*)[ \t]*{")
      continue()
    endif()
    set(ns "${CMAKE_MATCH_1}")
    set(bad "")
    if(area STREQUAL "core")
      foreach(other IN LISTS _areas)
        if(ns MATCHES "^smi::${other}(::|$)")
          set(bad "core is the shared vocabulary in smi (and its components smi::<component>); it opens no other area's namespace")
        endif()
      endforeach()
    elseif(NOT ns MATCHES "^smi::${area}(::|$)")
      set(bad "a kernel in host/kernels/${area}/ lives in smi::${area} (or a namespace nested in it)")
    endif()
    if(bad)
      string(APPEND _violations "${rel}:${n}: namespace ${ns} -- ${bad}\n")
      math(EXPR _count "${_count} + 1")
    endif()
  endforeach()
endforeach()

if(_count GREATER 0)
  message(NOTICE "${_violations}")
  message(FATAL_ERROR "${_count} kernel namespace(s) outside their area; the rule is in cmake/check_namespaces.cmake and the README (Layout)")
endif()
