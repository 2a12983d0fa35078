// The opaque characters: the primitives no plugin claims, glTF's material model
// (render/opaque.frag.glsl) lit by the environment and the punctual lights. Where the frame has
// punctual lights, shaded once per pixel: `opaque` draws the primitives whose materials put no
// layer on the base into the surface targets (their materials; their emitted light into the
// colour: common/surface_targets.glsl), `lighting` shades each pixel they cover, and
// `opaque_layers` draws the others (clear coat, sheen, iridescence, anisotropy), shaded where
// they are drawn. A CPU rasteriser shades every fragment of a small triangle's quads, and the
// hidden ones; with the lights and their shadow lookups that costs more than the targets' round
// trip, with the environment alone less (docs/performance.md): then `opaque` draws and shades
// them all. Where the frame accumulates, the draws write their motion from the previous frame's
// deformation and placement.
#include "Passes.h"

#include "engine/gl/Commands.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace render::passes {
namespace {

/** What `opaque` writes where it draws into the surface targets. */
struct GeometryTargets : SceneTargets {
    SurfaceTargets surfaces;
};

gl::Cull cullFor(const scene::Material* material) {
    return material && material->doubleSided ? gl::Cull::None : gl::Cull::Back;
}

/** The layers `item`'s material puts on the base (Material::surfaceLayers()). */
int layersOf(const DrawItem& item) {
    return item.values ? item.values->surfaceLayers() : 0;
}

/** Drawn into the surface targets: unclaimed, without layers. */
bool deferred(const DrawItem& item) {
    return !item.owner && layersOf(item) == 0;
}

/** Drawn and shaded by `opaque_layers` after the lighting: unclaimed, with layers. */
bool layered(const DrawItem& item) {
    return !item.owner && layersOf(item) != 0;
}

bool unclaimed(const DrawItem& item) {
    return !item.owner;
}

/** Draws `item` with `p` (mesh.vert.glsl with an opaque.frag.glsl variant). */
void drawItem(const gl::Program& p, const DrawItem& item, std::size_t index) {
    p.use();
    p.set("uModel", item.world);
    p.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(item.world)));
    p.set("uPreviousModel", item.previousWorld);
    p.set("uMotionObject", int(index + 1));
    gl::apply({.cull = cullFor(item.values), .clockwise = item.mirrored});
    item.materials->bind(p, item.values);
    gl::bindStorage(gl::slot::kVertices, *item.gpu->deformed);
    gl::bindStorage(gl::slot::kPreviousVertices,
                    item.gpu->previous ? *item.gpu->previous : *item.gpu->deformed);
    gl::bindStorage(gl::slot::kUvs, *item.gpu->uvs);
    item.vertexArray->bind();
    gl::drawIndexed(item.gpu->indexCount);
}

void setViewUniforms(const gl::Program& p, const FrameInfo& frame) {
    p.set("uViewProjection", frame.camera.viewProjection());
    p.set("uCameraPosition", frame.camera.position);
    setMotionUniforms(p, frame);
}

/** `opaque`: creates the surface targets and draws the items without layers into them. */
GeometryTargets addGeometry(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                            SceneTargets scene, fg::BufferHandle vertices) {
    const glm::ivec2 size = frame.settings.size;
    return graph.addPass<GeometryTargets>(
        "opaque",
        [&](fg::Builder& b, GeometryTargets& d) {
            b.read(vertices);
            d.color = b.write(scene.color);
            d.depth = b.write(scene.depth);
            if (scene.motion.valid())
                d.motion = b.write(scene.motion);
            const auto target = [&](const char* name, gl::Format format) {
                return b.write(b.create(name, {size, format, 1}));
            };
            d.surfaces = {target("surface.position", gl::Format::RGBA32F),
                          target("surface.normal", gl::Format::RGBA32F),
                          target("surface.base", gl::Format::RGBA16F),
                          target("surface.specular", gl::Format::RGBA16F)};
        },
        [&gpu, &frame](const fg::Resources& r, const GeometryTargets& d,
                       gl::Context&) -> core::Status {
            std::vector<const gl::Texture*> targets{&r.texture(d.color)};
            for (const fg::TextureHandle surface : d.surfaces.all())
                targets.push_back(&r.texture(surface));
            if (d.motion.valid())
                targets.push_back(&r.texture(d.motion));
            if (auto bound = gpu.framebuffer.bindTargets("opaque", targets, &r.texture(d.depth));
                !bound)
                return bound;
            auto program =
                frame.programs->graphics("render/mesh.vert.glsl", "render/opaque.frag.glsl",
                                         {motionDefine(frame), "SURFACE_LAYERS 0", "DEFERRED 1"});
            if (!program)
                return program.error();
            setViewUniforms(**program, frame);
            for (std::size_t index = 0; index < frame.items.size(); ++index)
                if (deferred(frame.items[index]))
                    drawItem(**program, frame.items[index], index);
            return {};
        });
}

/** Pass `name`: the items `drawn` picks, each shaded as drawn by the variant of its material's
 *  layers (RenderGpu::layerSets). */
SceneTargets addForward(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                        SceneTargets scene, fg::BufferHandle vertices,
                        const fg::Blackboard& blackboard, const char* name,
                        bool (*drawn)(const DrawItem&)) {
    return graph.addPass<LitTargets>(
        name,
        [&](fg::Builder& b, LitTargets& d) {
            d.shadows = ShadowAtlases::readFinal(b, blackboard);
            b.read(vertices);
            d.color = b.write(scene.color);
            d.depth = b.write(scene.depth);
            if (scene.motion.valid())
                d.motion = b.write(scene.motion);
        },
        [&gpu, &frame, name, drawn](const fg::Resources& r, const LitTargets& d,
                                    gl::Context&) -> core::Status {
            if (auto bound =
                    gpu.framebuffer.bindTargets(name, sceneTargets(r, d), &r.texture(d.depth));
                !bound)
                return bound;
            d.shadows.bind(r, gpu.shadowSampler);
            std::map<int, const gl::Program*> programs;
            for (std::size_t index = 0; index < frame.items.size(); ++index) {
                if (!drawn(frame.items[index]))
                    continue;
                const int layers = layersOf(frame.items[index]);
                const gl::Program*& program = programs[layers];
                if (!program) {
                    std::vector<std::string> defines = litDefines(frame);
                    defines.push_back("SURFACE_LAYERS " + std::to_string(layers));
                    auto variant = frame.programs->graphics("render/mesh.vert.glsl",
                                                            "render/opaque.frag.glsl", defines);
                    if (!variant)
                        return variant.error();
                    program = *variant;
                    gpu.environment->bind(*program, frame.settings.environmentRotation,
                                          frame.settings.environmentIntensity);
                    setViewUniforms(*program, frame);
                }
                drawItem(*program, frame.items[index], index);
            }
            return {};
        });
}

} // namespace

SceneTargets addOpaque(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, fg::BufferHandle vertices,
                       const fg::Blackboard& blackboard) {
    const auto any = [&](bool (*test)(const DrawItem&)) {
        return std::any_of(frame.items.begin(), frame.items.end(), test);
    };
    if (frame.lights.empty() || !any(deferred))
        return addForward(graph, gpu, frame, scene, vertices, blackboard, "opaque", unclaimed);
    const GeometryTargets geometry = addGeometry(graph, gpu, frame, scene, vertices);
    scene = geometry;
    scene.color = addLighting(graph, gpu, frame, geometry, geometry.surfaces, blackboard);
    if (any(layered))
        scene =
            addForward(graph, gpu, frame, scene, vertices, blackboard, "opaque_layers", layered);
    return scene;
}

} // namespace render::passes
