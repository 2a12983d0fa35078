// glass-inspect: what a glTF character contains (meshes, skins, morph targets, clips, glass
// materials), or a scene's characters, as text or JSON, and the deformed vertices at a given
// time as PLY.
#include "../common/Cli.h"
#include "../common/ToolMain.h"
#include "InspectJson.h"
#include "Ply.h"

#include "engine/anim/Pose.h"
#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/core/Files.h"
#include "engine/core/Log.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/GpuDeformer.h"
#include "engine/gl/Context.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Shaders.h"
#include "engine/render/WorldLoader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace {

constexpr const char* kDescription =
    R"(glass-inspect MODEL|SCENE [MODEL...] [--json]: prints the meshes, primitives, vertex and
triangle counts, skins and joints, morph targets, animation clips (duration, interpolation) and
glass materials (KHR_materials_transmission, _volume, _ior, _dispersion) of a .gltf or .glb
file. For a scene file (.json, README "Scene files"), or several models (a scene of them side by
side, each playing its first clip from scene time 0): each character's model, clip, timing,
glass mode and counts, and the totals. What loading skipped or could not honour (an extension
the file uses that the engine does not implement, a POINTS or LINES primitive) is listed as
warnings.
glass-inspect MODEL|SCENE [MODEL...] --vertices cpu|gpu --out FILE.ply [--time T] [--clip C]
[--ascii]: writes the deformed vertices.
glass-inspect --check DIR|FILE...: checks every file below the folders.)";

constexpr const char* kFooter =
    R"(PLY layout: one vertex element with float properties x y z nx ny nz, in world space. Vertices
come mesh node by mesh node of the default scene in depth-first order (children in file order),
then primitive by primitive in file order, then in the primitive's vertex order (the file's
order; a primitive without NORMAL is unwelded, three vertices per triangle in index order). A
scene writes its characters in the file's order, each in that order, placed in the world. A
header comment per primitive gives its (character,) node, mesh, primitive, first vertex and
count.

Exit status: 0 success, 1 the model could not be loaded or the output written, 2 bad arguments.)";

int usageError(const std::string& message) {
    return tool::usageError("glass-inspect", message);
}

struct Options {
    std::vector<std::string> models;
    std::string model; ///< the first of them
    bool json = false;
    std::optional<std::string> vertices;
    std::optional<std::string> out;
    double time = 0.0;
    std::optional<std::string> clip;
    bool ascii = false;
    bool force = false;
    bool check = false;
};

void addOptions(CLI::App& app, Options& o) {
    app.add_option("models", o.models,
                   "glTF models, a scene file, or with --check folders and "
                   "files")
        ->type_name("MODEL|SCENE");
    app.add_flag("--check", o.check,
                 "load every .gltf and .glb below the folders (and files) given, images decoded, "
                 "and print one line per file: ok, ok with warnings (and which), or refused (and "
                 "why); then a summary. Exit 1 if any file is refused.");
    app.add_flag("--json", o.json,
                 "print the same as one JSON object (keys as in shared/assets/INVENTORY.json: "
                 "meshes, primitives, triangles, vertices, skins, joints_per_skin, "
                 "max_morph_targets, animations, animation_list)");
    app.add_option("--vertices", o.vertices,
                   "cpu: deform the model on the CPU (double-precision reference: morph, then "
                   "skin) and write its vertices to --out; gpu: the same through the engine's "
                   "GPU deform pass (headless EGL context), read back")
        ->check(tool::oneOf({"cpu", "gpu"}))
        ->type_name("cpu|gpu");
    app.add_option("--out", o.out, "PLY file to write (atomically: no partial file on failure)")
        ->type_name("FILE.ply");
    app.add_flag("--force", o.force,
                 "replace FILE.ply when it exists (otherwise that is an error)");
    app.add_option("--time", o.time,
                   "clip time in seconds (default 0); for a scene, the scene time")
        ->check(CLI::NonNegativeNumber.description(""))
        ->type_name("T");
    app.add_option("--clip", o.clip,
                   "clip name or index (default: the first clip; the rest pose if none); only "
                   "with one model (a scene's characters name their own)")
        ->type_name("C");
    app.add_flag("--ascii", o.ascii, "ASCII PLY instead of binary little-endian");
}

