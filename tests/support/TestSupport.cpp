// Test helpers: shared-asset lookup, temporary directories, glTF writing, commands.
#include "support/TestSupport.h"

#include "engine/asset/Glb.h"
#include "engine/asset/HdrImage.h"
#include "engine/asset/ModelLoader.h"

#include <stb_image_write.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sys/wait.h>

namespace test {
namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t b0 = bytes[i];
        const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const std::uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
        out += table[(triple >> 18) & 63];
        out += table[(triple >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(triple >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[triple & 63] : '=';
    }
    return out;
}

void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

} // namespace

std::filesystem::path sharedDir() {
    const char* overridden = std::getenv("GLASS_SHARED_DIR");
    const std::filesystem::path dir = overridden ? overridden : GLASS_SHARED_DIR;
    std::error_code ec;
    if (std::filesystem::is_regular_file(dir / "assets" / "INVENTORY.json", ec))
        return std::filesystem::weakly_canonical(dir, ec);
    return {};
}

namespace {

std::filesystem::path freshTempName() {
    std::random_device random;
    return std::filesystem::temp_directory_path() /
           ("glass-test-" + std::to_string(random()) + std::to_string(random()));
}

} // namespace

TempDir::TempDir() : mPath(freshTempName()) {
    std::filesystem::create_directories(mPath);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(mPath, ec);
}

GltfBuilder::GltfBuilder()
    : doc({{"asset", {{"version", "2.0"}, {"generator", "glass tests"}}},
           {"buffers", nlohmann::json::array()},
           {"bufferViews", nlohmann::json::array()},
           {"accessors", nlohmann::json::array()}}) {}

int GltfBuilder::componentsOf(const std::string& type) {
    if (type == "SCALAR")
        return 1;
    if (type == "VEC2")
        return 2;
    if (type == "VEC3")
        return 3;
    if (type == "VEC4" || type == "MAT2")
        return 4;
    if (type == "MAT3")
        return 9;
    return 16;
}

int GltfBuilder::addView(const void* data, std::size_t bytes, int byteStride) {
    while (bin.size() % 4)
        bin.push_back(0);
    const std::size_t offset = bin.size();
    bin.resize(offset + bytes);
    if (bytes)
        std::memcpy(bin.data() + offset, data, bytes);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (byteStride)
        view["byteStride"] = byteStride;
    doc["bufferViews"].push_back(view);
    return int(doc["bufferViews"].size()) - 1;
}

std::filesystem::path GltfBuilder::save(const std::filesystem::path& directory,
                                        const std::string& name, GltfFormat format) const {
    nlohmann::json out = doc;
    std::vector<std::uint8_t> padded = bin;
    while (padded.size() % 4)
        padded.push_back(0);
    const bool hasBuffer = !out["buffers"].empty() || !padded.empty();
    if (hasBuffer && out["buffers"].empty())
        out["buffers"].push_back({{"byteLength", padded.size()}});
    if (hasBuffer && !out["buffers"][0].contains("byteLength"))
        out["buffers"][0]["byteLength"] = padded.size();
    std::filesystem::path path =
        directory / (name + (format == GltfFormat::Glb ? ".glb" : ".gltf"));
    if (format == GltfFormat::DataUri) {
        if (hasBuffer && !out["buffers"][0].contains("uri"))
            out["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(padded);
        writeBytes(path, out.dump(2));
    } else if (format == GltfFormat::ExternalBin) {
        if (hasBuffer && !out["buffers"][0].contains("uri")) {
            out["buffers"][0]["uri"] = name + ".bin";
            writeBytes(directory / (name + ".bin"), std::string(padded.begin(), padded.end()));
        }
        writeBytes(path, out.dump(2));
    } else {
        const std::vector<std::uint8_t> glb = asset::encodeGlb(out.dump(), padded);
        writeBytes(path, std::string(glb.begin(), glb.end()));
    }
    return path;
}

GltfBuilder twoJointModel() {
    GltfBuilder b;
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
    const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::vector<std::uint16_t> joints = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0,
                                               0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0};
    const std::vector<float> weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0,
                                        1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0};
    const std::vector<std::uint16_t> indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
    const std::vector<float> morph = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    // Inverse bind: joint 0 at the origin (identity), joint 1 at x = 1 (translate by -1).
    const std::vector<float> inverseBind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,
                                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1};
    const std::vector<float> times = {0.0f, 1.0f};
    const float s = std::sqrt(0.5f);
    const std::vector<float> rotations = {0, 0, 0, 1, 0, 0, s, s};
    const std::vector<float> morphWeights = {0.0f, 1.0f};

    const int aPos = b.addAccessor(positions, 5126, "VEC3");
    b.doc["accessors"][aPos]["min"] = {0, 0, 0};
    b.doc["accessors"][aPos]["max"] = {2, 1, 0};
    const int aNrm = b.addAccessor(normals, 5126, "VEC3");
    const int aJnt = b.addAccessor(joints, 5123, "VEC4");
    const int aWgt = b.addAccessor(weights, 5126, "VEC4");
    const int aIdx = b.addAccessor(indices, 5123, "SCALAR");
    const int aMorph = b.addAccessor(morph, 5126, "VEC3");
    const int aIbm = b.addAccessor(inverseBind, 5126, "MAT4");
    const int aTime = b.addAccessor(times, 5126, "SCALAR");
    b.doc["accessors"][aTime]["min"] = {0.0};
    b.doc["accessors"][aTime]["max"] = {1.0};
    const int aRot = b.addAccessor(rotations, 5126, "VEC4");
    const int aMw = b.addAccessor(morphWeights, 5126, "SCALAR");

    b.doc["meshes"] = {
        {{"name", "strip"},
         {"primitives",
          {{{"attributes",
             {{"POSITION", aPos}, {"NORMAL", aNrm}, {"JOINTS_0", aJnt}, {"WEIGHTS_0", aWgt}}},
            {"indices", aIdx},
            {"targets", {{{"POSITION", aMorph}}}}}}},
         {"weights", {0.0}}}};
    b.doc["nodes"] = {{{"name", "skinned"}, {"mesh", 0}, {"skin", 0}},
                      {{"name", "root"}, {"children", {2}}},
                      {{"name", "tip"}, {"translation", {1.0, 0.0, 0.0}}}};
    b.doc["skins"] = {{{"joints", {1, 2}}, {"inverseBindMatrices", aIbm}}};
    b.doc["scenes"] = {{{"nodes", {0, 1}}}};
    b.doc["scene"] = 0;
    b.doc["animations"] = {{{"name", "bend"},
                            {"samplers",
                             {{{"input", aTime}, {"output", aRot}, {"interpolation", "LINEAR"}},
                              {{"input", aTime}, {"output", aMw}, {"interpolation", "LINEAR"}}}},
                            {"channels",
                             {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}},
                              {{"sampler", 1}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}};
    return b;
}

