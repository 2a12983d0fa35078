# Installation (cmake --install, cpack): public headers under include/glass, libglass-engine,
# the refraction plugin (static library, Embree reference, loadable module), the tools, the
# default character and sky, and the CMake package Glass (README "Using Glass in your project").
include(CMakePackageConfigHelpers)

set(GLASS_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Glass)
set(GLASS_INSTALL_PLUGINDIR ${CMAKE_INSTALL_LIBDIR}/glass)
set(GLASS_INSTALL_ASSETSDIR ${CMAKE_INSTALL_DATADIR}/glass/assets)

install(DIRECTORY engine/include/engine plugin_refraction/include/refraction
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/glass)
install(TARGETS engine refraction EXPORT GlassTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS glass_refraction EXPORT GlassTargets LIBRARY DESTINATION ${GLASS_INSTALL_PLUGINDIR})
set(glass_tools glass-capture glass-compare glass-inspect glass-viewer glass-bench glass-soak
                glass-cpu-bench)
install(TARGETS ${glass_tools} EXPORT GlassTargets RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT GlassTargets NAMESPACE Glass:: DESTINATION ${GLASS_INSTALL_CMAKEDIR})
# The reference tracer links Embree statically into its users: its own export set, which
# GlassConfig loads when Embree is found.
install(TARGETS refraction_reference EXPORT GlassReferenceTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT GlassReferenceTargets NAMESPACE Glass:: DESTINATION ${GLASS_INSTALL_CMAKEDIR})

install(FILES assets/models/glass_figure.glb DESTINATION ${GLASS_INSTALL_ASSETSDIR}/models)
install(FILES assets/env/sunset_sky.hdr DESTINATION ${GLASS_INSTALL_ASSETSDIR}/env)
install(FILES assets/scenes/walk_past.json DESTINATION ${GLASS_INSTALL_ASSETSDIR}/scenes)
install(FILES README.md ARCHITECTURE.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)

configure_package_config_file(cmake/GlassConfig.cmake.in
    ${CMAKE_CURRENT_BINARY_DIR}/GlassConfig.cmake
    INSTALL_DESTINATION ${GLASS_INSTALL_CMAKEDIR}
    PATH_VARS GLASS_INSTALL_ASSETSDIR GLASS_INSTALL_PLUGINDIR)
# Versioning (README): before 1.0 a minor version may break the API and the ABI, so a request
# is met by the same major.minor only; from 1.0 by the same major version.
if(PROJECT_VERSION_MAJOR EQUAL 0)
    set(glass_compatibility SameMinorVersion)
else()
    set(glass_compatibility SameMajorVersion)
endif()
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/GlassConfigVersion.cmake
    COMPATIBILITY ${glass_compatibility})
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/GlassConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/GlassConfigVersion.cmake cmake/GlassCapture.cmake
        DESTINATION ${GLASS_INSTALL_CMAKEDIR})