/** Parses argv; returns an exit code when the program should stop (help or bad arguments). */
std::optional<int> parse(int argc, char** argv, Options& o) {
    CLI::App app{"", "glass-inspect"};
    tool::configure(app, kDescription, kFooter);
    addOptions(app, o);
    if (const auto code = tool::parseArguments(app, argc, argv))
        return code;
    if (o.models.empty())
        return usageError(o.check ? "--check needs folders or files" : "no model given");
    if (o.check && (o.json || o.vertices || o.clip))
        return usageError("--check is a mode of its own");
    o.model = o.models.front();
    if (o.vertices.has_value() != o.out.has_value())
        return usageError("--vertices and --out go together");
    if (o.json && o.vertices)
        return usageError("--json and --vertices are separate modes");
    if (o.out && !o.force && std::filesystem::exists(*o.out)) {
        std::fprintf(stderr, "glass-inspect: %s exists (use --force to replace it)\n",
                     o.out->c_str());
        return 1;
    }
    return std::nullopt;
}

void printText(const scene::Model& model) {
    const auto j = inspect::describe(model);
    std::printf("%s\n", model.sourceName.c_str());
    std::printf("  meshes %zu, primitives %zu, triangles %zu, vertices %zu, nodes %zu\n",
                j["meshes"].get<std::size_t>(), j["primitives"].get<std::size_t>(),
                j["triangles"].get<std::size_t>(), j["vertices"].get<std::size_t>(),
                model.nodes.size());
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
        if (!model.nodes[n].instances.empty())
            std::printf("  node %zu '%s': mesh %d drawn %zu times (EXT_mesh_gpu_instancing)\n", n,
                        model.nodes[n].name.c_str(), model.nodes[n].mesh,
                        model.nodes[n].instances.size());
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const scene::Mesh& mesh = model.meshes[m];
        std::printf("  mesh %zu '%s': %zu primitive(s), %zu morph target(s)\n", m,
                    mesh.name.c_str(), mesh.primitives.size(), mesh.morphTargetCount());
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const scene::Primitive& prim = mesh.primitives[p];
            std::printf(
                "    primitive %zu: %zu vertices, %zu triangles, material %d, %d influences%s%s\n",
                p, prim.sourceVertexCount, prim.triangleCount(), prim.material,
                4 * prim.influenceSets(), prim.flatNormals ? ", flat normals generated" : "",
                prim.generatedTangents ? ", tangents generated" : "");
        }
    }
    for (std::size_t s = 0; s < model.skins.size(); ++s)
        std::printf("  skin %zu '%s': %zu joints\n", s, model.skins[s].name.c_str(),
                    model.skins[s].joints.size());
    for (const auto& clip : j["animation_list"]) {
        std::string modes;
        for (const auto& mode : clip["interpolation"]) {
            // appended in two steps: `(cond ? "" : ",") + std::string` trips GCC 12's
            // -Wrestrict false positive at -O3 (GCC bug 105329)
            if (!modes.empty())
                modes += ',';
            modes += mode.get<std::string>();
        }
        std::printf("  clip '%s': %.3f s, %zu channels, %s\n",
                    clip["name"].get<std::string>().c_str(), clip["duration_s"].get<double>(),
                    clip["channels"].get<std::size_t>(), modes.c_str());
        for (const auto& p : clip["pointer_channels"])
            std::printf("    channel %d: KHR_animation_pointer %s, %s\n", p["channel"].get<int>(),
                        p["pointer"].get<std::string>().c_str(),
                        p["played"].get<bool>() ? "played" : "skipped");
    }
    if (!model.variants.empty()) {
        std::string names;
        for (const std::string& name : model.variants)
            names += (names.empty() ? "'" : ", '") + name + "'";
        std::printf("  variants (KHR_materials_variants, glass-capture --variant): %s\n",
                    names.c_str());
    }
    for (const auto& g : j["transmissive_materials"]) {
        std::printf("  glass material '%s': transmission %.3g, ior %.4g, dispersion %.3g",
                    g["material"].get<std::string>().c_str(), g["transmission"].get<double>(),
                    g["ior"].get<double>(), g["dispersion"].get<double>());
        if (g["volume"].get<bool>())
            std::printf(", thickness %.3g, attenuation %s at distance %s",
                        g["thickness"].get<double>(), g["attenuationColor"].dump().c_str(),
                        g["attenuationDistance"].dump().c_str());
        std::printf("\n");
    }
    for (const auto& [name, n] : j["material_layers"].items())
        std::printf("  %s: %d material(s)\n", name.c_str(), n.get<int>());
    if (!model.lights.empty()) {
        std::string lights;
        for (const auto& l : j["lights"])
            lights += (lights.empty() ? "" : ", ") + l["type"].get<std::string>() + " '" +
                      l["name"].get<std::string>() + "'";
        std::printf("  lights (KHR_lights_punctual) %zu: %s\n", model.lights.size(),
                    lights.c_str());
    }
    if (model.cameras.size())
        std::printf("  cameras %zu\n", model.cameras.size());
    for (const std::string& warning : model.warnings)
        std::printf("  warning: %s\n", warning.c_str());
}

