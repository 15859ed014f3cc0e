# SPDX-License-Identifier: MIT
# Fails on a file that opens a namespace outside its folder's (cmake -DROOT=<source dir> -P this).
#
# The rule (docs/design.md, Layout): every folder of host/ lives in the namespace named after it,
# nested ones inside it allowed (smi::surrogate::kriging, smi::stats::detail):
#   host/kernels/<area>/  and host/platform/<area>/   smi::<area>
#   host/platform/core/   smi and its components (smi::cancel, smi::pool, ...): the shared
#                         vocabulary, which opens no other folder's namespace
#   host/luax/            smi::lua        host/vm/, sandbox/, app/, repl/, cli/   smi::<folder>
#   bindings/             smi::bind (an area's files in smi::bind::<area>)
# Run by the test layout.namespace_check (tests/layout/). Each violation:
# "<file>:<line>: namespace <name> -- <rule>".

cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/source_lines.cmake)

if(NOT ROOT)
  message(FATAL_ERROR "check_namespaces.cmake: pass -DROOT=<source dir>")
endif()

# Every namespace a folder of the tree owns (core's components are checked apart).
set(_owned stats surrogate improve eval lua vm sandbox app repl cli bind)

file(GLOB_RECURSE _files RELATIVE ${ROOT} LIST_DIRECTORIES false ${ROOT}/host/* ${ROOT}/bindings/*)
set(_violations "")
set(_count 0)
foreach(rel IN LISTS _files)
  if(NOT rel MATCHES "\\.(cpp|hpp|h|inc|cc|hh)$")
    continue()
  endif()
  set(core FALSE)
  if(rel MATCHES "^host/platform/core/")
    set(core TRUE)
    set(folder "host/platform/core")
  elseif(rel MATCHES "^host/(kernels|platform)/([^/]+)/")
    set(want "${CMAKE_MATCH_2}")
    set(folder "host/${CMAKE_MATCH_1}/${CMAKE_MATCH_2}")
  elseif(rel MATCHES "^host/luax/")
    set(want lua)
    set(folder host/luax)
  elseif(rel MATCHES "^host/([^/]+)/")
    set(want "${CMAKE_MATCH_1}")
    set(folder "host/${CMAKE_MATCH_1}")
  elseif(rel MATCHES "^bindings/")
    set(want bind)
    set(folder bindings)
  else()
    continue()
  endif()
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
    if(core)
      foreach(other IN LISTS _owned)
        if(ns MATCHES "^smi::${other}(::|$)")
          set(bad "core is the shared vocabulary in smi (and its components smi::<component>); it opens no other folder's namespace")
        endif()
      endforeach()
    elseif(NOT ns MATCHES "^smi::${want}(::|$)")
      set(bad "a file in ${folder}/ lives in smi::${want} (or a namespace nested in it)")
    endif()
    if(bad)
      string(APPEND _violations "${rel}:${n}: namespace ${ns} -- ${bad}\n")
      math(EXPR _count "${_count} + 1")
    endif()
  endforeach()
endforeach()

if(_count GREATER 0)
  message(NOTICE "${_violations}")
  message(FATAL_ERROR "${_count} namespace(s) outside their folder's; the rule is in cmake/check_namespaces.cmake and docs/design.md (Layout)")
endif()
