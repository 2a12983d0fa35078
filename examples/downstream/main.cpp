// glass-example: a program of another project that uses only the installed Glass package. It
// loads a glTF model, plays its first clip as glass with the refraction plugin (linked
// statically), optionally adds a plugin module, renders one frame headless and writes a PNG.
// To show that the glass was drawn it also renders the same frame with the plugin switched off
// and counts the pixels that differ.
#include "engine/asset/ModelLoader.h"
#include "engine/capture/Image.h"
#include "engine/core/Version.h"
#include "engine/gl/Context.h"
#include "engine/render/Camera.h"
#include "engine/render/Environment.h"
#include "engine/render/Renderer.h"
#include "refraction/RefractionPlugin.h"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr const char* kUsage =
    "usage: glass-example MODEL OUT.png [--time SECONDS] [--plugin MODULE]\n"
    "MODEL: a .gltf/.glb file or builtin:sphere\n";

int fail(const std::string& message) {
    std::fprintf(stderr, "glass-example: %s\n", message.c_str());
    return 1;
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::string> positional;
    double time = 0.0;
    std::string modulePath;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--time" && i + 1 < argc) {
            time = std::atof(argv[++i]);
        } else if (arg == "--plugin" && i + 1 < argc) {
            modulePath = argv[++i];
        } else if (arg.rfind("--", 0) == 0) {
            std::fputs(kUsage, stderr);
            return 2;
        } else {
            positional.push_back(arg);
        }
    }
    if (positional.size() != 2) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    std::printf("Glass %s\n", core::engineVersion());

    auto loaded = asset::loadModel(positional[0]);
    if (!loaded)
        return fail(loaded.error().message);
    const auto model = std::make_shared<const scene::Model>(std::move(*loaded));
    auto context = gl::createHeadlessContext();
    if (!context)
        return fail(context.error().message);
    // The plugins outlive the renderer that calls them (declared first, destroyed last but
    // for the context): the refraction plugin, every mesh as glass, searched exits (DIR), and
    // the module given, if any.
    auto glass = refraction::createPlugin();
    for (const auto& [key, value] : {std::pair{"method", "dir"}, std::pair{"glass", "all"}})
        if (auto set = glass->parameters().set(key, value); !set)
            return fail(set.error().message);
    plugin::LoadedPlugin extra;
    if (!modulePath.empty()) {
        auto loaded = plugin::loadPlugin(modulePath);
        if (!loaded)
            return fail(loaded.error().message);
        extra = std::move(*loaded);
    }
    auto renderer = render::Renderer::create(render::Environment::proceduralSky(), **context);
    if (!renderer)
        return fail(renderer.error().message);
    for (plugin::Plugin* added : {glass.get(), extra.get()})
        if (added)
            if (auto status = (*renderer)->addPlugin(added); !status)
                return fail(status.error().message);

    // A world of one character playing the model's first clip.
    const int clip = model->animations.empty() ? -1 : 0;
    const scene::World world = scene::singleCharacterWorld(model, clip, positional[0]);
    render::RenderSettings settings;
    settings.size = {256, 256};
    const render::Camera camera =
        render::frameBounds(render::animatedBounds(*model, clip), 1.0f, 0.7f, 0.4f, 0.2f);
    auto frame = [&]() -> core::Result<capture::Image> {
        auto stats = (*renderer)->render(world, camera, settings, time);
        if (!stats)
            return stats.error();
        return capture::Image{settings.size.x, settings.size.y, (*renderer)->readOutput()};
    };
    auto asGlass = frame();
    if (!asGlass)
        return fail(asGlass.error().message);
    (void)glass->parameters().set("method", "opaque");
    auto asOpaque = frame();
    if (!asOpaque)
        return fail(asOpaque.error().message);

    std::size_t changed = 0;
    for (std::size_t i = 0; i < asGlass->rgba.size(); i += 4)
        changed += asGlass->rgba[i] != asOpaque->rgba[i] ||
                   asGlass->rgba[i + 1] != asOpaque->rgba[i + 1] ||
                   asGlass->rgba[i + 2] != asOpaque->rgba[i + 2];
    if (auto written = capture::writePng(positional[1], *asGlass); !written)
        return fail(written.error().message);
    std::printf("wrote %s: %zu of %zu pixels show glass\n", positional[1].c_str(), changed,
                asGlass->rgba.size() / 4);
    return changed > 0 ? 0 : fail("the refraction plugin changed no pixel");
}