/** --check: every .gltf/.glb below `roots` (sorted), one line each, then a summary; 1 if any
 *  file is refused. */
int checkFiles(const std::vector<std::string>& roots) {
    std::vector<std::filesystem::path> files;
    for (const std::string& root : roots) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(root, ec)) {
            files.emplace_back(root);
            continue;
        }
        if (!std::filesystem::is_directory(root, ec)) {
            std::fprintf(stderr, "glass-inspect: --check: %s is neither a folder nor a file\n",
                         root.c_str());
            return 2;
        }
        for (auto it = std::filesystem::recursive_directory_iterator(
                 root, std::filesystem::directory_options::skip_permission_denied, ec);
             !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
            std::string extension = it->path().extension().string();
            for (char& c : extension)
                c = char(std::tolower(static_cast<unsigned char>(c)));
            if (it->is_regular_file(ec) && (extension == ".gltf" || extension == ".glb"))
                files.push_back(it->path());
        }
    }
    std::sort(files.begin(), files.end());
    std::size_t ok = 0, warned = 0, refused = 0;
    for (const std::filesystem::path& file : files) {
        const auto model = asset::loadGltf(file);
        if (!model) {
            ++refused;
            std::printf("refused  %s: %s\n", file.string().c_str(), model.error().message.c_str());
        } else if (!model->warnings.empty()) {
            ++warned;
            std::printf("warnings %s:", file.string().c_str());
            for (std::size_t i = 0; i < model->warnings.size(); ++i)
                std::printf("%s %s", i ? ";" : "", model->warnings[i].c_str());
            std::printf("\n");
        } else {
            ++ok;
            std::printf("ok       %s\n", file.string().c_str());
        }
        std::fflush(stdout);
    }
    std::printf("%zu files: %zu ok, %zu ok with warnings, %zu refused\n", files.size(), ok, warned,
                refused);
    return refused > 0 ? 1 : 0;
}

/** True when the input is a world of characters rather than one model: a scene file, or
 *  several models. */
bool isWorld(const Options& o) {
    return o.models.size() > 1 || asset::isSceneFile(o.model);
}

/** The world to deform: a scene file's, several models side by side (render::loadWorld), or
 *  one model as a character at the origin playing its first clip, whose clock is the clip time
 *  itself (held at the clip's ends). */
core::Result<scene::World> worldOf(const Options& o, const asset::LoadOptions& loadOptions) {
    if (isWorld(o))
        return render::loadWorld(o.models, loadOptions);
    auto model = asset::loadModel(o.model, loadOptions);
    if (!model)
        return model.error();
    scene::Character c;
    c.model = std::make_shared<const scene::Model>(std::move(*model));
    c.modelPath = o.model;
    c.name = c.model->sourceName;
    c.play(c.model->animations.empty() ? -1 : 0);
    c.performance.layers.front().loop = scene::Loop::Clamp;
    scene::World world;
    world.characters.push_back(std::move(c));
    return world;
}

/** Every character deformed at scene time `time` (meshToWorld includes its placement); with
 *  `onGpu` the primitives are the GPU deform pass's, read back: one upload per model, one
 *  placement per character, as the renderer does. */
