// `refraction.shade_layers`: the walk. Over the glass pixels (the capture's mask), each pixel's
// refracted path walked through its layers, SIR, ISR or DIR finding each exit (compiled in:
// layers_shade.frag.glsl), and shaded over the copied scene colour; with outlines on, each
// pixel's nearest layer for the outline pass.
#include "Passes.h"

#include <vector>

namespace refraction {
namespace {

/** The layer depth maps as uLayerDepths0/1 (layers.glsl); an absent second map: the first
 *  stands in. */
void bindLayerDepthMaps(const gl::Program& program, const fg::Resources& r,
                        fg::TextureHandle depths0, fg::TextureHandle depths1) {
    for (int map = 0; map < 2; ++map) {
        const fg::TextureHandle depths = map == 1 && depths1.valid() ? depths1 : depths0;
        gl::bindTexture(std::uint32_t(kLayerDepthUnit + map), r.texture(depths));
        program.set(map == 0 ? "uLayerDepths0" : "uLayerDepths1", kLayerDepthUnit + map);
    }
}

} // namespace

LayerShade addLayerShadePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                             const SceneInputs& scene, fg::TextureHandle mask,
                             const LayerDepths& depths) {
    const glm::ivec2 size = c.frame->settings.size;
    struct ShadeData {
        fg::TextureHandle sceneColor, sceneDepth, mask, depths0, depths1, out, surface;
        fg::BufferHandle layers, rectangle;
    };
    const bool outlines = c.settings.outlineAntialiasing;
    const auto& shaded = graph.addPass<ShadeData>(
        "refraction.shade_layers",
        [&](fg::Builder& b, ShadeData& d) {
            d.layers = b.read(buffers.layers);
            b.read(buffers.materials);
            d.mask = b.read(mask);
            d.depths0 = b.read(depths.depths0);
            if (depths.depths1.valid())
                d.depths1 = b.read(depths.depths1);
            d.rectangle = b.write(buffers.rectangle); // counts the overflowing pixels
            d.sceneColor = b.read(scene.color);
            d.sceneDepth = b.read(scene.depth);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
            if (outlines) // the nearest layer per pixel, for the outline pass
                d.surface =
                    b.write(b.create("refraction.layers.surface", {size, gl::Format::R32UI, 1}));
        },
        [c, outlines](const fg::Resources& r, const ShadeData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            gl::copyTexture(r.texture(d.sceneColor), r.texture(d.out));
            std::vector<const gl::Texture*> targets{&r.texture(d.out)};
            if (outlines)
                targets.push_back(&r.texture(d.surface));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.shade_layers", targets,
                                                         &r.texture(d.mask));
                !bound)
                return bound;
            if (outlines)
                gl::clearColorUint(1, 0u); // no glass
            const gl::Program& program = *c.layerShade;
            c.setWalkUniforms(program);
            program.set("uMarchSteps", c.settings.marchSteps);
            program.set("uInterfaces", c.settings.interfaces);
            c.setLayerUniforms(program);
            gl::bindTexture(kSceneColorUnit, r.texture(d.sceneColor));
            gl::bindTexture(kSceneDepthUnit, r.texture(d.sceneDepth));
            program.set("uSceneColor", kSceneColorUnit);
            program.set("uSceneDepth", kSceneDepthUnit);
            bindLayerDepthMaps(program, r, d.depths0, d.depths1);
            c.drawMaskedRectangle();
            return {};
        });
    buffers.rectangle = shaded.rectangle;
    return {shaded.out, shaded.surface};
}

} // namespace refraction
