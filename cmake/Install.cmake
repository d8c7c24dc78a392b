# cmake --install build --prefix P (docs/library.md). Components, for installing parts:
#   library   libstrahl, the public headers, the CMake package (find_package(strahl)), strahl.pc
#   programs  strahl, strahl-diff, strahl-bench
#   docs      README.md, docs/, scenes/
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(STRAHL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/strahl)

# The library and the interface target that carries the compile options its headers' inline
# kernel code is built with (strahl::optimise: -ffp-contract=off etc., cmake/Warnings.cmake).
set_target_properties(strahl_optimise PROPERTIES EXPORT_NAME optimise)
install(TARGETS strahl strahl_optimise EXPORT strahlTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT library
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT library
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT library)
install(EXPORT strahlTargets NAMESPACE strahl:: DESTINATION ${STRAHL_CMAKE_DIR} COMPONENT library)

# Public headers: strahl/strahl.h and what it includes (cmake/public_headers.cmake), and the
# generated strahl/version.h.
install(CODE "set(STRAHL_INSTALL_HEADERS_FROM \"${PROJECT_SOURCE_DIR}/src\")
set(STRAHL_INSTALL_HEADERS_TO \"${CMAKE_INSTALL_INCLUDEDIR}\")
include(\"${PROJECT_SOURCE_DIR}/cmake/public_headers.cmake\")" COMPONENT library)
install(FILES ${PROJECT_BINARY_DIR}/include/strahl/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/strahl
        COMPONENT library)

configure_package_config_file(cmake/strahlConfig.cmake.in ${PROJECT_BINARY_DIR}/strahlConfig.cmake
                              INSTALL_DESTINATION ${STRAHL_CMAKE_DIR})
# 0.x: a new minor version may change the API, so find_package(strahl 0.1) accepts 0.1.* only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/strahlConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/strahlConfig.cmake ${PROJECT_BINARY_DIR}/strahlConfigVersion.cmake
        DESTINATION ${STRAHL_CMAKE_DIR} COMPONENT library)

# pkg-config: relocatable (paths relative to the .pc file), the same compile options and
# definitions as the CMake target.
file(RELATIVE_PATH STRAHL_PC_PREFIX_FROM_PCDIR /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" STRAHL_PC_PREFIX_FROM_PCDIR "${STRAHL_PC_PREFIX_FROM_PCDIR}")
get_target_property(optimise_options strahl_optimise INTERFACE_COMPILE_OPTIONS)
list(JOIN optimise_options " " STRAHL_PC_CFLAGS)
# The options are C++-only ($<$<COMPILE_LANGUAGE:CXX>:…>, kept from nvcc): pkg-config gets them bare.
string(REGEX REPLACE "\\$<\\$<COMPILE_LANGUAGE:CXX>:([^>]*)>" "\\1" STRAHL_PC_CFLAGS "${STRAHL_PC_CFLAGS}")
set(STRAHL_PC_LIBS_PRIVATE "")
if(embree_FOUND)
  string(APPEND STRAHL_PC_CFLAGS " -DSTRAHL_HAVE_EMBREE")
  set(STRAHL_PC_LIBS_PRIVATE "-lembree3")
endif()
set(STRAHL_PC_REQUIRES_ZLIB "")
if(ZLIB_FOUND)  # the PNG encoder (image/png_writer.h)
  set(STRAHL_PC_REQUIRES_ZLIB " zlib")
endif()
configure_file(cmake/strahl.pc.in ${PROJECT_BINARY_DIR}/strahl.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/strahl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT library)

# Programs; a shared libstrahl is found beside them ($ORIGIN/../lib).
if(BUILD_SHARED_LIBS)
  file(RELATIVE_PATH lib_from_bin /prefix/${CMAKE_INSTALL_BINDIR} /prefix/${CMAKE_INSTALL_LIBDIR})
  set_target_properties(strahl_cli strahl-diff PROPERTIES INSTALL_RPATH "$ORIGIN/${lib_from_bin}")
  if(TARGET strahl-bench)
    set_target_properties(strahl-bench PROPERTIES INSTALL_RPATH "$ORIGIN/${lib_from_bin}")
  endif()
endif()
install(TARGETS strahl_cli strahl-diff RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT programs)
if(TARGET strahl-bench)
  install(TARGETS strahl-bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT programs)
endif()

install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT docs)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT docs)
install(DIRECTORY scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/strahl/scenes COMPONENT docs)