core::Result<std::vector<std::vector<deform::DeformedInstance>>>
deformWorld(const scene::World& world, double time, bool onGpu) {
    std::vector<std::vector<deform::DeformedInstance>> characters;
    if (!onGpu) {
        for (const scene::Character& c : world.characters)
            characters.push_back(deform::deformCharacter(c, time));
        return characters;
    }
    auto context = gl::createHeadlessContext();
    if (!context)
        return context.error();
    gl::ShaderLibrary shaders;
    shaders.add(engineShaderFiles());
    std::map<const scene::Model*, std::shared_ptr<const deform::GpuModel>> uploads;
    for (const scene::Character& c : world.characters) {
        auto& upload = uploads[c.model.get()];
        if (!upload) {
            auto created = deform::GpuModel::create(*c.model);
            if (!created)
                return created.error();
            upload = std::move(*created);
        }
        auto deformer = deform::GpuDeformer::create(upload, shaders);
        if (!deformer)
            return deformer.error();
        (*deformer)->update(anim::evaluate(*c.model, c.performance, time), c.transform());
        std::vector<deform::DeformedInstance>& instances = characters.emplace_back();
        const auto& placed = (*deformer)->instances();
        for (std::size_t i = 0; i < placed.size(); ++i) {
            deform::DeformedInstance& instance = instances.emplace_back();
            instance.node = placed[i].node;
            instance.mesh = placed[i].mesh;
            instance.meshToWorld = glm::dmat4(placed[i].meshToWorld); // placement included
            for (std::size_t p = 0; p < placed[i].primitives.size(); ++p)
                instance.primitives.push_back((*deformer)->download(i, p));
        }
    }
    if (gl::checkErrors("glass-inspect --vertices gpu") > 0 || gl::errorCount() > 0)
        return core::Error{"glass-inspect: GL errors during GPU deformation (see log)"};
    return characters;
}

int writeVertices(const scene::World& world, const Options& o) {
    const bool isScene = isWorld(o);
    auto characters = deformWorld(world, o.time, *o.vertices == "gpu");
    if (!characters) {
        std::fprintf(stderr, "glass-inspect: %s\n", characters.error().message.c_str());
        return 1;
    }
    std::vector<deform::DeformedPrimitive> placed;
    std::vector<std::string> labels;
    for (std::size_t ci = 0; ci < characters->size(); ++ci)
        for (const auto& instance : (*characters)[ci])
            for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
                placed.push_back(deform::toWorld(instance.primitives[p], instance.meshToWorld));
                const std::string character = isScene ? "character " + std::to_string(ci) + " '" +
                                                            world.characters[ci].name + "' "
                                                      : std::string();
                labels.push_back(character + "node " + std::to_string(instance.node) + " mesh " +
                                 std::to_string(instance.mesh) + " primitive " + std::to_string(p));
            }
    std::vector<inspect::PlyBlock> blocks;
    for (std::size_t i = 0; i < placed.size(); ++i)
        blocks.push_back({labels[i], &placed[i]});
    const scene::Character& first = world.characters.front();
    const std::string what = isScene ? "scene " + o.model + (o.models.size() > 1 ? " ..." : "") +
                                           " time " + std::to_string(o.time)
                                     : first.model->sourceName + " clip " +
                                           std::to_string(first.mainClip()) + " time " +
                                           std::to_string(o.time);
    const std::string comment =
        "glass-inspect " + what + " vertices " + *o.vertices + ", world space";
    const core::Status written =
        core::writeFileAtomic(*o.out, inspect::makePly(blocks, comment, o.ascii));
    if (!written) {
        std::fprintf(stderr, "glass-inspect: %s\n", written.error().message.c_str());
        return 1;
    }
    return 0;
}

const char* glassModeName(scene::GlassMode mode) {
    return mode == scene::GlassMode::All ? "all" : mode == scene::GlassMode::None ? "none" : "auto";
}

/** A scene's characters (model, clip, timing, glass, counts) and totals, as JSON. */
nlohmann::ordered_json describeScene(const scene::World& world) {
    nlohmann::ordered_json characters = nlohmann::ordered_json::array();
    std::size_t vertices = 0, triangles = 0;
    for (const scene::Character& c : world.characters) {
        const auto model = inspect::describe(*c.model);
        vertices += model["vertices"].get<std::size_t>();
        triangles += model["triangles"].get<std::size_t>();
        nlohmann::ordered_json character = {{"name", c.name}, {"model", c.modelPath}};
        // What it plays, as its scene file spells it.
        character.update(nlohmann::ordered_json::parse(asset::encodePerformance(c)));
        if (!character.contains("clip") && !character.contains("layers"))
            character["clip"] = ""; // the rest pose
        character.update({{"glass", glassModeName(c.glass)},
                          {"vertices", model["vertices"]},
                          {"triangles", model["triangles"]}});
        characters.push_back(std::move(character));
    }
    std::map<const scene::Model*, int> models;
    for (const scene::Character& c : world.characters)
        ++models[c.model.get()];
    return {{"characters", characters},
            {"models", models.size()},
            {"vertices", vertices},
            {"triangles", triangles}};
}

