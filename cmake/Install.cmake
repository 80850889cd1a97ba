# `cmake --install build` (and the Debian package, tools/package_deb.sh): the binary, its man page and the user
# documentation, in the GNUInstallDirs places (prefix /usr/local by default, /usr for the package):
#   bin/sacfuse, share/man/man1/sacfuse.1.gz, share/doc/sacfuse/{README.md, LICENSE (also as copyright),
#   CHANGELOG.md, CITATION.cff, docs/}. Nothing else is installed: the libraries are static and internal.
include(GNUInstallDirs)
install(TARGETS sacfuse RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${SACFUSE_MAN_PAGE} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
set(doc_files README.md LICENSE CITATION.cff CHANGELOG.md)
foreach(f ${doc_files})
  if(EXISTS ${PROJECT_SOURCE_DIR}/${f})
    install(FILES ${PROJECT_SOURCE_DIR}/${f} DESTINATION ${CMAKE_INSTALL_DOCDIR})
  endif()
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
# Debian policy: the licence as /usr/share/doc/<package>/copyright.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)

# CPack: the Debian package sacfuse_<version>_<arch>.deb (tools/package_deb.sh). Its dependencies are the shared
# libraries the binary links, found by dpkg-shlibdeps; the binary is stripped.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME sacfuse)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "the sacfuse authors")
set(SACFUSE_PACKAGE_CONTACT "sacfuse maintainers <maintainers@sacfuse.invalid>" CACHE STRING
  "Maintainer field of the Debian package (Name <email>)")
set(CPACK_PACKAGE_CONTACT ${SACFUSE_PACKAGE_CONTACT})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "Select-and-Combine depth-map fusion for oriented aerial image blocks")
set(CPACK_PACKAGE_DESCRIPTION
  "sacfuse fuses the per-view depth maps of an oriented aerial image block (COLMAP or OpenMVS workspaces, depth
rasters with a camera file) into one clean, georeferenced LAS/LAZ point cloud with Select-and-Combine depth fusion
(Elhashash and Qin), in geo-tiles within a memory budget, with an HTML run report.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_PACKAGE_INSTALL_DIRECTORY sacfuse)
include(CPack)
