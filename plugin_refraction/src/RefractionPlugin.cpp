// The refraction plugin's parameters and frame-graph passes.
#include "refraction/RefractionPlugin.h"

#include "NormalDistance.h"
#include "Optics.h"

#include "engine/deform/GpuDeformer.h"
#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/render/Environment.h"
#include "engine/render/FrameInfo.h"
#include "engine/render/MaterialTextures.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

std::span<const gl::ShaderFile> refractionShaderFiles();

namespace refraction {

using Type = plugin::Parameter::Type;

struct RefractionPlugin::Gpu {
    gl::Program surface, front, composite, depthRange, refit, normalDistance;
    gl::Program surfaces, resolve, deferred, rectangleGrow; // the single-geometry-pass path
    gl::Framebuffer framebuffer;
    gl::VertexArray emptyVao;
    gl::Buffer range{4 * sizeof(std::uint32_t)};
    gl::Buffer rectangle{4 * sizeof(std::int32_t)}; // the glass's pixel rectangle (surfaces.glsl)
    const scene::Model* model = nullptr;
    std::uint64_t geometry = 0; // GpuDeformer::serial() the caches below belong to
    std::vector<gl::VertexArray> vaos; // per instance primitive, flattened
    /** d_N of one glass primitive: measured on the deformed cage (the file's triangles); with
     *  subdivision carried to the drawn vertices by the refinement stencils. */
    struct Distance {
        std::unique_ptr<NormalDistance> cage;
        gl::Buffer drawn; // with subdivision: one float per drawn vertex
        const gl::Buffer& values() const { return drawn ? drawn : cage->distances(); }
    };
    std::map<std::pair<std::size_t, std::size_t>, Distance> distances;
};

RefractionPlugin::RefractionPlugin() {
    auto& p = mParameters;
    p.declare({"method",
               "Method",
               Type::Enum,
               0,
               0,
               3,
               {"opaque", "sir", "isr", "dir"},
               "opaque: no glass; sir: one interface; isr: Wyman's estimate with per-frame d_N; "
               "dir: depth-map search, no preprocessing"});
    p.declare({"glass",
               "Glass",
               Type::Enum,
               0,
               0,
               0,
               {"auto", "all"},
               "auto: materials with transmission; all: every mesh"});
    p.declare(
        {"ior", "IOR", Type::Float, 0.0, 4.0, 0.0, {}, "index of refraction; 0: the material's"});
    p.declare({"dispersion",
               "Dispersion",
               Type::Float,
               -1.0,
               10.0,
               -1.0,
               {},
               "20 / Abbe number (KHR_materials_dispersion); -1: the material's"});
    p.declare({"dispersion-search",
               "Dispersion search",
               Type::Enum,
               0,
               0,
               0,
               {"shared", "per-channel"},
               "shared: one exit search, red and blue bent from green's exit point by their own "
               "indices; per-channel: red, green and blue each search their exit (three "
               "searches and lookups)"});
    p.declare(
        {"tint", "Tint", Type::Color, 0.0, 1.0, 1.0, {}, "multiplies the attenuation colour"});
    p.declare({"absorption-distance",
               "Absorption distance",
               Type::Float,
               0.0,
               1e6,
               0.0,
               {},
               "distance at which light takes the attenuation colour; 0: the material's"});
    p.declare({"fresnel", "Fresnel", Type::Enum, 0, 0, 0, {"exact", "schlick", "off"}, ""});
    p.declare({"search-steps",
               "Search steps",
               Type::Int,
               1,
               16,
               5,
               {},
               "DIR conservative binary search steps"});
    p.declare({"tir",
               "TIR",
               Type::Enum,
               0,
               0,
               0,
               {"clamp", "reflect"},
               "clamp: exit tangent (the papers); reflect: bounce inside and search again"});
    p.declare({"tir-bounces",
               "TIR bounces",
               Type::Int,
               1,
               8,
               2,
               {},
               "reflections followed with tir=reflect"});
    p.declare({"back-surface",
               "Back surface",
               Type::Enum,
               0,
               0,
               0,
               {"farthest", "first"},
               "which back face the depth map keeps (ISR paper §3.2)"});
    p.declare({"geometry-passes",
               "Geometry passes",
               Type::Enum,
               0,
               0,
               0,
               {"one", "two"},
               "one: front and back surfaces gathered in one pass (MAX blending), refracted in a "
               "full-screen pass; two: the papers' back-face pass, then a front-face pass. One "
               "needs a single glass material without a normal map and back-surface=farthest; "
               "otherwise two runs"});
    p.declare({"nearby",
               "Nearby scene",
               Type::Bool,
               0,
               1,
               1,
               {},
               "exit rays see the opaque scene on screen before the environment"});
    p.declare({"debug",
               "Debug view",
               Type::Enum,
               0,
               0,
               0,
               {"none", "back-depth", "back-normal", "dv", "dn", "exit-uv", "steps", "tir",
                "exit-point", "exit-direction"},
               ""});
}

RefractionPlugin::~RefractionPlugin() = default;

core::Status RefractionPlugin::initialize(gl::ShaderLibrary& shaders) {
    shaders.add(refractionShaderFiles());
    mGpu = std::make_unique<Gpu>();
    struct Spec {
        gl::Program* target;
        const char* vertex;
        const char* fragment;
    };
    for (const Spec& spec :
         {Spec{&mGpu->surface, "refraction/glass.vert.glsl", "refraction/surface.frag.glsl"},
          Spec{&mGpu->front, "refraction/glass.vert.glsl", "refraction/front.frag.glsl"},
          Spec{&mGpu->composite, "render/fullscreen.vert.glsl",
               "refraction/composite.frag.glsl"},
          Spec{&mGpu->surfaces, "refraction/glass.vert.glsl", "refraction/surfaces.frag.glsl"},
          Spec{&mGpu->resolve, "refraction/rectangle.vert.glsl", "refraction/resolve.frag.glsl"},
          Spec{&mGpu->deferred, "refraction/rectangle.vert.glsl",
               "refraction/deferred.frag.glsl"}}) {
        auto program = gl::Program::graphics(shaders, spec.vertex, spec.fragment);
        if (!program)
            return program.error();
        *spec.target = std::move(*program);
    }
    for (auto [target, name] :
         {std::pair{&mGpu->depthRange, "refraction/depth_range.comp.glsl"},
          std::pair{&mGpu->refit, "refraction/bvh_refit.comp.glsl"},
          std::pair{&mGpu->rectangleGrow, "refraction/rectangle.comp.glsl"},
          std::pair{&mGpu->normalDistance, "refraction/normal_distance.comp.glsl"}}) {
        auto program = gl::Program::compute(shaders, name);
        if (!program)
            return program.error();
        *target = std::move(*program);
    }
    return {};
}

void RefractionPlugin::drawPanel(void* imguiContext) {
    // Refractive index n_d and Abbe number V_d (dispersion = 20 / V_d, as in
    // KHR_materials_dispersion) of common transparent materials.
    struct Preset {
        const char* name;
        double ior, abbe;
    };
    static constexpr Preset kPresets[] = {
        {"water", 1.333, 55.7},           {"ice", 1.309, 56.0},
        {"acrylic (PMMA)", 1.491, 57.2},  {"glass (crown, BK7)", 1.517, 64.2},
        {"fused quartz", 1.458, 67.8},    {"polycarbonate", 1.585, 30.0},
        {"flint glass (F2)", 1.620, 36.4}, {"sapphire", 1.770, 72.2},
        {"cubic zirconia", 2.150, 33.8},  {"diamond", 2.417, 55.3},
    };
    ImGui::SetCurrentContext(static_cast<ImGuiContext*>(imguiContext));
    if (ImGui::BeginCombo("Material preset", "sets IOR and dispersion")) {
        if (ImGui::Selectable("the material's own")) {
            mParameters.setNumber("ior", 0.0);
            mParameters.setNumber("dispersion", -1.0);
        }
        for (const Preset& preset : kPresets) {
            char label[64];
            std::snprintf(label, sizeof label, "%s  %.3f", preset.name, preset.ior);
            if (ImGui::Selectable(label)) {
                mParameters.setNumber("ior", preset.ior);
                mParameters.setNumber("dispersion", 20.0 / preset.abbe);
            }
        }
        ImGui::EndCombo();
    }
}

bool RefractionPlugin::isGlass(const scene::Model& model, const scene::Primitive& primitive) const {
    if (mParameters.choice("method") == "opaque")
        return false;
    if (mParameters.choice("glass") == "all")
        return true;
    return primitive.material >= 0 &&
           model.materials[std::size_t(primitive.material)].isTransmissive();
}

bool RefractionPlugin::drawsPrimitive(const scene::Model& model, int,
                                      const scene::Primitive& primitive) const {
    return mGpu && isGlass(model, primitive);
}

void RefractionPlugin::prepare(const scene::Model& model, const deform::GpuDeformer& geometry) {
    if (mGpu->model == &model && mGpu->geometry == geometry.serial())
        return;
    mGpu->model = &model;
    mGpu->geometry = geometry.serial();
    mGpu->vaos.clear();
    mGpu->distances.clear();
    const auto& instances = geometry.instances();
    for (const auto& instance : instances)
        for (const auto& primitive : instance.primitives) {
            gl::VertexArray vao;
            vao.setIndexBuffer(*primitive.indices);
            mGpu->vaos.push_back(std::move(vao));
        }
}

namespace {

struct SurfaceData {
    fg::TextureHandle depth, normal, zbuffer;
};
struct FrontData {
    fg::TextureHandle backDepth, backNormal, frontDepth, frontNormal, sceneColor, sceneDepth, glass,
        zbuffer;
};
struct CompositeData {
    fg::TextureHandle scene, glass, out;
};

constexpr float kNoSurface = -3.0e38f; // surfaces.glsl: the MAX-blended targets' clear value
// The mip level the searches read the surface normals at (DIR §3.1: mip-filtered normals); the
// normal maps need no level above it.
constexpr int kNormalLod = 1;
// Texture units of the shading passes: 0-1 environment, 2-7 the maps (setShading), 8-13 the
// material's textures, then the gathered far target of the single geometry pass.
constexpr std::uint32_t kGatherFarUnit = 14;

} // namespace

void RefractionPlugin::addPasses(plugin::Stage stage, fg::FrameGraph& graph,
                                 fg::Blackboard& blackboard) {
    if (stage != plugin::Stage::AfterOpaque || !mGpu || mParameters.choice("method") == "opaque")
        return;
    const render::FrameInfo* frame = blackboard.get<const render::FrameInfo*>(plugin::kFrame);
    const scene::Model& model = *frame->model;
    prepare(model, *frame->geometry);
    bool anyGlass = false;
    for (const auto& instance : frame->geometry->instances())
        for (const auto& primitive : instance.primitives)
            anyGlass = anyGlass || isGlass(model, *primitive.source);
    if (!anyGlass)
        return;

    const std::string method = mParameters.choice("method");
    const bool reflect = mParameters.choice("tir") == "reflect" && method != "sir";
    const bool firstBack = mParameters.choice("back-surface") == "first";
    const glm::ivec2 size = frame->settings.size;
    const gl::TextureDesc depthDesc{size, gl::Format::R32F, 1},
        normalDesc{size, gl::Format::RGBA16F, kNormalLod + 1},
        zDesc{size, gl::Format::Depth32F, 1},
        colorDesc{size, gl::Format::RGBA16F, 1}, gatherDesc{size, gl::Format::RGBA32F, 1};
    Gpu& gpu = *mGpu;

    // The single geometry pass needs what one full-screen pass can shade: one glass material,
    // no normal map (no UV or tangent is gathered), the farthest back surface (MAX blending).
    const scene::Material* glassMaterial = nullptr;
    int glassMaterialIndex = -2;
    bool oneMaterial = true;
    for (const auto& instance : frame->geometry->instances())
        for (const auto& primitive : instance.primitives) {
            if (!isGlass(model, *primitive.source))
                continue;
            const int m = primitive.source->material;
            oneMaterial = oneMaterial && (glassMaterialIndex == -2 || glassMaterialIndex == m);
            glassMaterialIndex = m;
            glassMaterial = m >= 0 ? &model.materials[std::size_t(m)] : nullptr;
        }
    const bool onePass = mParameters.choice("geometry-passes") == "one" && oneMaterial &&
                         !firstBack && !(glassMaterial && glassMaterial->normalTexture.present());

    // Material and optics uniforms of the glass shading (glass_shading.glsl).
    auto setMaterial = [this, frame, &model](const gl::Program& program, int material) {
        const scene::Material* m = material >= 0 ? &model.materials[std::size_t(material)] : nullptr;
        frame->materials->bind(program, model, material, 8);
        const Optics o = opticsFor(mParameters, m);
        program.set("uIor", o.ior);
        program.set("uDispersion", o.dispersion ? 1 : 0);
        program.set("uSigma", o.sigma);
        program.set("uTransmission", o.transmission);
        program.set("uBaseColor", o.baseColor);
        program.set("uRoughness", o.roughness);
        program.set("uMetallic", o.metallic);
        program.set("uEmissive", m ? m->emissiveFactor * m->emissiveStrength : glm::vec3(0.0f));
    };

    // Draws every glass primitive with `program` (glass.vert.glsl), setting per-primitive state.
    auto drawGlass = [this, frame, &model, setMaterial](const gl::Program& program,
                                                        const gl::PipelineState& state,
                                                        bool front) {
        Gpu& g = *mGpu;
        program.use();
        program.set("uProjection", frame->camera.projection);
        std::size_t vao = 0, instanceIndex = 0;
        for (const auto& instance : frame->geometry->instances()) {
            const glm::mat4 modelView = frame->camera.view * instance.meshToWorld;
            program.set("uModelView", modelView);
            program.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(modelView)));
            for (std::size_t p = 0; p < instance.primitives.size(); ++p, ++vao) {
                const auto& primitive = instance.primitives[p];
                if (!isGlass(model, *primitive.source))
                    continue;
                gl::bindStorage(0, primitive.deformed);
                gl::bindStorage(1, *primitive.uv0);
                const auto distance = g.distances.find({instanceIndex, p});
                const bool hasDistance =
                    distance != g.distances.end() && mParameters.choice("method") == "isr";
                program.set("uHasNormalDistance", hasDistance ? 1 : 0);
                if (hasDistance)
                    gl::bindStorage(2, distance->second.values());
                else
                    gl::bindStorage(2, primitive.deformed); // unread; keeps the binding valid
                if (front)
                    setMaterial(program, primitive.source->material);
                gl::apply(state);
                g.vaos[vao].bind();
                gl::drawIndexed(primitive.indexCount);
            }
            ++instanceIndex;
        }
    };

    // d_N per deformed vertex, every frame (ISR only).
    if (method == "isr") {
        struct Empty {};
        graph.addPass<Empty>(
            "refraction.normal_distance", [](fg::Builder& b, Empty&) { b.after("deform"); },
            [this, frame, &model](const fg::Resources&, const Empty&, gl::Context&) {
                Gpu& g = *mGpu;
                std::size_t instanceIndex = 0;
                for (const auto& instance : frame->geometry->instances()) {
                    for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
                        const auto& primitive = instance.primitives[p];
                        if (!isGlass(model, *primitive.source))
                            continue;
                        auto& distance = g.distances[{instanceIndex, p}];
                        const bool refined = frame->geometry->subdivisionLevel() > 0;
                        if (!distance.cage) {
                            distance.cage = std::make_unique<NormalDistance>(*primitive.source);
                            if (refined)
                                distance.drawn =
                                    gl::Buffer(std::size_t(primitive.vertexCount) * sizeof(float));
                        }
                        const auto cage = frame->geometry->cage(instanceIndex, p);
                        distance.cage->update(cage.vertices, cage.indices, g.refit,
                                              g.normalDistance);
                        if (refined)
                            frame->geometry->refineScalar(instanceIndex, p,
                                                          distance.cage->distances(),
                                                          distance.drawn);
                    }
                    ++instanceIndex;
                }
            });
    }

    // 1. The surfaces the searches read. Two geometry passes (the papers): back faces (DIR
    //    §3.1), farthest (GREATER, cleared to 0) or first (LESS, cleared to 1), and for TIR
    //    reflection the front faces. One geometry pass: both gathered by MAX blending, then
    //    unpacked into the same maps.
    auto surfacePass = [&](const char* name, bool backFaces, bool nearest) -> const SurfaceData& {
        return graph.addPass<SurfaceData>(
            name,
            [&](fg::Builder& b, SurfaceData& d) {
                b.after("deform");
                d.depth = b.write(b.create(std::string(name) + ".depth", depthDesc));
                d.normal = b.write(b.create(std::string(name) + ".normal", normalDesc));
                d.zbuffer = b.write(b.create(std::string(name) + ".zbuffer", zDesc));
            },
            [&gpu, drawGlass, backFaces, nearest, name](const fg::Resources& r,
                                                        const SurfaceData& d, gl::Context&) {
                auto status = gpu.framebuffer.attach(
                    name, {&r.texture(d.depth), &r.texture(d.normal)}, &r.texture(d.zbuffer));
                ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
                gpu.framebuffer.bind();
                gl::clearColor(0, glm::vec4(0.0f));
                gl::clearColor(1, glm::vec4(0.0f));
                gl::clearDepth(nearest ? 1.0f : 0.0f);
                drawGlass(gpu.surface,
                          {.cull = backFaces ? gl::Cull::Front : gl::Cull::Back,
                           .depthFunc = nearest ? gl::DepthFunc::Less : gl::DepthFunc::Greater},
                          false);
                r.texture(d.normal).generateMipmaps(); // DIR §3.1: mip-filtered normals
            });
    };
    const bool twoInterfaces = method != "sir";
    SurfaceData back, front;
    // One pass: the gathered far target (back normals, d_N keys) and the shading mask.
    fg::TextureHandle gatheredFar, glassMask;
    if (onePass) {
        struct GatherData {
            fg::TextureHandle nearTargets, farTargets;
        };
        const auto& gathered = graph.addPass<GatherData>(
            "refraction.surfaces",
            [&](fg::Builder& b, GatherData& d) {
                b.after("deform");
                if (method == "isr")
                    b.after("refraction.normal_distance");
                d.nearTargets = b.write(b.create("refraction.surfaces.near", gatherDesc));
                d.farTargets = b.write(b.create("refraction.surfaces.far", gatherDesc));
            },
            [this, &gpu, drawGlass, frame, &model](const fg::Resources& r, const GatherData& d,
                                                   gl::Context&) {
                // The glass rectangle from the deformed cages (rectangle.comp.glsl).
                gpu.rectangle.fill(0, 2, std::uint32_t(INT32_MAX)); // empty: min > max
                gpu.rectangle.fill(8, 2, std::uint32_t(INT32_MIN));
                gpu.rectangleGrow.use();
                gpu.rectangleGrow.set("uViewportSize", glm::vec2(frame->settings.size));
                gl::bindStorage(4, gpu.rectangle);
                const auto& instances = frame->geometry->instances();
                for (std::size_t i = 0; i < instances.size(); ++i)
                    for (std::size_t p = 0; p < instances[i].primitives.size(); ++p) {
                        const auto& primitive = instances[i].primitives[p];
                        if (!isGlass(model, *primitive.source))
                            continue;
                        gpu.rectangleGrow.set(
                            "uModelViewProjection",
                            frame->camera.viewProjection() * instances[i].meshToWorld);
                        const int count = int(primitive.source->vertexCount());
                        gpu.rectangleGrow.set("uVertexCount", count);
                        gl::bindStorage(0, frame->geometry->cage(i, p).vertices);
                        gl::dispatch(std::uint32_t((count + 63) / 64));
                    }
                gl::memoryBarrier(gl::BarrierStorage);
                auto status = gpu.framebuffer.attach(
                    "refraction.surfaces",
                    {&r.texture(d.nearTargets), &r.texture(d.farTargets)}, nullptr);
                ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
                gpu.framebuffer.bind();
                gl::clearColor(0, glm::vec4(kNoSurface));
                gl::clearColor(1, glm::vec4(kNoSurface));
                gpu.surfaces.use();
                gpu.surfaces.set("uKeyNear", frame->camera.znear);
                gpu.surfaces.set("uKeyLogRange",
                                 std::log2(frame->camera.zfar / frame->camera.znear));
                drawGlass(gpu.surfaces,
                          {.cull = gl::Cull::None,
                           .depthTest = false,
                           .depthWrite = false,
                           .blend = gl::Blend::Max},
                          false);
            });
        struct ResolveData {
            fg::TextureHandle farTargets, sceneDepth, backNormal, frontDepth, frontNormal, mask;
        };
        const fg::TextureHandle sceneDepthIn =
            blackboard.get<fg::TextureHandle>(plugin::kSceneDepth);
        const auto& resolved = graph.addPass<ResolveData>(
            "refraction.resolve",
            [&](fg::Builder& b, ResolveData& d) {
                b.read(gathered.nearTargets);
                d.farTargets = b.read(gathered.farTargets);
                d.sceneDepth = b.read(sceneDepthIn);
                d.backNormal = b.write(b.create("refraction.back.normal", normalDesc));
                if (reflect) {
                    d.frontDepth = b.write(b.create("refraction.front.depth", depthDesc));
                    d.frontNormal = b.write(b.create("refraction.front.normal", normalDesc));
                }
                d.mask = b.write(b.create("refraction.glass_mask", zDesc));
            },
            [&gpu, frame, size, reflect, near = gathered.nearTargets](
                const fg::Resources& r, const ResolveData& d, gl::Context&) {
                std::vector<const gl::Texture*> targets{&r.texture(d.backNormal)};
                if (reflect)
                    targets.insert(targets.end(),
                                   {&r.texture(d.frontDepth), &r.texture(d.frontNormal)});
                auto status =
                    gpu.framebuffer.attach("refraction.resolve", targets, &r.texture(d.mask));
                ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
                gpu.framebuffer.bind();
                // Outside the glass rectangle: no surface, and the mask rejects.
                for (int i = 0; i < int(targets.size()); ++i)
                    gl::clearColor(i, glm::vec4(0.0f));
                gl::clearDepth(1.0f);
                gl::apply({.cull = gl::Cull::None, .depthFunc = gl::DepthFunc::Always});
                gpu.resolve.use();
                const std::pair<const char*, fg::TextureHandle> inputs[] = {
                    {"uGatherNear", near}, {"uGatherFar", d.farTargets},
                    {"uSceneDepth", d.sceneDepth}};
                int unit = 0;
                for (const auto& [uniform, handle] : inputs) {
                    gl::bindTexture(std::uint32_t(unit), r.texture(handle));
                    gpu.resolve.set(uniform, unit++);
                }
                gpu.resolve.set("uNear", frame->camera.znear);
                gpu.resolve.set("uFar", frame->camera.zfar);
                gpu.resolve.set("uViewportSize", glm::vec2(size));
                gl::bindStorage(4, gpu.rectangle);
                gpu.emptyVao.bind();
                gl::drawArrays(6);
                r.texture(d.backNormal).generateMipmaps(); // DIR §3.1: mip-filtered normals
                if (reflect) // only TIR bounces toward the front read its normals' mips
                    r.texture(d.frontNormal).generateMipmaps();
            });
        back = {gathered.nearTargets, resolved.backNormal, {}};
        if (reflect)
            front = {resolved.frontDepth, resolved.frontNormal, {}};
        gatheredFar = gathered.farTargets;
        glassMask = resolved.mask;
    } else {
        if (twoInterfaces)
            back = surfacePass("refraction.back_faces", true, firstBack);
        if (reflect)
            front = surfacePass("refraction.front_depth", false, true);
    }

    // 2. Depth range of the valid back (and front) texels: a compute reduction.
    struct RangeData {
        fg::TextureHandle back, front;
    };
    if (twoInterfaces)
        graph.addPass<RangeData>(
            "refraction.depth_range",
            [&](fg::Builder& b, RangeData& d) {
                d.back = b.read(back.depth);
                if (reflect)
                    d.front = b.read(front.depth);
            },
            [&gpu, size, onePass](const fg::Resources& r, const RangeData& d, gl::Context&) {
                for (std::size_t slot = 0; slot < 2; ++slot) { // min: FLT_MAX bits, max: 0
                    gpu.range.fill(8 * slot, 1, 0x7F7FFFFFu);
                    gpu.range.fill(8 * slot + 4, 1, 0u);
                }
                if (!onePass) { // the separate passes grow no glass rectangle: the screen
                    gpu.rectangle.fill(0, 2, 0u);
                    gpu.rectangle.fill(8, 1, std::uint32_t(size.x - 1));
                    gpu.rectangle.fill(12, 1, std::uint32_t(size.y - 1));
                }
                gpu.depthRange.use();
                gl::bindStorage(0, gpu.range);
                gl::bindStorage(1, gpu.rectangle);
                for (int slot = 0; slot < (d.front.valid() ? 2 : 1); ++slot) {
                    gl::bindTexture(0, r.texture(slot == 0 ? d.back : d.front));
                    gpu.depthRange.set("uDepth", 0);
                    gpu.depthRange.set("uSlot", slot);
                    gl::dispatch(std::uint32_t((size.x + 63) / 64),
                                 std::uint32_t((size.y + 63) / 64));
                }
                gl::memoryBarrier(gl::BarrierStorage);
            });

    // 3. Shade: uniforms common to both paths.
    auto setShading = [this, &gpu, frame, size](const gl::Program& f, const FrontData& d,
                                                const fg::Resources& r) {
        f.use();
        const std::string chosen = mParameters.choice("method");
        f.set("uMethod", chosen == "sir" ? 1 : chosen == "isr" ? 2 : 3);
        f.set("uSteps", int(mParameters.number("search-steps")));
        f.set("uTirPolicy", mParameters.choice("tir") == "reflect" ? 1 : 0);
        f.set("uBounces", int(mParameters.number("tir-bounces")));
        const std::string fresnel = mParameters.choice("fresnel");
        f.set("uFresnelMode", fresnel == "exact" ? 0 : fresnel == "schlick" ? 1 : 2);
        // Without opaque geometry the walk could only find the background, which is the
        // environment the lookup falls back to: skip it (the same image, cheaper).
        f.set("uNearby", mParameters.flag("nearby") && frame->opaqueGeometry ? 1 : 0);
        f.set("uDebug", int(mParameters.number("debug")));
        f.set("uSharedDispersion", mParameters.choice("dispersion-search") == "shared" ? 1 : 0);
        f.set("uViewportSize", glm::vec2(size));
        f.set("uNear", frame->camera.znear);
        f.set("uFar", frame->camera.zfar);
        f.set("uNearbyDistance", 0.5f * (frame->camera.zfar - frame->camera.znear));
        const glm::mat4 viewToWorld = glm::inverse(frame->camera.view);
        f.set("uViewToWorld", glm::mat3(viewToWorld));
        f.set("uViewOriginWorld", glm::vec3(viewToWorld[3]));
        f.set("uNormalLod", float(kNormalLod));
        frame->environment->bind(f, 0, frame->settings.environmentRotation,
                                 frame->settings.environmentIntensity);
        const std::pair<const char*, fg::TextureHandle> samplers[] = {
            {"uBackDepth", d.backDepth},   {"uBackNormal", d.backNormal},
            {"uFrontDepth", d.frontDepth}, {"uFrontNormal", d.frontNormal},
            {"uSceneColor", d.sceneColor}, {"uSceneDepth", d.sceneDepth}};
        int unit = 2;
        for (const auto& [uniform, handle] : samplers) {
            // Maps this method does not read are absent: the scene depth stands in (unread).
            gl::bindTexture(std::uint32_t(unit), r.texture(handle.valid() ? handle : d.sceneDepth));
            f.set(uniform, unit++);
        }
        gl::bindStorage(3, gpu.range);
    };
    const fg::TextureHandle sceneColor = blackboard.get<fg::TextureHandle>(plugin::kSceneColor);
    const fg::TextureHandle sceneDepth = blackboard.get<fg::TextureHandle>(plugin::kSceneDepth);
    auto readInputs = [&](fg::Builder& b, FrontData& d) {
        if (twoInterfaces) {
            b.after("refraction.depth_range");
            d.backNormal = b.read(back.normal);
        }
        if (twoInterfaces || onePass) // one pass: the gathered near target, front surface too
            d.backDepth = b.read(back.depth);
        if (method == "isr")
            b.after("refraction.normal_distance");
        if (reflect) {
            d.frontDepth = b.read(front.depth);
            d.frontNormal = b.read(front.normal);
        }
        d.sceneColor = b.read(sceneColor);
        d.sceneDepth = b.read(sceneDepth);
    };

    if (onePass) {
        // 4. The scene colour copied, then one pass over the glass rectangle shades the glass
        //    pixels (the mask's early depth test skips the others).
        struct ShadeData : FrontData {
            fg::TextureHandle mask, gatheredFar;
        };
        const auto& shaded = graph.addPass<ShadeData>(
            "refraction.shade",
            [&](fg::Builder& b, ShadeData& d) {
                readInputs(b, d);
                d.mask = b.read(glassMask);
                d.gatheredFar = b.read(gatheredFar);
                d.glass = b.write(b.create("refraction.scene_color", colorDesc));
            },
            [&gpu, setShading, setMaterial, frame, glassMaterialIndex](
                const fg::Resources& r, const ShadeData& d, gl::Context&) {
                gl::copyTexture(r.texture(d.sceneColor), r.texture(d.glass));
                auto status = gpu.framebuffer.attach("refraction.shade", {&r.texture(d.glass)},
                                                     &r.texture(d.mask));
                ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
                gpu.framebuffer.bind();
                // The rectangle lies at depth 1: it passes only where the mask holds 0.
                gl::apply({.cull = gl::Cull::None,
                           .depthWrite = false,
                           .depthFunc = gl::DepthFunc::Greater});
                setShading(gpu.deferred, d, r);
                setMaterial(gpu.deferred, glassMaterialIndex);
                gl::bindTexture(kGatherFarUnit, r.texture(d.gatheredFar));
                gpu.deferred.set("uGatherFar", int(kGatherFarUnit));
                gpu.deferred.set("uProjection", frame->camera.projection);
                gpu.deferred.set("uInverseProjection", glm::inverse(frame->camera.projection));
                gl::bindStorage(4, gpu.rectangle);
                gpu.emptyVao.bind();
                gl::drawArrays(6);
            });
        blackboard.put(plugin::kSceneColor, shaded.glass);
        return;
    }

    // 4. Front faces: refract, find the exit, shade.
    const auto& shaded = graph.addPass<FrontData>(
        "refraction.front_faces",
        [&](fg::Builder& b, FrontData& d) {
            readInputs(b, d);
            d.glass = b.write(b.create("refraction.glass", colorDesc));
            d.zbuffer = b.write(b.create("refraction.glass_zbuffer", zDesc));
        },
        [&gpu, drawGlass, setShading](const fg::Resources& r, const FrontData& d, gl::Context&) {
            auto status = gpu.framebuffer.attach("refraction.front_faces", {&r.texture(d.glass)},
                                                 &r.texture(d.zbuffer));
            ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
            gpu.framebuffer.bind();
            gl::clearColor(0, glm::vec4(0.0f));
            gl::clearDepth(1.0f);
            setShading(gpu.front, d, r);
            drawGlass(gpu.front, {.cull = gl::Cull::Back, .depthFunc = gl::DepthFunc::Less}, true);
        });

    // 5. Glass over the scene colour.
    const auto& composite = graph.addPass<CompositeData>(
        "refraction.composite",
        [&](fg::Builder& b, CompositeData& d) {
            d.scene = b.read(sceneColor);
            d.glass = b.read(shaded.glass);
            d.out = b.write(b.create("refraction.scene_color", colorDesc));
        },
        [&gpu](const fg::Resources& r, const CompositeData& d, gl::Context&) {
            auto status =
                gpu.framebuffer.attach("refraction.composite", {&r.texture(d.out)}, nullptr);
            ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
            gpu.framebuffer.bind();
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            gpu.composite.use();
            gl::bindTexture(0, r.texture(d.scene));
            gl::bindTexture(1, r.texture(d.glass));
            gpu.composite.set("uScene", 0);
            gpu.composite.set("uGlass", 1);
            gpu.emptyVao.bind();
            gl::drawArrays(3);
        });
    blackboard.put(plugin::kSceneColor, composite.out);
}

std::unique_ptr<plugin::Plugin> createPlugin() {
    return std::make_unique<RefractionPlugin>();
}

} // namespace refraction
