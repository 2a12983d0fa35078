// `opaque`: the primitives no plugin claims, glTF's material model (render/opaque.frag.glsl, one
// program per set of material layers) lit by the environment and the punctual lights; where the
// frame accumulates, their motion from the previous frame's deformation and placement.
#include "Passes.h"

#include "engine/gl/Commands.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <map>
#include <string>
#include <vector>

namespace render::passes {
namespace {

gl::Cull cullFor(const scene::Material* material) {
    return material && material->doubleSided ? gl::Cull::None : gl::Cull::Back;
}

/** The variant for each set of material layers the prepared models use (RenderGpu::layerSets,
 *  Material::surfaceLayers()), for the frame's lights and motion. */
core::Result<std::map<int, const gl::Program*>> opaquePrograms(const RenderGpu& gpu,
                                                               const FrameInfo& frame) {
    std::map<int, const gl::Program*> programs;
    for (const int layers : gpu.layerSets) {
        std::vector<std::string> defines = litDefines(frame);
        defines.push_back("SURFACE_LAYERS " + std::to_string(layers));
        auto program =
            frame.programs->graphics("render/mesh.vert.glsl", "render/opaque.frag.glsl", defines);
        if (!program)
            return program.error();
        programs.emplace(layers, *program);
    }
    return programs;
}

} // namespace

SceneTargets addOpaque(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, fg::BufferHandle vertices,
                       const fg::Blackboard& blackboard) {
    return graph.addPass<LitTargets>(
        "opaque",
        [&](fg::Builder& b, LitTargets& d) {
            d.shadows = ShadowAtlases::readFinal(b, blackboard);
            b.read(vertices);
            d.color = b.write(scene.color);
            d.depth = b.write(scene.depth);
            if (scene.motion.valid())
                d.motion = b.write(scene.motion);
        },
        [&gpu, &frame](const fg::Resources& r, const LitTargets& d, gl::Context&) -> core::Status {
            auto programs = opaquePrograms(gpu, frame);
            if (!programs)
                return programs.error();
            if (auto bound =
                    gpu.framebuffer.bindTargets("opaque", sceneTargets(r, d), &r.texture(d.depth));
                !bound)
                return bound;
            d.shadows.bind(r, gpu.shadowSampler);
            for (auto& [layers, program] : *programs) {
                gpu.environment->bind(*program, frame.settings.environmentRotation,
                                      frame.settings.environmentIntensity);
                program->set("uViewProjection", frame.camera.viewProjection());
                program->set("uCameraPosition", frame.camera.position);
                setMotionUniforms(*program, frame);
            }
            for (std::size_t index = 0; index < frame.items.size(); ++index) {
                const DrawItem& item = frame.items[index];
                if (item.owner)
                    continue;
                // The program of the layers its material puts on the base.
                const int layers = item.values ? item.values->surfaceLayers() : 0;
                const gl::Program& p = *programs->at(layers);
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
            return {};
        });
}

} // namespace render::passes
