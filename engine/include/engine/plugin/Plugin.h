// The plugin interface: a plugin adds passes to the engine's frame graph at declared stages,
// reads named resources from the blackboard and exposes parameters (with presets) and a panel
// hook. This header is the contract between the engine and a plugin built separately.
#pragma once

#include "engine/core/Result.h"
#include "engine/plugin/ParameterSet.h"

#include <memory>
#include <string>

namespace fg {
class FrameGraph;
class Blackboard;
} // namespace fg
namespace gl {
class ShaderLibrary;
}
namespace render {
struct DrawItem;
}

/** The contract, in full.
 *
 *  Lifetime. A host constructs the plugin (statically, or `glass_plugin_create` of a module),
 *  sets parameters, then calls `initialize` once, with the GL context current, before any
 *  frame; `addPasses` every frame; the destructor (or `glass_plugin_destroy`) runs with the
 *  same context still current, so GL objects the plugin owns may be released there. The host
 *  keeps the plugin until its renderer is gone; a module stays loaded while a LoadedPlugin copy
 *  lives.
 *
 *  Frames. `addPasses(stage, graph, blackboard)` only records: it declares passes with
 *  `graph.addPass<Data>(name, setup, execute)`, whose execute callbacks run later in the same
 *  frame, in an order the graph derives from reads and writes (of textures and buffers); an
 *  execute callback may return a core::Status, and an error ends the frame with it. Stages run in
 *  enum order; at each stage the blackboard holds the keys below. A plugin that replaces the scene
 *  colour writes a new texture and puts its handle back under kSceneColor; later stages and the
 *  tonemap read that. Handles and the FrameInfo pointer are valid for that frame only.
 *  A frame draws a world of characters as draw items (render::DrawItem: character, primitive,
 *  deformed vertices, material, world matrix); `claims` is asked once a frame per item before
 *  recording, plugins in the order they were added: the first that says yes owns the item
 *  (DrawItem::owner), which keeps it out of the opaque pass. Caches of per-character GPU data
 *  key on DrawItem::key, never on a model's address.
 *
 *  Threading. Every call, execute callbacks included, comes from the one thread that owns the
 *  GL context, never concurrently. A plugin may use threads of its own inside a call if it
 *  joins them before returning and makes no GL call from them.
 *
 *  Errors. `initialize` returns an error (a shader that will not link, say) and the host
 *  refuses the plugin; GL errors are caught by the host's KHR_debug callback (tests fail on
 *  any). Parameters are checked by ParameterSet: bad text is an error naming the parameter.
 *
 *  Versioning. kInterfaceVersion names this contract. It changes whenever a plugin built
 *  against the old headers could misbehave with the new engine: any change to the Plugin class
 *  (virtual functions, their signatures or order), to the types a plugin receives or reads
 *  (ParameterSet, Parameter, ParameterPreset, render::FrameInfo, render::DrawItem and what they
 *  point to,
 *  fg::FrameGraph, fg::Blackboard, gl:: objects), to the blackboard keys or their value types,
 *  to the stages or to the module entry points. Adding engine functions a plugin may call does
 *  not change it. Plugins are C++ with the engine's ABI: build them with the same compiler
 *  family and standard library as the engine (Debian 12's GCC 12 for the package). */
