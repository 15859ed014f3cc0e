# SPDX-License-Identifier: MIT
# Installing smi-lua (`cmake --install build --prefix P`) and packaging it (`cpack -G DEB` in the
# build folder). Installed:
#   bin/smi-lua, bin/smi-column-fe, bin/smi-beam-solver   the program and the example solvers
#   share/smi-lua/scripts/                        the example studies with their data (the
#                                                 scripts/ tree without its build files)
#   share/doc/smi-lua/html/                       the reference (`smi-lua doc --html`, at build time)
#   share/doc/smi-lua/                            README.md and docs/ (tutorial, file formats, ...)
#   share/man/man1/smi-lua.1.gz                   made from `smi-lua --help` at build time
#   share/man/man1/smi-column-fe.1.gz, smi-beam-solver.1.gz   the solvers' pages (packaging/man)
#   share/doc/smi-lua/copyright                   the licences (packaging/copyright, Debian's format)
#   share/doc/smi-lua/changelog.Debian.gz         the package's changelog (packaging/changelog.Debian.in)
# An installed study finds its modules and data beside itself (smi.script_dir) and its solver
# on PATH, so nothing points back into the source tree.
include(GNUInstallDirs)

option(SMI_BUILD_DOCS "Build the HTML reference and the man page with the program (needed by install)" ON)

# The package's maintainer (Debian's Maintainer field and the changelog's signature). Set it with
# -DSMI_PACKAGE_MAINTAINER="Name <address>" for a package that leaves the building machine. The
# default follows Debian's tools: DEBFULLNAME and DEBEMAIL (as dch reads them), else the git
# identity of the source tree (as gbp dch reads it), else a placeholder of the project.
set(_maintainer "smi-lua maintainers <maintainers@smi-lua.org>")
if(DEFINED ENV{DEBEMAIL} AND NOT "$ENV{DEBEMAIL}" STREQUAL "")
  set(_name "$ENV{DEBFULLNAME}")
  if(_name STREQUAL "")
    set(_name "$ENV{NAME}")
  endif()
  set(_maintainer "${_name} <$ENV{DEBEMAIL}>")
