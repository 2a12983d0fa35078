// The plugin interface: a plugin adds passes to the engine's frame graph at declared stages,
// reads named resources from the blackboard and exposes parameters and a panel hook.
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
namespace scene {
struct Model;
struct Primitive;
} // namespace scene

namespace plugin {

/** Checked when a plugin is loaded: a plugin built against another interface is refused. */
inline constexpr const char* kInterfaceVersion = "glass.plugin/1";

/** Where in the frame a plugin's passes go. */
enum class Stage {
    AfterOpaque,   ///< the opaque scene colour and depth are complete
    BeforeTonemap, ///< last HDR stage
};

/** Blackboard keys the engine fills for plugins each frame (see ARCHITECTURE.md):
 *  "scene.color" fg::TextureHandle (HDR, RGBA16F), "scene.depth" fg::TextureHandle (Depth32F),
 *  "frame" const render::FrameInfo* (camera, size, time, model, deformed geometry, environment,
 *  shaders). A plugin that changes the scene colour puts its new version back under
 *  "scene.color". */
inline constexpr const char* kSceneColor = "scene.color";
inline constexpr const char* kSceneDepth = "scene.depth";
inline constexpr const char* kFrame = "frame";

class Plugin {
public:
    virtual ~Plugin() = default;
    virtual const char* name() const = 0;
    /** Called once with a current GL context: add shaders to `shaders`, create GPU objects. */
    virtual core::Status initialize(gl::ShaderLibrary& shaders) = 0;
    /** Adds this plugin's passes for `stage` (may add none). */
    virtual void addPasses(Stage stage, fg::FrameGraph& graph, fg::Blackboard& blackboard) = 0;
    /** True when this plugin draws primitive `primitive` of mesh node `node` itself, so the
     *  opaque pass leaves it out (a glass plugin claims its glass). */
    virtual bool drawsPrimitive(const scene::Model& model, int node,
                                const scene::Primitive& primitive) const {
        (void)model, (void)node, (void)primitive;
        return false;
    }
    /** Parameters the host may list, set from the command line and show in a panel. */
    virtual ParameterSet& parameters() = 0;
    /** Draws extra panel widgets; `imguiContext` is the viewer's ImGuiContext*. */
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