namespace plugin {

/** Checked when a plugin is loaded: a plugin built against another interface is refused.
 *  History: 1 first interface; 2 ParameterSet presets, buffer resources in the frame graph
 *  ("scene.vertices"), execute callbacks that may return a core::Status; 3 worlds of characters:
 *  FrameInfo::items (render::DrawItem) and Plugin::claims instead of FrameInfo::model,
 *  FrameInfo::geometry, FrameInfo::materials and Plugin::drawsPrimitive; 4 materials' layers and
 *  lights: FrameInfo::lights, MaterialTextures::bind's fifteen slots as uniform arrays
 *  (uHasTexture[], uTexture[], uTextureUv[]: common/material_uv.glsl), the lighting buffer at
 *  storage binding 9 (render::kLightingBinding), instances sharing deformed buffers; 5 the
 *  registry of shared numbers (gl/Registry.h): bindings and units as registered slots
 *  (gl::bindStorage(gl::slot::kLighting, ...), plugins' own from gl::slot::kFirstPluginBinding,
 *  registered with ShaderLibrary::share), MaterialTextures::bind at gl::slot::kMaterial with
 *  seventeen slots (transmission and thickness added); 6 shadows: Stage::Shadows, the shadow
 *  atlases kShadowDepth and kShadowGlass at units 23 and 24, plugins' units from 26; 7 caustics:
 *  kShadowCaustics at unit 25; 8 no texture bound for the whole frame: a pass that shades with the
 *  lights reads and binds the shadow atlases itself (render::ShadowAtlases,
 *  FrameInfo::shadowSampler); 9 one entry a frame: Stage::Shadows gone, a plugin draws into the
 *  shadow atlases at AfterOpaque and the engine's shading reads them as the frame leaves them
 *  (fg::Builder::readFinal). */
inline constexpr const char* kInterfaceVersion = "glass.plugin/9";

/** Where in the frame a plugin's passes go: each stage is entered once a frame, in this order.
 *  A plugin does its frame's work at one of them. */
enum class Stage {
    /** The background, the ground and the opaque scene are recorded into the scene colour and
     *  depth, and the lights' shadow atlases (FrameInfo::shadows not empty) into kShadowDepth
     *  and kShadowGlass. A plugin whose surfaces let light through draws them into the glass
     *  atlas (common/shadows.glsl) and puts its version back, and may put an atlas of caustics
     *  under kShadowCaustics: every pass that shades with the lights, the engine's recorded
     *  before this stage among them, reads the atlases as the frame leaves them, so the graph
     *  runs the plugin's shadow passes before the scene is shaded. */
    AfterOpaque,
    BeforeTonemap, ///< last HDR stage: after every plugin's AfterOpaque passes
};

/** Blackboard keys the engine fills for plugins each frame (see ARCHITECTURE.md):
 *  "scene.color" fg::TextureHandle (HDR, RGBA16F, the frame's size), "scene.depth"
 *  fg::TextureHandle (Depth32F, the opaque scene's depth), "scene.vertices" fg::BufferHandle
 *  (every character's deformed vertices, FrameInfo::items: a pass that draws or reads them
 *  declares a read, which orders it after the deform pass), "frame" const render::FrameInfo*
 *  (camera, settings and size, scene time, world, draw items, environment, shaders).
 *  A plugin that changes the scene colour puts its new version back under "scene.color". */
inline constexpr const char* kSceneColor = "scene.color";
inline constexpr const char* kSceneDepth = "scene.depth";
/** Where the frame accumulates (FrameInfo::temporal.enabled): every pixel's motion
 *  (common/motion.glsl, RGBA32UI). A plugin that draws pixels of its own writes their motion
 *  into a new version (or a copy) and puts it back, as it does the colour. */
inline constexpr const char* kSceneMotion = "scene.motion";
/** With "scene.motion": the previous frame's motion texels, which the temporal resolve checks
 *  its history against (RGBA32UI; meaningless on a history's first frame, temporal.index 0).
 *  A plugin reads it to know beforehand where a pixel's history will be rejected
 *  (common/motion.glsl's historyShows). */
inline constexpr const char* kHistoryMotion = "history.motion";
/** With it: the history's colour as the previous frame's resolve left it (RGBA32F; rgb, and
 *  in a the frames it holds). */
inline constexpr const char* kHistoryColor = "history.color";
inline constexpr const char* kSceneVertices = "scene.vertices";
/** The shadow atlases (fg::TextureHandle; render/Shadows.h, common/shadows.glsl): a pass whose
 *  program shades with the lights declares reads of them and binds them where it executes, all
 *  three with the caustics (render::ShadowAtlases); one recorded before the plugins' passes
 *  reads them as the frame leaves them (ShadowAtlases::readFinal). "scene.shadow_glass"
 *  holds, per texel, the optical depth of the glass along the light's ray (RGB, added) and its
 *  nearest distance from the light (A, the minimum). */
inline constexpr const char* kShadowDepth = "scene.shadow_depth";
inline constexpr const char* kShadowGlass = "scene.shadow_glass";
/** The caustics (fg::TextureHandle, RGBA16F, common/shadows.glsl), read at
 *  gl::slot::kShadowCaustics: per texel of a light's view, the light that reached the receiver
 *  seen there through glass, as a share of what would reach it unblocked (RGB), where A is
 *  under kNoGlass; where A is kNoGlass, none was focused and light through glass goes straight.
 *  The engine's holds none; a plugin that focuses light through its surfaces creates its own
 *  atlas (the tiles of the depth atlas, any resolution) and puts it here; a pass that shades
 *  with the lights reads and binds it. */
inline constexpr const char* kShadowCaustics = "scene.shadow_caustics";
inline constexpr const char* kFrame = "frame";

class Plugin {
public:
    virtual ~Plugin() = default;
    virtual const char* name() const = 0;
    /** Called once with a current GL context, before the first frame: add shaders to
     *  `shaders` (names under a directory of the plugin's own, e.g. "tint/..."), create GPU
     *  objects. An error refuses the plugin. */
    virtual core::Status initialize(gl::ShaderLibrary& shaders) = 0;
    /** Adds this plugin's passes for `stage` (may add none). */
    virtual void addPasses(Stage stage, fg::FrameGraph& graph, fg::Blackboard& blackboard) = 0;
    /** True when this plugin draws `item` itself, so the opaque pass leaves it out (a glass
     *  plugin claims its glass). Asked before the frame's passes are added. */
    virtual bool claims(const render::DrawItem& item) const {
        (void)item;
        return false;
    }
    /** Parameters (and presets) the host may list, set from the command line and show in a
     *  panel; the host sets them between frames only. */
    virtual ParameterSet& parameters() = 0;
    /** Draws extra panel widgets; `imguiContext` is the viewer's ImGuiContext*. Optional: the
     *  host's panel already shows every parameter and the presets of parameters(); only a
     *  plugin that links Dear ImGui itself (the same version as the host) overrides this. */
    virtual void drawPanel(void* imguiContext) { (void)imguiContext; }
};

/** A plugin and whatever keeps its code loaded: for a module, destroying the last copy calls
 *  the module's destroy function and then unloads the module. */
class LoadedPlugin {
public:
    LoadedPlugin() = default;
    explicit LoadedPlugin(std::shared_ptr<Plugin> plugin) : mPlugin(std::move(plugin)) {}
    Plugin* get() const { return mPlugin.get(); }
    Plugin* operator->() const { return mPlugin.get(); }
    explicit operator bool() const { return mPlugin != nullptr; }

private:
    std::shared_ptr<Plugin> mPlugin;
};

/** Loads a plugin from a shared module exporting `glass_plugin_interface` (returns the
 *  interface version string), `glass_plugin_create` and `glass_plugin_destroy`. Fails naming
 *  the path: cannot open, missing symbol, or a version other than kInterfaceVersion. */
core::Result<LoadedPlugin> loadPlugin(const std::string& path);

} // namespace plugin

/** Defines the three entry points of a plugin module for class `Type`. */
#define GLASS_PLUGIN_ENTRY(Type)                                                                   \
    extern "C" __attribute__((visibility("default"))) const char* glass_plugin_interface() {       \
        return ::plugin::kInterfaceVersion;                                                        \
    }                                                                                              \
    extern "C" __attribute__((visibility("default"))) ::plugin::Plugin* glass_plugin_create() {    \
        return new Type();                                                                         \
    }                                                                                              \
    extern "C" __attribute__((visibility("default"))) void glass_plugin_destroy(                   \
        ::plugin::Plugin* p) {                                                                     \
        delete p;                                                                                  \
    }
