// The GL layer: shader includes, program errors, framebuffer completeness, error accounting.
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/gl/Buffer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/ProgramCache.h"
#include "engine/gl/Registry.h"
#include "engine/gl/Texture.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>

namespace {

class GlLayer : public test::GlTest {};

/** A test's own storage slots, registered past the engine's and the plugin's. */
constexpr gl::StorageSlot kOut{70, "OUT_BINDING", "Out"};
constexpr gl::StorageSlot kOther{71, "OTHER_BINDING", "Other"};
constexpr gl::Shared kTestTable[] = {kOut, kOther};

const gl::ShaderFile kFiles[] = {
    {"a.glsl", "#include \"b.glsl\"\nfloat a() { return b(); }\n"},
    {"b.glsl", "float b() { return 2.0; }\n"},
    {"loop1.glsl", "#include \"loop2.glsl\"\n"},
    {"loop2.glsl", "#include \"loop1.glsl\"\n"},
    {"main.comp.glsl", "#include \"a.glsl\"\nlayout(local_size_x = 1) in;\n"
                       "layout(std430, binding = OUT_BINDING) buffer Out { float v[]; };\n"
                       "void main() { v[0] = a(); }\n"},
    // Block Out declared at the binding registered for block Other.
    {"misplaced.comp.glsl", "layout(local_size_x = 1) in;\n"
                            "layout(std430, binding = OTHER_BINDING) buffer Out { float v[]; };\n"
                            "void main() { v[0] = 1.0; }\n"},
    {"broken.comp.glsl", "layout(local_size_x = 1) in;\nvoid main() { undefined_call(); }\n"},
    // VALUE and SCALE (2 unless given) make the variant.
    {"variant.comp.glsl", "layout(local_size_x = 1) in;\n"
                          "layout(std430, binding = OUT_BINDING) buffer Out { float v[]; };\n"
                          "#ifndef SCALE\n#define SCALE 2.0\n#endif\n"
                          "void main() { v[0] = VALUE * SCALE; }\n"},
};

/** A library of kFiles with the test's table shared. */
gl::ShaderLibrary testLibrary() {
    gl::ShaderLibrary library;
    library.add(kFiles);
    EXPECT_TRUE(library.share("test", kTestTable).ok());
    return library;
}

/** What `program` writes into a one-float buffer. */
float runOnce(const gl::Program& program) {
    gl::Buffer out(sizeof(float));
    program.use();
    gl::bindStorage(kOut, out);
    gl::dispatch(1);
    gl::memoryBarrier(gl::BarrierAll);
    const auto bytes = out.download();
    float value = 0.0f;
    std::memcpy(&value, bytes.data(), sizeof value);
    return value;
}

TEST_F(GlLayer, IncludesResolveAndComputeRuns) {
    gl::ShaderLibrary library = testLibrary();
    auto program = gl::Program::compute(library, "main.comp.glsl");
    ASSERT_TRUE(program.ok()) << program.error().message;
    EXPECT_EQ(runOnce(*program), 2.0f);
}

TEST_F(GlLayer, ALibraryDumpsEachProgramItCompiledByItsSources) {
    test::TempDir dir;
    gl::ShaderLibrary library = testLibrary();
    library.dumpTo(dir.path());
    ASSERT_TRUE(gl::Program::compute(library, "variant.comp.glsl", {"VALUE 3.0"}).ok());
    ASSERT_TRUE(gl::Program::compute(library, "variant.comp.glsl", {"VALUE 3.0"}).ok());
    ASSERT_TRUE(gl::Program::compute(library, "variant.comp.glsl", {"VALUE 4.0"}).ok());
    ASSERT_FALSE(gl::Program::compute(library, "broken.comp.glsl").ok());
    acceptErrors(); // the driver also reports the failed compile through KHR_debug
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    ASSERT_EQ(names.size(), 2u) << "one file a variant; a program that did not compile, none";
    for (const std::string& name : names) {
        EXPECT_EQ(name.rfind("variant-", 0), 0u) << name;
        EXPECT_EQ(name.substr(name.size() - 5), ".comp") << name;
    }
    std::ifstream in(dir / names[0]);
    const std::string source((std::istreambuf_iterator<char>(in)), {});
    auto assembled = library.assemble("variant.comp.glsl", {"VALUE 3.0"});
    auto other = library.assemble("variant.comp.glsl", {"VALUE 4.0"});
    ASSERT_TRUE(assembled.ok() && other.ok());
    EXPECT_TRUE(source == *assembled || source == *other) << "the source as given to GL";
}

TEST_F(GlLayer, TheProgramCacheCompilesEachVariantOnce) {
    gl::ShaderLibrary library = testLibrary();
    gl::ProgramCache cache(library);
    auto three = cache.compute("variant.comp.glsl", {"VALUE 3.0"});
    ASSERT_TRUE(three.ok()) << three.error().message;
    auto scaled = cache.compute("variant.comp.glsl", {"VALUE 3.0", "SCALE 5.0"});
    ASSERT_TRUE(scaled.ok()) << scaled.error().message;
    EXPECT_NE(*three, *scaled);
    EXPECT_EQ(runOnce(**three), 6.0f);
    EXPECT_EQ(runOnce(**scaled), 15.0f);
    // The same variant, asked again with its defines in another order: nothing compiled.
    auto again = cache.compute("variant.comp.glsl", {"SCALE 5.0", "VALUE 3.0"});
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(*again, *scaled);
    EXPECT_EQ(cache.size(), 2u);
    // A variant that does not compile is an error naming the file, and is not kept.
    auto broken = cache.compute("variant.comp.glsl", {});
    ASSERT_FALSE(broken.ok());
    EXPECT_NE(broken.error().message.find("variant.comp.glsl does not compile"), std::string::npos);
    EXPECT_EQ(cache.size(), 2u);
    acceptErrors(); // the driver also reports the failed compile through KHR_debug
}

TEST_F(GlLayer, TheRegistryRefusesABindingOrANameTwice) {
    gl::Registry registry; // the engine's table first
    constexpr gl::StorageSlot kOnLights{gl::slot::kLighting.index, "MINE_BINDING", "Mine"};
    constexpr gl::Shared clash[] = {kOnLights};
    const core::Status refused = registry.add("plugin", clash);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("plugin's MINE_BINDING (storage binding 16) overlaps "
                                           "engine's LIGHTING_BINDING"),
              std::string::npos)
        << refused.error().message;
    constexpr gl::Shared renamed[] = {gl::Shared::integer("VERTICES_BINDING", 3)};
    EXPECT_FALSE(registry.add("plugin", renamed).ok());
    // A run of texture units overlapping another's.
    constexpr gl::Shared units[] = {gl::TextureSlot{4, "MINE_UNIT", 2}};
    EXPECT_FALSE(registry.add("plugin", units).ok()); // the engine's materials from 3
    EXPECT_TRUE(registry.add("test", kTestTable).ok());
    EXPECT_TRUE(registry.add("test", kTestTable).ok()); // the same table again: nothing new
    constexpr gl::Shared twice[] = {kOut, gl::StorageSlot{72, "OUT_BINDING", "Out2"}};
    static_assert(!gl::distinct(twice));
    EXPECT_FALSE(gl::Registry().add("twice", twice).ok());
}

