# The Debian package: `cpack -G DEB` in a build folder writes glass_VERSION_ARCH.deb, the
# install tree above under /usr. Its dependencies are what the installed files need: the
# shared libraries the programs and libglass-engine link (dpkg-shlibdeps), GLM for the public
# headers, and libGL/libEGL, which epoxy and OpenSubdiv open at run time.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME glass)
set(CPACK_PACKAGE_VENDOR "the Glass developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Real-time refraction through animated glTF characters: engine, plugin and tools")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
    "An OpenGL 4.5 engine that plays skinned and morph-target glTF characters, a refraction "
    "plugin that renders them as glass (DIR, ISR, SIR), the Embree reference, frame-capture "
    "tests, and the CMake package Glass (find_package(Glass)).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON) # programs and shared objects; the static libraries keep their symbols
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "The Glass developers <glass@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libglm-dev, libegl1, libgl1")
# A GPU driver or Mesa's software rasteriser (llvmpipe) to render with
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri")
# Glass::refraction_reference (libembree-dev), building against the package (cmake, g++)
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libembree-dev, cmake, g++")
include(CPack)
