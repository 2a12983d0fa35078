// `refraction.caustic_photons` (after the glass shadow pass has marked the emitters): the light the
// glass refracts, followed from each light's views through the glass BVH onto the receivers as
// photons (caustic_photons.comp.glsl), summed for the resolve (CausticResolvePass.cpp;
// docs/materials.md, "Caustics").
#include "Passes.h"

#include "engine/gl/Commands.h"

#include <string>

namespace refraction {

namespace {

/** Byte offsets in the emitters' buffer (caustics.glsl's CausticEmitters: the emitter count, the
 *  list pass's work groups, the photon count, the photon pass's work groups) of the two
 *  indirect dispatches' groups. */
constexpr std::size_t kListGroups = 4, kPhotonGroups = 20;

/** The photons' receivers besides the BVH's opaque parts: the ground square. */
void setGroundUniforms(const gl::Program& program, const FrameContext& c) {
    const render::GroundPlane& ground = c.frame->ground;
    program.set("uGround", c.frame->settings.ground ? 1 : 0);
    program.set("uGroundPlane",
                glm::vec4(ground.height, ground.center.x, ground.center.z, ground.halfSize));
}

/** Lists the frame's photons (an invocation a cell of the grid) and traces them (an invocation
 *  a listed photon), adding their light into the caustics' sums. */
core::Status tracePhotons(const fg::Resources& r, const FrameContext& c, fg::TextureHandle depth,
                          const GpuState::Glass& glass, const gl::Buffer& materials,
                          gl::Buffer& emitters, gl::Buffer& sums) {
    if (!glass.bvh)
        return core::Error{"refraction: the caustics have no glass BVH"};
    // The list pass's work groups, the list of photons, the photons.
    const std::string shader = "refraction/passes/caustic_photons.comp.glsl";
    auto grid = c.compute(shader, {"CAUSTIC_GRID 1"});
    auto listed = c.compute(shader, {"CAUSTIC_LIST 1"});
    auto photons = c.compute(shader, c.glassModel);
    for (const auto* built : {&grid, &listed, &photons})
        if (!*built)
            return built->error();
    const render::ShadowPlan& plan = *c.frame->shadows;
    gl::bindStorage(slot::kCausticEmitters, emitters);
    gl::bindStorage(slot::kCausticSums, sums);
    // The grid for this frame's emitters, then the photons that start on them, listed (an
    // invocation a cell of the grid; caustic_photons.comp.glsl).
    (*grid)->use();
    setCausticUniforms(**grid, c);
    gl::dispatch(1);
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierCommand);
    (*listed)->use();
    setCausticUniforms(**listed, c);
    gl::dispatchIndirect(emitters, kListGroups);
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierCommand);
    const gl::Program& program = **photons;
    program.use();
    setCausticUniforms(program, c);
    setGroundUniforms(program, c);
    program.set("uFresnelMode", int(c.settings.fresnel));
    program.set("uViewCount", int(plan.views.size()));
    for (std::size_t v = 0; v < plan.views.size(); ++v) {
        const render::ShadowView& view = plan.views[v];
        program.set(gl::Program::element("uViewLight", v).c_str(), int(view.light));
        program.set(gl::Program::element("uInverseViewProjection", v).c_str(),
                    glm::inverse(view.viewProjection()));
        // The view looks down its -z.
        program.set(gl::Program::element("uViewAxis", v).c_str(),
                    -glm::vec3(glm::transpose(view.view)[2]));
    }
    glass.bvh->bindForTraversal();
    gl::bindStorage(slot::kGlassMaterials, materials);
    gl::bindTexture(slot::kCausticDepth, r.texture(depth));
    bindTracedTextures(*c.gpu);
    gl::dispatchIndirect(emitters, kPhotonGroups); // a listed photon an invocation
    // the sums for the resolve; and for the next frame's clear (BarrierBufferUpdate)
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate);
    return {};
}

} // namespace

void addCausticPhotonsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           fg::TextureHandle depth) {
    struct Photons {
        fg::BufferHandle bvh, materials, emitters, sums;
    };
    const Photons& photons = graph.addPass<Photons>(
        "refraction.caustic_photons",
        [&](fg::Builder& b, Photons& d) {
            d.bvh = b.read(buffers.bvh);
            d.materials = b.read(buffers.materials);
            b.read(depth);
            d.emitters = b.write(buffers.causticEmitters);
            d.sums = b.write(buffers.causticSums);
        },
        [c, depth](const fg::Resources& r, const Photons& d, gl::Context&) {
            return tracePhotons(r, c, depth, glassBvh(r, d.bvh), r.buffer(d.materials),
                                r.buffer(d.emitters), r.buffer(d.sums));
        });
    buffers.causticEmitters = photons.emitters;
    buffers.causticSums = photons.sums;
}

} // namespace refraction
