// Runtime loading of plugin modules (dlopen), with the interface version checked.
#include "engine/plugin/Plugin.h"

#include <dlfcn.h>

#include <cstring>

namespace plugin {

core::Result<LoadedPlugin> loadPlugin(const std::string& path) {
    const std::string prefix = "plugin::loadPlugin(): " + path + ": ";
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* error = dlerror();
        return core::Error{prefix + "cannot load (" + (error ? error : "unknown error") + ")"};
    }
    std::shared_ptr<void> library(handle, [](void* h) { dlclose(h); });
    using InterfaceFn = const char* (*)();
    using CreateFn = Plugin* (*)();
    using DestroyFn = void (*)(Plugin*);
    auto interface = reinterpret_cast<InterfaceFn>(dlsym(handle, "glass_plugin_interface"));
    auto create = reinterpret_cast<CreateFn>(dlsym(handle, "glass_plugin_create"));
    auto destroy = reinterpret_cast<DestroyFn>(dlsym(handle, "glass_plugin_destroy"));
    if (!interface || !create || !destroy)
        return core::Error{prefix + "not a glass plugin (needs glass_plugin_interface, "
                                    "glass_plugin_create and glass_plugin_destroy)"};
    const char* version = interface();
    if (!version || std::strcmp(version, kInterfaceVersion) != 0)
        return core::Error{prefix + "built for plugin interface '" +
                           (version ? version : "(null)") + "', this engine needs '" +
                           kInterfaceVersion + "'"};
    Plugin* raw = create();
    if (!raw)
        return core::Error{prefix + "glass_plugin_create returned no plugin"};
    // The module's own destroy function deletes what its create made; the deleter holds the
    // library, so the module is unloaded only after that.
    return LoadedPlugin(
        std::shared_ptr<Plugin>(raw, [library, destroy](Plugin* p) { destroy(p); }));
}

} // namespace plugin
