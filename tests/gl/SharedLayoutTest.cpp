// The layouts C++ and GLSL share field by field: the offset of every member of a storage block
// as the GL compiled it against the C++ struct's (GlassMaterialGpu and the small buffers:
// GlassExtentGpu, PairRangesGpu, WalkCountersGpu).
#include "support/GlTest.h"

#include "GpuState.h"
#include "Shared.h"

#include "engine/gl/Program.h"
#include "engine/gl/Shaders.h"
#include "engine/render/Shared.h"

#include <epoxy/gl.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

std::span<const gl::ShaderFile> refractionShaderFiles();

namespace {

class SharedLayout : public test::GlTest {};

const gl::ShaderFile kProbe[] = {{"probe.comp.glsl",
                                  "#include \"refraction/model/glass_materials.glsl\"\n"
                                  "#include \"refraction/passes/glass_extent.glsl\"\n"
                                  "#include \"refraction/passes/pair_ranges.glsl\"\n"
                                  "#include \"refraction/passes/walk_counters.glsl\"\n"
                                  "layout(local_size_x = 1) in;\n"
                                  "void main() {\n"
                                  "    walkedPixels = glassMaterials[0].solid + pairFrontMin;\n"
                                  "    glassBoxMax[0] = int(walkHybridBy[3]);\n"
                                  "}\n"}};

/** The byte offset GL gives `variable` of the program's storage blocks (-1: none). */
int offsetOf(const gl::Program& program, const std::string& variable) {
    const GLuint index =
        glGetProgramResourceIndex(program.id(), GL_BUFFER_VARIABLE, variable.c_str());
    if (index == GL_INVALID_INDEX)
        return -1;
    const GLenum property = GL_OFFSET;
    GLint offset = -1;
    glGetProgramResourceiv(program.id(), GL_BUFFER_VARIABLE, index, 1, &property, 1, nullptr,
                           &offset);
    return offset;
}

TEST_F(SharedLayout, GlassMaterialsAndTheSmallBuffersLieWhereTheirStructsSay) {
    gl::ShaderLibrary library;
    library.add(engineShaderFiles());
    library.add(refractionShaderFiles());
    library.add(kProbe);
    ASSERT_TRUE(library.share("render", render::sharedTable()).ok());
    ASSERT_TRUE(library.share("refraction", refraction::sharedTable()).ok());
    auto program = gl::Program::compute(library, "probe.comp.glsl");
    ASSERT_TRUE(program.ok()) << program.error().message;
    using M = refraction::GlassMaterialGpu;
    using T = refraction::TracedTextureGpu;
    const std::pair<const char*, std::size_t> material[] = {
        {"ior", offsetof(M, ior)},
        {"transmission", offsetof(M, transmission)},
        {"sigma", offsetof(M, sigma)},
        {"roughness", offsetof(M, roughness)},
        {"baseColor", offsetof(M, baseColor)},
        {"metallic", offsetof(M, metallic)},
        {"emissive", offsetof(M, emissive)},
        {"solid", offsetof(M, solid)},
        {"specularColor", offsetof(M, specularColor)},
        {"specularWeight", offsetof(M, specularWeight)},
        {"sheenColor", offsetof(M, sheenColor)},
        {"sheenRoughness", offsetof(M, sheenRoughness)},
        {"clearcoat", offsetof(M, clearcoat)},
        {"clearcoatRoughness", offsetof(M, clearcoatRoughness)},
        {"iridescence", offsetof(M, iridescence)},
        {"iridescenceIor", offsetof(M, iridescenceIor)},
        {"filmThickness", offsetof(M, filmThickness)},
        {"normalScale", offsetof(M, normalScale)},
        {"authored", offsetof(M, authored)},
        {"normalTexture.row0", offsetof(M, normalTexture) + offsetof(T, row0)},
        {"normalTexture.unit", offsetof(M, normalTexture) + offsetof(T, unit)},
        {"normalTexture.row1", offsetof(M, normalTexture) + offsetof(T, row1)},
        {"normalTexture.uvSet", offsetof(M, normalTexture) + offsetof(T, uvSet)},
        {"baseColorTexture.unit", offsetof(M, baseColorTexture) + offsetof(T, unit)},
        {"metallicRoughnessTexture.unit",
         offsetof(M, metallicRoughnessTexture) + offsetof(T, unit)},
        {"transmissionTexture.uvSet", offsetof(M, transmissionTexture) + offsetof(T, uvSet)},
    };
    for (const auto& [field, offset] : material)
        EXPECT_EQ(offsetOf(*program, std::string("glassMaterials[0].") + field), int(offset))
            << field;
    const int second = offsetOf(*program, "glassMaterials[1].ior");
    EXPECT_TRUE(second == -1 || second == int(sizeof(M))) << "the array's stride";
    using E = refraction::GlassExtentGpu;
    using P = refraction::PairRangesGpu;
    using C = refraction::WalkCountersGpu;
    const std::pair<const char*, std::size_t> small[] = {
        {"glassPixelMin[0]", offsetof(E, pixelMin)},
        {"glassPixelMax[0]", offsetof(E, pixelMax)},
        {"glassBoxMin[0]", offsetof(E, boxMin)},
        {"glassBoxMax[0]", offsetof(E, boxMax)},
        {"pairBackRange[0]", offsetof(P, backRange)},
        {"pairFrontMin", offsetof(P, frontMin)},
        {"walkOverflowPixels", offsetof(C, overflowPixels)},
        {"walkTraceRays", offsetof(C, traceRays)},
        {"walkTraceSteps[0]", offsetof(C, traceSteps)},
        {"walkTraceMaxSteps", offsetof(C, traceMaxSteps)},
        {"walkedPixels", offsetof(C, walkedPixels)},
        {"walkHybridTraced", offsetof(C, hybridTraced)},
        {"walkHybridBy[0]", offsetof(C, hybridBy)},
        {"walkFreshPixels", offsetof(C, freshPixels)},
        {"freshGroups[0]", offsetof(C, freshGroups)},
        {"freshPixelList[0]", sizeof(C)},
    };
    for (const auto& [field, offset] : small)
        EXPECT_EQ(offsetOf(*program, field), int(offset)) << field;
}

} // namespace