TEST_F(GlLayer, ADispatchReadsOnlyBlocksBoundForThemThroughTheRegistry) {
    gl::ShaderLibrary library = testLibrary();
    const bool checks = gl::bindingChecks();
    gl::setBindingChecks(true);
    gl::Buffer out(sizeof(float)), other(sizeof(float));
    // Block Out where the registry has block Other: refused, though a buffer is bound there.
    auto misplaced = gl::Program::compute(library, "misplaced.comp.glsl");
    ASSERT_TRUE(misplaced.ok()) << misplaced.error().message;
    misplaced->use();
    gl::bindStorage(kOther, other);
    std::uint64_t before = gl::errorCount();
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before + 1);
    // Its block in place, then bound over by code outside the registry: refused; rebound: fine.
    auto program = gl::Program::compute(library, "main.comp.glsl");
    ASSERT_TRUE(program.ok());
    program->use();
    gl::bindStorage(kOut, out);
    before = gl::errorCount();
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOut.index, other.id());
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before + 1);
    gl::bindStorage(kOut, out);
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before + 1);
    gl::setBindingChecks(checks);
    acceptErrors(); // the two refused above, on purpose
}

TEST_F(GlLayer, BufferFillsAndCopiesWithinItself) {
    const std::uint32_t words[] = {1, 2, 3, 4, 5, 6, 7, 8};
    gl::Buffer buffer{std::span<const std::uint32_t>(words)};
    buffer.fill(4, 2, 9u);        // words 1-2
    buffer.copy(0, 5 * 4, 3 * 4); // words 0-2 over 5-7
    std::uint32_t got[8];
    std::memcpy(got, buffer.download().data(), sizeof got);
    const std::uint32_t expected[] = {1, 9, 9, 4, 5, 1, 9, 9};
    EXPECT_TRUE(std::equal(std::begin(got), std::end(got), std::begin(expected)));
}

