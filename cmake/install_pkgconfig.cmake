# Run by `cmake --install` (install(CODE) in CMakeLists.txt): writes the pkg-config files with the prefix of
# this install, which `cmake --install build --prefix P` sets to P (the configure-time CMAKE_INSTALL_PREFIX
# otherwise: /usr for the Debian packages), and installs them (DESTDIR is honoured by file(INSTALL)).
# In: TRIONET_PC_NAMES (trionet, trionet-host), TRIONET_PC_SOURCE_DIR (cmake/), TRIONET_PC_BINARY_DIR,
# TRIONET_PC_INCLUDE (CMAKE_INSTALL_INCLUDEDIR), TRIONET_PC_LIB (CMAKE_INSTALL_LIBDIR), PROJECT_DESCRIPTION,
# PROJECT_VERSION. A relative include or lib directory is written under ${prefix}, so that
# `pkg-config --define-variable=prefix=...` moves it too; an absolute one is written as it is.
set(TRIONET_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
foreach(kind INCLUDE LIB)
  if(IS_ABSOLUTE "${TRIONET_PC_${kind}}")
    set(TRIONET_PC_${kind}DIR "${TRIONET_PC_${kind}}")
  else()
    set(TRIONET_PC_${kind}DIR "\${prefix}/${TRIONET_PC_${kind}}")
  endif()
endforeach()
if(IS_ABSOLUTE "${TRIONET_PC_LIB}")
  set(destination "${TRIONET_PC_LIB}/pkgconfig")
else()
  set(destination "${CMAKE_INSTALL_PREFIX}/${TRIONET_PC_LIB}/pkgconfig")
endif()
foreach(name ${TRIONET_PC_NAMES})
  configure_file("${TRIONET_PC_SOURCE_DIR}/${name}.pc.in" "${TRIONET_PC_BINARY_DIR}/${name}.pc" @ONLY)
  file(INSTALL DESTINATION "${destination}" TYPE FILE FILES "${TRIONET_PC_BINARY_DIR}/${name}.pc")
endforeach()
