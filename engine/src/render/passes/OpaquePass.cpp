// `opaque`: the primitives no plugin claims, metallic-roughness with image-based lighting.
#include "Passes.h"

#include "engine/gl/Commands.h"

#include <glm/gtc/matrix_inverse.hpp>

namespace render::passes {
namespace {

gl::Cull cullFor(const scene::Model& model, int material) {
    return material >= 0 && model.materials[std::size_t(material)].doubleSided ? gl::Cull::None
                                                                               : gl::Cull::Back;
}

} // namespace

SceneTargets addOpaque(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, fg::BufferHandle vertices) {
    return graph.addPass<SceneTargets>(
        "opaque",
        [&](fg::Builder& b, SceneTargets& d) {
            b.read(vertices);
            d.color = b.write(scene.color);
            d.depth = b.write(scene.depth);
        },
        [&gpu, &frame](const fg::Resources& r, const SceneTargets& d,
                       gl::Context&) -> core::Status {
            if (auto bound = gpu.framebuffer.bindTargets("opaque", {&r.texture(d.color)},
                                                         &r.texture(d.depth));
                !bound)
                return bound;
            const scene::Model& model = *frame.model;
            gl::Program& p = gpu.opaque;
            p.use();
            gpu.environment->bind(p, 0, frame.settings.environmentRotation,
                                  frame.settings.environmentIntensity);
            p.set("uViewProjection", frame.camera.viewProjection());
            p.set("uCameraPosition", frame.camera.position);
            std::size_t vao = 0;
            for (const auto& instance : gpu.deformer->instances()) {
                p.set("uModel", instance.meshToWorld);
                p.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(instance.meshToWorld)));
                for (const auto& primitive : instance.primitives) {
                    if (gpu.claimed[vao]) {
                        ++vao;
                        continue;
                    }
                    const int material = primitive.source->material;
                    gl::apply({.cull = cullFor(model, material)});
                    gpu.materials->bind(p, model, material, 2);
                    gl::bindStorage(0, primitive.deformed);
                    gl::bindStorage(1, *primitive.uv0);
                    gpu.vaos[vao++].bind();
                    gl::drawIndexed(primitive.indexCount);
                }
            }
            return {};
        });
}

} // namespace render::passes