TEST_F(GlLayer, FramebufferBlitConvertsColourFormats) {
    gl::Texture half({{8, 4}, gl::Format::RGBA16F, 1}), single({{8, 4}, gl::Format::RGBA32F, 1});
    gl::Framebuffer from, to;
    ASSERT_TRUE(from.bindTargets("half", {&half}, nullptr).ok());
    gl::clearColor(0, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
    ASSERT_TRUE(to.attach("single", {&single}, nullptr).ok());
    to.blitColorFrom(from, {8, 4});
    const std::vector<float> texels = single.downloadFloat();
    ASSERT_EQ(texels.size(), 8u * 4u * 4u);
    for (std::size_t i = 0; i < texels.size(); i += 4)
        ASSERT_EQ(glm::vec4(texels[i], texels[i + 1], texels[i + 2], texels[i + 3]),
                  glm::vec4(0.25f, 0.5f, 0.75f, 1.0f))
            << "texel " << i / 4;
}

TEST_F(GlLayer, ShaderErrorsNameTheFile) {
    gl::ShaderLibrary library;
    library.add(kFiles);
    auto cycle = library.assemble("loop1.glsl", {});
    ASSERT_FALSE(cycle.ok());
    EXPECT_NE(cycle.error().message.find("include cycle"), std::string::npos);
    auto missing = library.assemble("nope.glsl", {});
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("no shader file 'nope.glsl'"), std::string::npos);
    auto broken = gl::Program::compute(library, "broken.comp.glsl");
    ASSERT_FALSE(broken.ok());
    EXPECT_NE(broken.error().message.find("broken.comp.glsl does not compile"), std::string::npos);
    acceptErrors(); // the driver also reports the failed compile through KHR_debug
}

TEST_F(GlLayer, ADispatchRightAfterAMipmapGenerationIsAnError) {
    // llvmpipe's rasteriser makes the levels later and its compute does not wait for them (the
    // timing-dependent frame, docs/hardening.md): a finish or barrier must come between.
    gl::ShaderLibrary library = testLibrary();
    auto program = gl::Program::compute(library, "main.comp.glsl");
    ASSERT_TRUE(program.ok()) << program.error().message;
    gl::Texture texture({{64, 64}, gl::Format::RGBA8, 0});
    gl::Buffer out(sizeof(float));
    program->use();
    gl::bindStorage(kOut, out);
    texture.generateMipmaps();
    gl::finish();
    const std::uint64_t before = gl::errorCount();
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before) << "a finish between: no error";
    texture.generateMipmaps();
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before + 1) << "no finish between";
    gl::dispatch(1);
    EXPECT_EQ(gl::errorCount(), before + 1) << "reported once";
    gl::memoryBarrier(gl::BarrierAll);
    acceptErrors(); // the one above, on purpose
}

TEST_F(GlLayer, IncompleteFramebufferIsAnError) {
    gl::Texture color({{16, 16}, gl::Format::RGBA8, 1});
    gl::Texture depth({{8, 8}, gl::Format::Depth32F, 1});
    gl::Framebuffer fbo;
    EXPECT_TRUE(fbo.attach("complete", {&color}, nullptr).ok());
    // Attaching a depth texture as a colour attachment makes the FBO incomplete.
    const auto status = fbo.attach("depth-as-colour", {&depth}, nullptr);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("'depth-as-colour' is incomplete"), std::string::npos);
}

TEST_F(GlLayer, DebugOutputCountsErrors) {
    gl::ShaderLibrary library = testLibrary();
    auto program = gl::Program::compute(library, "main.comp.glsl");
    ASSERT_TRUE(program.ok());
    program->use();
    gl::Buffer out(sizeof(float));
    gl::bindStorage(kOut, out);
    const auto before = gl::errorCount();
    gl::dispatch(100000000); // over GL_MAX_COMPUTE_WORK_GROUP_COUNT: GL_INVALID_VALUE
    gl::checkErrors("deliberate error");
    EXPECT_GT(gl::errorCount(), before)
        << "a GL error must be noticed, or no test could fail on one";
    acceptErrors();
}

TEST_F(GlLayer, TextureRoundTrip) {
    gl::Texture t({{4, 2}, gl::Format::RGBA8, 1});
    std::vector<std::uint8_t> pixels(std::size_t(4 * 2 * 4));
    for (std::size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = std::uint8_t(i * 7);
    t.upload(0, pixels.data());
    EXPECT_EQ(t.downloadRgba8(), pixels);
}

} // namespace