/** What `c` plays, in words: "clip 'walk' (offset 0 s, speed 1, looping)", or its layers. */
std::string playsLine(const scene::Character& c) {
    const auto clipName = [&](int clip) {
        return clip < 0 ? std::string("rest")
                        : "'" + c.model->animations[std::size_t(clip)].name + "'";
    };
    const auto timing = [](const scene::Layer& l) {
        char text[96];
        std::snprintf(text, sizeof text, "offset %.3g s, speed %.3g, %s", l.timeOffset, l.speed,
                      l.loop == scene::Loop::Clamp      ? "clamped"
                      : l.loop == scene::Loop::PingPong ? "ping-pong"
                      : l.repetitions > 0
                          ? ("looping " + std::to_string(l.repetitions) + " times").c_str()
                          : "looping");
        return std::string(text);
    };
    const scene::Performance& p = c.performance;
    std::string line;
    if (p.layers.size() == 1 && p.layers[0].weight == 1.0 && !p.layers[0].additive &&
        p.layers[0].mask.empty()) {
        line = "clip " + clipName(p.layers[0].clip) + " (" + timing(p.layers[0]) + ")";
    } else {
        line = "layers";
        for (const scene::Layer& l : p.layers) {
            char weight[32];
            std::snprintf(weight, sizeof weight, " x%.3g", l.weight);
            line += std::string(line == "layers" ? " " : "; ") + clipName(l.clip) + weight +
                    (l.additive ? " additive" : "") + (l.mask.empty() ? "" : " masked") + " (" +
                    timing(l) + ")";
        }
    }
    for (const scene::Transition& t : p.transitions) {
        char text[96];
        std::snprintf(text, sizeof text, ", to %s at %.3g s over %.3g s", clipName(t.to).c_str(),
                      t.at, t.duration);
        line += text;
    }
    if (p.rootMotion != scene::RootMotion::Baked)
        line += std::string(", root motion ") + scene::toString(p.rootMotion);
    if (!p.morphs.empty())
        line += ", " + std::to_string(p.morphs.size()) + " morph weights set";
    if (p.pausedAt) {
        char text[48];
        std::snprintf(text, sizeof text, ", paused at %.3g s", *p.pausedAt);
        line += text;
    }
    return line;
}

void printScene(const std::string& path, const scene::World& world) {
    const auto j = describeScene(world);
    std::printf("%s\n  characters %zu, models %zu, vertices %zu, triangles %zu\n", path.c_str(),
                j["characters"].size(), j["models"].get<std::size_t>(),
                j["vertices"].get<std::size_t>(), j["triangles"].get<std::size_t>());
    for (std::size_t i = 0; i < world.characters.size(); ++i) {
        const auto& c = j["characters"][i];
        std::printf("  [%zu] '%s': %s, %s, glass %s, %zu vertices, %zu triangles\n", i,
                    c["name"].get<std::string>().c_str(), c["model"].get<std::string>().c_str(),
                    playsLine(world.characters[i]).c_str(), c["glass"].get<std::string>().c_str(),
                    c["vertices"].get<std::size_t>(), c["triangles"].get<std::size_t>());
    }
}

} // namespace

int run(int argc, char** argv) {
    Options options;
    if (const auto exitCode = parse(argc, argv, options))
        return *exitCode;
    if (options.check) {
        core::setLogLevel(core::LogLevel::Error); // the warnings are in the lines
        return checkFiles(options.models);
    }
    // Images decoded as every other tool decodes them: a file whose image data is corrupt is
    // refused here too, not inspected and then refused by glass-capture.
    const asset::LoadOptions loadOptions;
    const bool isScene = isWorld(options);
    if (isScene && options.clip)
        return usageError("--clip goes with one model; a scene's characters name their clips");
    auto world = worldOf(options, loadOptions);
    if (!world) {
        std::fprintf(stderr, "glass-inspect: %s\n", world.error().message.c_str());
        return 1;
    }
    if (options.clip) {
        scene::Character& only = world->characters.front();
        const auto found = only.model->findAnimation(*options.clip);
        if (!found)
            return usageError(only.model->sourceName + " has no clip '" + *options.clip + "'");
        only.performance.layers.front().clip = *found;
    }
    if (options.vertices)
        return writeVertices(*world, options);
    if (isScene && options.json)
        std::printf("%s\n", describeScene(*world).dump(2).c_str());
    else if (isScene)
        printScene(options.models.size() > 1 ? "models side by side" : options.model, *world);
    else if (options.json)
        std::printf("%s\n", inspect::describe(*world->characters[0].model).dump(2).c_str());
    else
        printText(*world->characters[0].model);
    return 0;
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-inspect", run, argc, argv);
}
