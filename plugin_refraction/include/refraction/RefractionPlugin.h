// The refraction plugin: renders the engine's deforming glTF characters as glass, through every
// glass surface a ray crosses (the layers) or through the papers' two (the pair), with no
// preprocessing (DIR), with per-frame d_N (ISR), through one interface (SIR), traced through a
// BVH of the deformed glass (trace) or both (hybrid). One pipeline a frame (ARCHITECTURE.md,
// src/passes/Passes.h): the glass's optics, [its BVH], its extent -> a capture (the layers, or
// the pair) -> the walk over the glass pixels -> [the hybrid's trace] -> [the outlines].
#pragma once

#include "engine/plugin/Plugin.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace deform {
class GpuDeformer;
}

namespace refraction {

struct FrameContext;
struct GpuState;
struct Settings;

/** The layered path's figures for a frame: what its storage holds and how many pixels
 *  overflowed it. */
struct LayerStats {
    int capacity = 0;                 ///< K
    std::size_t bytesPerPixel = 0;    ///< the per-pixel arrays and maps at K
    std::size_t bytes = 0;            ///< all of them at the frame's size
    std::uint32_t overflowPixels = 0; ///< glass pixels with more than K layers (last frame)
    std::uint64_t traceRays = 0;      ///< method trace: rays traced through the glass BVH
    std::uint64_t traceSteps = 0;     ///< their BVH nodes visited
    std::uint32_t traceMaxSteps = 0;  ///< the most one pixel's sample visited
    std::uint32_t walkedPixels = 0;   ///< glass pixels the walk shaded
    std::uint32_t hybridTraced = 0;   ///< method hybrid: those it traced
    /** Those it traced for each reason: more than K layers, the walk left the layers, a total
     *  internal reflection, a crossing near an outline (the reasons met where its walk stopped:
     *  a pixel may have several). */
    std::array<std::uint32_t, 4> hybridBy{};
    /** Glass pixels that took the fresh samples: their history will be rejected (a frame that
     *  accumulates while anything moves, Settings' fresh-samples). */
    std::uint32_t freshPixels = 0;
};

/** Parameters (ParameterSet names, also glass-capture flags; Settings.cpp's table has each
 *  one's help): method opaque|sir|isr|dir|trace|hybrid, glass auto|all, ior (0: the
 *  material's), dispersion (-1: the material's), tint (multiplies the attenuation colour),
 *  absorption-distance (0: the material's), fresnel exact|schlick|off, search-steps 1..16,
 *  surfaces layers|two-surface, layer-capacity 1..8, interfaces 1..32, march-steps 1..64, tir
 *  reflect|clamp, tir-bounces, back-surface farthest|first, geometry-passes one|two,
 *  dispersion-search shared|per-channel, trace-samples 1..64, hybrid-criteria 1..15, nearby
 *  on|off, outline-aa on|off, debug
 *  none|back-depth|back-normal|dv|dn|exit-uv|steps|tir|exit-point|exit-direction|layer-count|
 *  overflow|hybrid. */
class RefractionPlugin final : public plugin::Plugin {
public:
    RefractionPlugin();
    ~RefractionPlugin() override;
    const char* name() const override { return "refraction"; }
    core::Status initialize(gl::ShaderLibrary& shaders) override;
    void addPasses(plugin::Stage stage, fg::FrameGraph& graph, fg::Blackboard& blackboard) override;
    /** Claims the glass: items Settings::isGlass() picks under the character's glass mode. */
    bool claims(const render::DrawItem& item) const override;
    /** Also holds presets of common materials (water 1.333 ... diamond 2.417) as data. */
    plugin::ParameterSet& parameters() override { return mParameters; }
    /** The last layered frame's figures (reads the GPU back: tools and tests). */
    LayerStats layerStats() const;

private:
    /** The parameters decoded, again only after they change. */
    const Settings& settings() const;
    /** The frame's decisions into `c`: its settings, glass ids and their model's defines;
     *  false when no glass is drawn. */
    bool beginFrame(FrameContext& c, const fg::Blackboard& blackboard) const;
    plugin::ParameterSet mParameters;
    mutable std::unique_ptr<Settings> mSettings;
    mutable std::uint64_t mSettingsRevision = 0;
    std::unique_ptr<GpuState> mGpu;
};

/** For hosts that link the plugin statically instead of loading the module. */
std::unique_ptr<plugin::Plugin> createPlugin();

} // namespace refraction