GltfBuilder pointerTwoJointModel(const std::string& rotationPointer) {
    GltfBuilder b = twoJointModel();
    const auto pointer = [](const std::string& to) {
        return nlohmann::json{{"path", "pointer"},
                              {"extensions", {{"KHR_animation_pointer", {{"pointer", to}}}}}};
    };
    const std::vector<std::uint8_t> png = makePng(2, 2, {200, 120, 40, 255});
    b.doc["images"] = {
        {{"bufferView", b.addView(png.data(), png.size())}, {"mimeType", "image/png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    nlohmann::json baseColor = {{"index", 0}};
    baseColor["extensions"]["KHR_texture_transform"]["offset"] = {0.0, 0.0};
    b.doc["materials"] = nlohmann::json::array();
    b.doc["materials"][0]["pbrMetallicRoughness"] = {{"metallicFactor", 0.0},
                                                     {"baseColorTexture", baseColor}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["extensions"] = {{"KHR_lights_punctual",
                            {{"lights",
                              {{{"type", "spot"},
                                {"intensity", 4.0},
                                {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}}}}}}};
    b.doc["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    b.doc["nodes"].push_back({{"name", "lamp"},
                              {"translation", {0.0, 2.0, 0.0}},
                              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc["nodes"].push_back({{"name", "eye"}, {"translation", {0.0, 0.5, 4.0}}, {"camera", 0}});
    b.doc["scenes"][0]["nodes"] = {0, 1, 3, 4};
    // Samplers over the clip's second: a colour, an offset (0, 0) -> (0.5, 0.25) and an angle.
    auto& samplers = b.doc["animations"][0]["samplers"];
    const int times = samplers[1]["input"];
    samplers.push_back(
        {{"input", times},
         {"output", b.addAccessor(std::vector<float>{1, 1, 1, 0, 1, 0.5f}, 5126, "VEC3")}});
    samplers.push_back(
        {{"input", times},
         {"output", b.addAccessor(std::vector<float>{0, 0, 0.5f, 0.25f}, 5126, "VEC2")}});
    samplers.push_back({{"input", times},
                        {"output", b.addAccessor(std::vector<float>{0.6f, 1.0f}, 5126, "SCALAR")}});
    auto& channels = b.doc["animations"][0]["channels"];
    channels[0]["target"] = pointer(rotationPointer);
    channels[1]["target"] = pointer("/nodes/0/weights");
    const auto add = [&](int sampler, const std::string& to) {
        channels.push_back({{"sampler", sampler}, {"target", pointer(to)}});
    };
    add(1, "/materials/0/pbrMetallicRoughness/metallicFactor");
    add(1, "/materials/0/alphaCutoff");
    add(1, "/extensions/KHR_lights_punctual/lights/0/intensity");
    add(2, "/extensions/KHR_lights_punctual/lights/0/color");
    add(4, "/extensions/KHR_lights_punctual/lights/0/spot/outerConeAngle");
    add(3, "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/"
           "KHR_texture_transform/offset");
    add(4, "/cameras/0/perspective/yfov");
    b.doc["extensionsUsed"] = {"KHR_animation_pointer", "KHR_lights_punctual",
                               "KHR_texture_transform"};
    return b;
}

GltfBuilder pointerGlassSphereModel() {
    GltfBuilder b;
    const scene::Model shape = asset::makeSphere(48);
    const scene::Primitive& sphere = shape.meshes.at(0).primitives.at(0);
    std::vector<float> positions, normals, uvs;
    for (std::size_t v = 0; v < sphere.vertexCount(); ++v) {
        positions.insert(positions.end(),
                         {sphere.positions[v].x, sphere.positions[v].y, sphere.positions[v].z});
        normals.insert(normals.end(),
                       {sphere.normals[v].x, sphere.normals[v].y, sphere.normals[v].z});
        uvs.insert(uvs.end(), {sphere.uv0[v].x, sphere.uv0[v].y});
    }
    const int position = b.addAccessor(positions, 5126, "VEC3");
    b.doc["accessors"][position]["min"] = {-1.0, -1.0, -1.0};
    b.doc["accessors"][position]["max"] = {1.0, 1.0, 1.0};
    nlohmann::json primitive;
    primitive["attributes"] = {{"POSITION", position},
                               {"NORMAL", b.addAccessor(normals, 5126, "VEC3")},
                               {"TEXCOORD_0", b.addAccessor(uvs, 5126, "VEC2")}};
    primitive["indices"] = b.addAccessor(sphere.indices, 5125, "SCALAR");
    primitive["material"] = 0;
    b.doc["meshes"] = nlohmann::json::array();
    b.doc["meshes"][0]["primitives"] = {primitive};
    std::vector<std::uint8_t> checker;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            checker.insert(checker.end(),
                           (x / 4 + y / 4) % 2
                               ? std::initializer_list<std::uint8_t>{255, 200, 120, 255}
                               : std::initializer_list<std::uint8_t>{120, 190, 255, 255});
    const std::vector<std::uint8_t> png = makePng(16, 16, checker);
    b.doc["images"] = {
        {{"bufferView", b.addView(png.data(), png.size())}, {"mimeType", "image/png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    nlohmann::json base = {{"index", 0}};
    base["extensions"]["KHR_texture_transform"] = {{"offset", {0.1, 0.0}}, {"scale", {2.0, 1.0}}};
    nlohmann::json glass = {{"name", "glass"}};
    glass["pbrMetallicRoughness"] = {
        {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}, {"baseColorTexture", base}};
    glass["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = 1.0;
    glass["extensions"]["KHR_materials_ior"]["ior"] = 1.2;
    b.doc["materials"] = {glass};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "spot"},
         {"intensity", 8.0},
         {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.6}}}}};
    b.doc["nodes"] = {{{"name", "sphere"}, {"mesh", 0}},
                      {{"name", "lamp"},
                       {"translation", {0.6, 0.8, 2.5}},
                       {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}};
    b.doc["scenes"] = {{{"nodes", {0, 1}}}};
    b.doc["scene"] = 0;
    const int times = b.addAccessor(std::vector<float>{0.0f, 1.0f}, 5126, "SCALAR");
    b.doc["accessors"][times]["min"] = {0.0};
    b.doc["accessors"][times]["max"] = {1.0};
    nlohmann::json samplers = nlohmann::json::array(), channels = nlohmann::json::array();
    const auto play = [&](const std::string& pointer, const std::vector<float>& keys,
                          const char* type) {
        channels.push_back(
            {{"sampler", samplers.size()},
             {"target",
              {{"path", "pointer"},
               {"extensions", {{"KHR_animation_pointer", {{"pointer", pointer}}}}}}}});
        samplers.push_back({{"input", times}, {"output", b.addAccessor(keys, 5126, type)}});
    };
    play("/materials/0/extensions/KHR_materials_ior/ior", {1.2f, 1.8f}, "SCALAR");
    play("/materials/0/extensions/KHR_materials_transmission/transmissionFactor", {1.0f, 0.6f},
         "SCALAR");
    play("/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/"
         "offset",
         {0.1f, 0.0f, 0.35f, 0.2f}, "VEC2");
    play("/extensions/KHR_lights_punctual/lights/0/intensity", {8.0f, 30.0f}, "SCALAR");
    play("/extensions/KHR_lights_punctual/lights/0/color", {1.0f, 1.0f, 1.0f, 1.0f, 0.55f, 0.2f},
         "VEC3");
    b.doc["animations"] = {{{"name", "pointers"}, {"samplers", samplers}, {"channels", channels}}};
    b.doc["extensionsUsed"] = {"KHR_animation_pointer", "KHR_lights_punctual",
                               "KHR_texture_transform", "KHR_materials_transmission",
                               "KHR_materials_ior"};
    return b;
}

GltfBuilder instancedTwoJointModel() {
    GltfBuilder b = twoJointModel();
    const std::vector<float> translations = {0, 0, 0, 2, 0, 0, 0, 0, 3};
    const std::vector<float> rotations = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.7071068f, 0, 0.7071068f};
    const std::vector<float> scales = {1, 1, 1, 1, 1, 1, 2, 2, 2};
    b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
        {"TRANSLATION", b.addAccessor(translations, 5126, "VEC3")},
        {"ROTATION", b.addAccessor(rotations, 5126, "VEC4")},
        {"SCALE", b.addAccessor(scales, 5126, "VEC3")}};
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    return b;
}

std::vector<std::uint8_t> makePng(int width, int height, std::vector<std::uint8_t> rgba) {
    std::vector<std::uint8_t> pixels;
    if (rgba.size() == std::size_t(width) * std::size_t(height) * 4u)
        pixels = std::move(rgba);
    else
        for (int i = 0; i < width * height; ++i)
            pixels.insert(pixels.end(), rgba.begin(), rgba.end());
    std::vector<std::uint8_t> png;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<std::uint8_t>*>(context);
            out->insert(out->end(), static_cast<std::uint8_t*>(data),
                        static_cast<std::uint8_t*>(data) + size);
        },
        &png, width, height, 4, pixels.data(), width * 4);
    return png;
}

void writeHdr(const std::filesystem::path& path, int width, int height, float r, float g, float b) {
    asset::HdrImage image{width, height, {}};
    for (int i = 0; i < width * height; ++i)
        image.rgb.insert(image.rgb.end(), {r, g, b});
    const std::vector<std::uint8_t> bytes = asset::encodeHdr(image);
    writeBytes(path, std::string(bytes.begin(), bytes.end()));
}

int runCommand(const std::string& command, std::string* output) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe)
        return -1;
    std::array<char, 4096> buffer{};
    std::string text;
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        text.append(buffer.data(), n);
    const int status = pclose(pipe);
    if (output)
        *output = text;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace test
