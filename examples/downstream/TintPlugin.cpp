// A minimal plugin: multiplies the HDR scene colour by a tint in a pass of its own, which shows
// the whole plugin interface (module entry points, parameters, stages, blackboard, shaders).
// This project builds it against the installed package; the engine's own tests build it too,
// once more with TINT_WRONG_INTERFACE, as a module that claims another interface version.
#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Program.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/FrameInfo.h"

#include <memory>

namespace {

const gl::ShaderFile kShaders[] = {{"tint/tint.frag.glsl", R"(
in vec2 vUv;
out vec4 outColor;
layout(binding = SOURCE_UNIT) uniform sampler2D uScene; // the engine's registry (gl/Registry.h)
uniform vec3 uTint;
void main() { outColor = vec4(texelFetch(uScene, ivec2(gl_FragCoord.xy), 0).rgb * uTint, 1.0); }
)"}};

class TintPlugin final : public plugin::Plugin {
public:
    TintPlugin() {
        mParameters.declare(
            {"red", "Red", plugin::Parameter::Type::Float, 0.0, 4.0, 1.0, {}, "red multiplier"});
        mParameters.declare({"enabled", "Enabled", plugin::Parameter::Type::Bool, 0, 1, 1, {}, ""});
        mParameters.declare({"stage",
                             "Stage",
                             plugin::Parameter::Type::Enum,
                             0,
                             1,
                             1,
                             {"after-opaque", "before-tonemap"},
                             ""});
    }
    const char* name() const override { return "tint"; }
    core::Status initialize(gl::ShaderLibrary& shaders) override {
        shaders.add(kShaders);
        auto program =
            gl::Program::graphics(shaders, "render/fullscreen.vert.glsl", "tint/tint.frag.glsl");
        if (!program)
            return program.error();
        mProgram = std::move(*program);
        mFramebuffer = std::make_unique<gl::Framebuffer>();
        mVao = std::make_unique<gl::VertexArray>();
        return {};
    }
    void addPasses(plugin::Stage stage, fg::FrameGraph& graph,
                   fg::Blackboard& blackboard) override {
        if (!mParameters.flag("enabled") || int(stage) != int(mParameters.number("stage")))
            return;
        struct Data {
            fg::TextureHandle in, out;
        };
        const auto* frame = blackboard.get<const render::FrameInfo*>(plugin::kFrame);
        const fg::TextureHandle scene = blackboard.get<fg::TextureHandle>(plugin::kSceneColor);
        const float red = float(mParameters.number("red"));
        const auto& data = graph.addPass<Data>(
            "tint",
            [&](fg::Builder& b, Data& d) {
                d.in = b.read(scene);
                d.out =
                    b.write(b.create("tint.color", {frame->settings.size, gl::Format::RGBA16F, 1}));
            },
            [this, red](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
                if (auto bound = mFramebuffer->bindTargets("tint", {&r.texture(d.out)}, nullptr);
                    !bound)
                    return bound; // ends the frame with this error, naming the pass
                gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
                mProgram.use();
                gl::bindTexture(gl::slot::kSource, r.texture(d.in));
                mProgram.set("uTint", glm::vec3(red, 1.0f, 1.0f));
                mVao->bind();
                gl::drawArrays(3);
                return {};
            });
        blackboard.put(plugin::kSceneColor, data.out);
    }
    plugin::ParameterSet& parameters() override { return mParameters; }

private:
    plugin::ParameterSet mParameters;
    gl::Program mProgram;
    std::unique_ptr<gl::Framebuffer> mFramebuffer; // GL objects: made in initialize()
    std::unique_ptr<gl::VertexArray> mVao;
};

} // namespace

#ifdef TINT_WRONG_INTERFACE
extern "C" __attribute__((visibility("default"))) const char* glass_plugin_interface() {
    return "glass.plugin/0";
}
extern "C" __attribute__((visibility("default"))) plugin::Plugin* glass_plugin_create() {
    return new TintPlugin();
}
extern "C" __attribute__((visibility("default"))) void glass_plugin_destroy(plugin::Plugin* p) {
    delete p;
}
#else
GLASS_PLUGIN_ENTRY(TintPlugin)
#endif
