# SPDX-License-Identifier: MIT
# Fails on an implementation file that is not named after the header it implements
# (cmake -DROOT=<source dir> -P this). Run by the test layout.file_names (tests/layout/).
#
# The rule (docs/design.md, Layout), for host/: a header x.hpp is implemented in x.cpp, or in parts
# named x_<part>.cpp (kriging.hpp: kriging_fit.cpp, kriging_predict.cpp, ...), so a reader finds
# a declaration's body from the header's name. Hence:
#   - every .cpp is x.cpp or x_<part>.cpp of a header x.hpp in its folder (cli/main.cpp excepted);
#   - a header with no such file declares no free function out of line (it holds types, constants
#     and inline functions only).
# Each violation: "<file>[:<line>]: <what> -- <rule>". bindings/ keep their registration lists
# (modules.hpp, open_parts.hpp, doc.hpp), implemented by each part's file by design.

cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/source_lines.cmake)

if(NOT ROOT)
  message(FATAL_ERROR "check_file_names.cmake: pass -DROOT=<source dir>")
endif()

file(GLOB_RECURSE _cpps RELATIVE ${ROOT} LIST_DIRECTORIES false ${ROOT}/host/*.cpp)
file(GLOB_RECURSE _hpps RELATIVE ${ROOT} LIST_DIRECTORIES false ${ROOT}/host/*.hpp)
set(_violations "")
set(_count 0)
set(_implemented "")
foreach(rel IN LISTS _cpps)
  if(rel STREQUAL "host/cli/main.cpp")
    continue()
  endif()
  get_filename_component(dir ${rel} DIRECTORY)
  get_filename_component(stem ${rel} NAME_WE)
  # The header: the longest x with x.hpp beside it and stem = x or x_<part>.
  set(found "")
  set(probe "${stem}")
  while(NOT probe STREQUAL "")
    if(EXISTS ${ROOT}/${dir}/${probe}.hpp)
      set(found "${dir}/${probe}.hpp")
      break()
    endif()
    if(NOT probe MATCHES "_")
      break()
    endif()
    string(REGEX REPLACE "_[^_]*$" "" probe "${probe}")
  endwhile()
  if(found STREQUAL "")
    string(APPEND _violations "${rel}: no header ${stem}.hpp (or a prefix of it before _<part>) beside it -- name an implementation file after the header it implements: x.cpp or x_<part>.cpp\n")
    math(EXPR _count "${_count} + 1")
  else()
    list(APPEND _implemented "${found}")
  endif()
endforeach()

# Headers without an implementation file: types, constants and inline functions only. A free
# function declared out of line at namespace scope ("T name(...);" from column 0) is reported
# (smi_source_lines turns ";" into ",").
foreach(rel IN LISTS _hpps)
  if(rel IN_LIST _implemented)
    continue()
  endif()
  file(READ ${ROOT}/${rel} text)
  smi_source_lines("${text}" lines)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    if(line MATCHES "^(inline|template|constexpr|static|using|typedef|friend|extern|return|#|//|namespace|struct|class|enum|}|[ \t])")
      continue()
    endif()
    set(fn "")
    if(line MATCHES "^[A-Za-z_:<>,*& ]+[ *&]([A-Za-z_][A-Za-z0-9_]*)\\(.*\\)[ a-z]*,[ \t]*(//.*)?$")
      set(fn "${CMAKE_MATCH_1}")
    elseif(line MATCHES "^[A-Za-z_:<>,*& ]+[ *&]([A-Za-z_][A-Za-z0-9_]*)\\([^)]*,$")
      set(fn "${CMAKE_MATCH_1}")
    endif()
    if(NOT fn STREQUAL "")
      get_filename_component(stem ${rel} NAME_WE)
      string(APPEND _violations "${rel}:${n}: ${fn}() declared, but no ${stem}.cpp or ${stem}_<part>.cpp beside it -- a header's functions are implemented in a file of the same name\n")
      math(EXPR _count "${_count} + 1")
    endif()
  endforeach()
endforeach()

if(_count GREATER 0)
  message(NOTICE "${_violations}")
  message(FATAL_ERROR "${_count} file name(s) that do not match their header; the rule is in cmake/check_file_names.cmake and docs/design.md (Layout)")
endif()
