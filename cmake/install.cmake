# `cmake --install build --prefix P` (included by the top CMakeLists.txt):
#   P/bin/dynosize                                  the CLI
#   P/lib/libdynosize_*.a                           the library (static), target dynosize::dynosize
#   P/include/dynosize/dynosize.h                   the umbrella header
#   P/include/dynosize/<module>/*.h                 the headers of src/, in src/'s layout
#   P/lib/cmake/dynosize/dynosizeConfig*.cmake      find_package(dynosize CONFIG)
#   P/share/dynosize/catalog/                       the bundled catalog (the default catalog of an
#                                                   installed build: catalog/catalog_path.h)
include(CMakePackageConfigHelpers)

set(DYNOSIZE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/dynosize)

install(TARGETS dynosize RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS dynosize_library dynosize_optimization dynosize_solvers dynosize_core
        EXPORT dynosizeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT dynosizeTargets NAMESPACE dynosize:: DESTINATION ${DYNOSIZE_CMAKE_DIR})

install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dynosize
        FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_SOURCE_DIR}/include/dynosize/dynosize.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dynosize)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/catalog/ DESTINATION ${CMAKE_INSTALL_DATADIR}/dynosize/catalog)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/dynosizeConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/dynosizeConfig.cmake
                              INSTALL_DESTINATION ${DYNOSIZE_CMAKE_DIR}
                              PATH_VARS CMAKE_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/dynosizeConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/dynosizeConfig.cmake ${PROJECT_BINARY_DIR}/dynosizeConfigVersion.cmake
        DESTINATION ${DYNOSIZE_CMAKE_DIR})

# P/share/dynosize/web/: the page `dynosize serve` serves (web/ and Chart.js, as in <build>/web;
# server/page_files.h DefaultPageDir finds it beside P/bin/dynosize).
install(DIRECTORY ${PROJECT_BINARY_DIR}/web/ DESTINATION ${CMAKE_INSTALL_DATADIR}/dynosize/web)
