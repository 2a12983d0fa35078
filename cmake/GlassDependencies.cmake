# Dependencies, all from Debian 12 packages (scripts/deps installs them). Each is found once here
# and exposed as an imported target; modules link the targets, never raw paths.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)

# libglm-dev
find_package(glm REQUIRED)
# libtinygltf-dev: its header, whose implementation engine/src/asset/TinyGltf.cpp compiles (only
# engine/src/asset includes tiny_gltf.h)
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)
# libstb-dev: image decoding (PNG/JPEG in glTF, HDR environments) and PNG writing
pkg_check_modules(STB REQUIRED IMPORTED_TARGET GLOBAL stb)
# Its headers alone: the engine compiles the implementation (engine/src/third_party/Stb.cpp).
add_library(glass_stb_headers INTERFACE)
target_include_directories(glass_stb_headers SYSTEM INTERFACE ${STB_INCLUDE_DIRS})
# zlib1g-dev: checks PNG image data before stb inflates it (asset/ImageChecks)
find_package(ZLIB REQUIRED)
# libdraco-dev, libmeshoptimizer-dev: decoders of KHR_draco_mesh_compression and
# EXT_meshopt_compression geometry (only engine/src/asset includes them)
find_package(draco REQUIRED)
find_package(meshoptimizer REQUIRED)
# libjpeg-dev (libjpeg-turbo): JPEG images and environments (stb's JPEG decoder is not used)
find_package(JPEG REQUIRED)
# libwebp-dev: EXT_texture_webp images
pkg_check_modules(WEBP REQUIRED IMPORTED_TARGET GLOBAL libwebp)
# libepoxy-dev: GL and EGL entry points (only engine/src/gl includes it)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET GLOBAL epoxy)
# libglfw3-dev: windows (GL 4.5 core) for the viewer
pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET GLOBAL glfw3)
# libimgui-dev: Dear ImGui with its GLFW and OpenGL3 backends, unmodified (the viewer's panel and
# the plugins' panel hooks)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET GLOBAL imgui)
# libosd-dev: OpenSubdiv 3.5 (Far topology refinement and stencils, Osd CPU and GL compute
# evaluators; only engine/src/deform includes it). Debian's CMake config for it names static
# libraries the package does not ship, so the two shared libraries are found directly.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/osd/glComputeEvaluator.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
find_library(OPENSUBDIV_GPU_LIBRARY osdGPU REQUIRED)
foreach(part CPU GPU)
    add_library(OpenSubdiv::osd${part} SHARED IMPORTED)
    set_target_properties(OpenSubdiv::osd${part} PROPERTIES
        IMPORTED_LOCATION ${OPENSUBDIV_${part}_LIBRARY}
        INTERFACE_INCLUDE_DIRECTORIES ${OPENSUBDIV_INCLUDE_DIR}
        INTERFACE_COMPILE_DEFINITIONS "OPENSUBDIV_HAS_OPENGL;OPENSUBDIV_HAS_GLSL_COMPUTE")
endforeach()
# libembree-dev: the reference ray tracer (plugin_refraction only)
find_package(embree 3 REQUIRED)
# nlohmann-json3-dev: JSON output of the tools and parsing in tests (tinygltf uses it too)
find_package(nlohmann_json 3 REQUIRED)

if(GLASS_BUILD_TESTS)
    # libgtest-dev
    find_package(GTest REQUIRED)
endif()
