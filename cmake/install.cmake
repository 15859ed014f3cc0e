# Installing smi-lua (`cmake --install build --prefix P`) and packaging it (`cpack -G DEB` in the
# build folder). Installed:
#   bin/smi-lua, bin/column-fe, bin/beam-solver   the program and the example solvers
#   share/smi-lua/scripts/                        the example studies with their data (the
#                                                 scripts/ tree without its build files)
#   share/doc/smi-lua/html/                       the reference (`smi-lua doc --html`, at build time)
#   share/doc/smi-lua/                            README.md and docs/ (tutorial, file formats, ...)
#   share/man/man1/smi-lua.1                      made from `smi-lua --help` at build time
# An installed study finds its modules and data beside itself (smi.script_dir) and its solver
# on PATH, so nothing points back into the source tree.
include(GNUInstallDirs)

option(SMI_BUILD_DOCS "Build the HTML reference and the man page with the program (needed by install)" ON)

install(TARGETS smi-lua column-fe beam-solver RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${SMI_SOURCE_DIR}/scripts/ DESTINATION ${CMAKE_INSTALL_DATADIR}/smi-lua/scripts
        PATTERN "CMakeLists.txt" EXCLUDE PATTERN "*.cpp" EXCLUDE PATTERN "*.hpp" EXCLUDE)
# The harness's shell script drives a build folder: it keeps its execute bit.
install(PROGRAMS ${SMI_SOURCE_DIR}/scripts/steering_column/harness/run.sh
        DESTINATION ${CMAKE_INSTALL_DATADIR}/smi-lua/scripts/steering_column/harness)
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
  add_custom_target(smi_docs ALL DEPENDS ${_html}/index.html ${CMAKE_BINARY_DIR}/doc/smi-lua.1)
  install(DIRECTORY ${_html}/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/html PATTERN "example-files" EXCLUDE)
  install(FILES ${CMAKE_BINARY_DIR}/doc/smi-lua.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()

# The Debian package: cpack -G DEB gives smi-lua_<version>_amd64.deb. Its Depends come from the
# shared libraries the installed programs link (dpkg-shlibdeps, package dpkg-dev).
set(CPACK_PACKAGE_NAME smi-lua)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "smi-lua")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "statistical model improvement in Lua: calibration, validation, refinement")
set(CPACK_PACKAGE_DESCRIPTION
    "smi-lua runs studies written in Lua that calibrate, validate and refine computer models of\n"
    "products against scarce test data (Son et al. 2020): kernel density estimation with estimated\n"
    "bounded data, variance-based screening, Kriging, probability-residual calibration, u-pooling\n"
    "validation and the weighted decision matrix, in C++ over Eigen, in a sandbox that runs only\n"
    "the solvers the user names. Includes the example studies and their solver programs.")
string(REPLACE ";" "" CPACK_PACKAGE_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "smi-lua maintainers <smi-lua@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The second product's study drives CalculiX (ccx); smi-lua itself runs without it.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS calculix-ccx)
set(CPACK_GENERATOR DEB)
include(CPack)