else()
  find_package(Git QUIET)
  if(GIT_FOUND)
    execute_process(COMMAND ${GIT_EXECUTABLE} config user.name WORKING_DIRECTORY ${SMI_SOURCE_DIR}
                    OUTPUT_VARIABLE _name OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    execute_process(COMMAND ${GIT_EXECUTABLE} config user.email WORKING_DIRECTORY ${SMI_SOURCE_DIR}
                    OUTPUT_VARIABLE _email OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    # An address without a dotted host (user@localhost) is no address to write to.
    if(NOT _name STREQUAL "" AND _email MATCHES "^[^@ ]+@[^@ ]+[.][^@ .]+$")
      set(_maintainer "${_name} <${_email}>")
    endif()
  endif()
endif()
set(SMI_PACKAGE_MAINTAINER "${_maintainer}" CACHE STRING "Maintainer of the Debian package: Name <address>")
if(NOT SMI_PACKAGE_MAINTAINER MATCHES "^[^<>]+ <[^@<> ]+@[^@<> ]+[.][^@<> .]+>$")
  message(FATAL_ERROR "SMI_PACKAGE_MAINTAINER is '${SMI_PACKAGE_MAINTAINER}': give it as "
                      "\"Name <user@host.domain>\" (-DSMI_PACKAGE_MAINTAINER=...)")
endif()

# Man pages and the changelog go compressed (gzip -9n: no name or time stamp, so two builds of
# one tree give the same bytes), as Debian policy asks.
find_program(SMI_GZIP gzip REQUIRED)
function(smi_gzip src dst)
  add_custom_command(OUTPUT ${dst} COMMAND ${SMI_GZIP} -9nc ${src} > ${dst} DEPENDS ${src}
                     COMMENT "Compressing ${dst}")
endfunction()
set(_pkg ${CMAKE_BINARY_DIR}/packaging)
configure_file(${SMI_SOURCE_DIR}/packaging/changelog.Debian.in ${_pkg}/changelog.Debian @ONLY)
smi_gzip(${_pkg}/changelog.Debian ${_pkg}/changelog.Debian.gz)
set(_package_files ${_pkg}/changelog.Debian.gz)
foreach(page smi-column-fe smi-beam-solver)
  smi_gzip(${SMI_SOURCE_DIR}/packaging/man/${page}.1 ${_pkg}/${page}.1.gz)
  list(APPEND _package_files ${_pkg}/${page}.1.gz)
endforeach()
add_custom_target(smi_package_files ALL DEPENDS ${_package_files})
install(FILES ${SMI_SOURCE_DIR}/packaging/copyright ${_pkg}/changelog.Debian.gz DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${_pkg}/smi-column-fe.1.gz ${_pkg}/smi-beam-solver.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

install(TARGETS smi-lua smi-column-fe smi-beam-solver RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The harnesses' shell scripts keep their execute bit (git records it): USE_SOURCE_PERMISSIONS.
install(DIRECTORY ${SMI_SOURCE_DIR}/scripts/ DESTINATION ${CMAKE_INSTALL_DATADIR}/smi-lua/scripts USE_SOURCE_PERMISSIONS
        PATTERN "CMakeLists.txt" EXCLUDE PATTERN "*.cpp" EXCLUDE PATTERN "*.hpp" EXCLUDE
        PATTERN "column-fe" EXCLUDE PATTERN "beam-solver" EXCLUDE)  # the solvers' sources: nothing to install
install(FILES ${SMI_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${SMI_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})

if(SMI_BUILD_DOCS)
  # Both follow the built program: a new option or reference entry appears in them on the next
  # build. The HTML reference runs every example (a few seconds); its outputs stay in the build.
  set(_html ${CMAKE_BINARY_DIR}/doc/html)
  file(GLOB _guides CONFIGURE_DEPENDS ${SMI_SOURCE_DIR}/docs/*.md)  # rendered into html/guides/
  add_custom_command(
    OUTPUT ${_html}/index.html
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${_html}
    COMMAND $<TARGET_FILE:smi-lua> --quiet doc --html ${_html} --guides ${SMI_SOURCE_DIR}/docs
            --out ${CMAKE_BINARY_DIR}/doc/example-out > /dev/null
    DEPENDS smi-lua ${_guides}
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}
    COMMENT "Writing the HTML reference (smi-lua doc --html)")
  add_custom_command(
    OUTPUT ${CMAKE_BINARY_DIR}/doc/smi-lua.1
    COMMAND sh ${SMI_SOURCE_DIR}/cmake/man_page.sh $<TARGET_FILE:smi-lua> ${CMAKE_BINARY_DIR}/doc/smi-lua.1
    DEPENDS smi-lua ${SMI_SOURCE_DIR}/cmake/man_page.sh
    COMMENT "Writing the man page smi-lua.1 from smi-lua --help")
  smi_gzip(${CMAKE_BINARY_DIR}/doc/smi-lua.1 ${CMAKE_BINARY_DIR}/doc/smi-lua.1.gz)
  add_custom_target(smi_docs ALL DEPENDS ${_html}/index.html ${CMAKE_BINARY_DIR}/doc/smi-lua.1.gz)
  install(DIRECTORY ${_html}/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/html PATTERN "example-files" EXCLUDE)
  install(FILES ${CMAKE_BINARY_DIR}/doc/smi-lua.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()

# The Debian package: cpack -G DEB gives smi-lua_<version>-1_amd64.deb. Its Depends come from the
# shared libraries the installed programs link (dpkg-shlibdeps, package dpkg-dev).
set(CPACK_PACKAGE_NAME smi-lua)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "smi-lua")
# Lines of the description: a summary under 80 characters, then paragraphs of lines under 80.
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "statistical model improvement in Lua: calibration, validation, refinement")
set(CPACK_PACKAGE_DESCRIPTION
    "smi-lua runs studies written in Lua that calibrate, validate and refine\n"
    "computer models of products against scarce test data (Son et al. 2020):\n"
    "kernel density estimation with estimated bounded data, variance-based\n"
    "screening, Kriging, probability-residual calibration, u-pooling validation\n"
    "and the weighted decision matrix, in C++ over Eigen, in a sandbox that runs\n"
    "only the solvers the user names. Includes the example studies and their\n"
    "solver programs, smi-column-fe and smi-beam-solver.")
string(REPLACE ";" "" CPACK_PACKAGE_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "${SMI_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${SMI_PACKAGE_MAINTAINER}")
# 0.1.0-1: the first package of upstream 0.1.0 (its changelog is changelog.Debian.gz).
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Binaries without their symbol tables, as Debian installs them.
set(CPACK_STRIP_FILES ON)
# The second product's study drives CalculiX (ccx); smi-lua itself runs without it.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS calculix-ccx)
set(CPACK_GENERATOR DEB)
include(CPack)
