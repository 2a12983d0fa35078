// One test per load error: each case breaks the valid two-joint model in one way, saves it, and
// checks the load fails with a message naming the function, the file and the element.
#include "support/TestSupport.h"

#include "engine/asset/GltfLoader.h"
#include "engine/core/Limits.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

namespace {

using Json = nlohmann::json;

struct MalformedCase {
    const char* name;
    std::function<void(test::GltfBuilder&)> breakIt;
    std::vector<std::string> expected; ///< substrings the message must contain
    test::GltfFormat format = test::GltfFormat::DataUri;
};

/** Embeds `bytes` as the model's only image (a PNG by its MIME type). */
void addImage(test::GltfBuilder& b, const std::vector<std::uint8_t>& bytes) {
    const int view = b.addView(bytes.data(), bytes.size());
    b.doc["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
}

/** A 4x34 PNG whose 12-byte zlib stream never ends (found by fuzz_image: stb's inflater kept
 *  doubling its buffer past 1.6 GB on it). */
std::vector<std::uint8_t> endlessPng() {
    return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d,
            0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x22,
            0x08, 0x06, 0x00, 0x00, 0x00, 0x7f, 0xa8, 0x00, 0x00, 0x63, 0x00, 0x7d,
            0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x3f, 0xcd, 0x46, 0x16,
            0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
}

/** A valid 64x64 PNG whose IDAT chunk is cut to half its zlib data (lengths kept consistent). */
std::vector<std::uint8_t> truncatedIdatPng() {
    std::vector<std::uint8_t> png(test::makePng(64, 64, {10, 20, 30, 255}));
    const std::string text(png.begin(), png.end());
    const std::size_t type = text.find("IDAT");
    const std::size_t at = type - 4;
    const std::uint32_t length = std::uint32_t(png[at]) << 24 | std::uint32_t(png[at + 1]) << 16 |
                                 std::uint32_t(png[at + 2]) << 8 | png[at + 3];
    const std::uint32_t kept = length / 2;
    for (int i = 0; i < 4; ++i)
        png[at + std::size_t(i)] = std::uint8_t(kept >> (24 - 8 * i));
    png.erase(png.begin() + std::ptrdiff_t(type + 4 + kept),
              png.begin() + std::ptrdiff_t(type + 4 + length));
    return png;
}

/** A valid 1x1 PNG whose header then claims `width` x `height`. */
std::vector<std::uint8_t> pngClaiming(std::uint32_t width, std::uint32_t height) {
    std::vector<std::uint8_t> png = test::makePng(1, 1, {1, 2, 3, 255});
    for (int i = 0; i < 4; ++i) {
        png[16 + std::size_t(i)] = std::uint8_t(width >> (24 - 8 * i));
        png[20 + std::size_t(i)] = std::uint8_t(height >> (24 - 8 * i));
    }
    return png;
}

const std::vector<MalformedCase>& cases() {
    static const std::vector<MalformedCase> all = {
        {"SceneNodeOutOfRange",
         [](auto& b) { b.doc["scenes"][0]["nodes"].push_back(99); },
         {"scene 0", "node 99", "file has 3 nodes"}},
        {"ChildNodeOutOfRange",
         [](auto& b) { b.doc["nodes"][1]["children"] = {7}; },
         {"node 1", "node 7", "3 nodes"}},
        {"MeshOutOfRange",
         [](auto& b) { b.doc["nodes"][0]["mesh"] = 5; },
         {"node 0", "mesh 5", "1 meshes"}},
        {"AccessorOutOfRange",
         [](auto& b) { b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 42; },
         {"accessor 42"}},
        {"BufferViewOutOfRange",
         [](auto& b) { b.doc["accessors"][0]["bufferView"] = 40; },
         {"bufferView 40"}},
        {"BufferOutOfRange", [](auto& b) { b.doc["bufferViews"][0]["buffer"] = 3; }, {"buffer"}},
        {"MaterialOutOfRange",
         [](auto& b) { b.doc["meshes"][0]["primitives"][0]["material"] = 2; },
         {"mesh 0 primitive 0", "material 2"}},
        {"TextureOutOfRange",
         [](auto& b) {
             b.doc["materials"] = {
                 {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 4}}}}}}};
             b.doc["meshes"][0]["primitives"][0]["material"] = 0;
         },
         {"material 0", "texture 4"}},
        {"SkinJointNodeOutOfRange",
         [](auto& b) { b.doc["skins"][0]["joints"][1] = 91; },
         {"skin 0: joint 1 references node 91, file has 3 nodes"}},
        {"JointIndexPastSkin",
         [](auto& b) {
             // Vertex 2's first influence (weight 1) now names joint 5 of a 2-joint skin.
             const int view = b.doc["accessors"][2]["bufferView"];
             const std::size_t offset = b.doc["bufferViews"][view]["byteOffset"];
             const std::uint16_t bad = 5;
             std::memcpy(b.bin.data() + offset + 2 * 8, &bad, 2);
         },
         {"JOINTS_0 of vertex 2 references joint 5", "skin 0 has 2 joints"}},
        {"AccessorPastBufferView",
         [](auto& b) { b.doc["accessors"][0]["count"] = 60; },
         {"accessor 0", "runs past the end of bufferView"}},
        {"BufferViewPastBuffer",
         [](auto& b) { b.doc["bufferViews"][0]["byteLength"] = 100000; },
         {"bufferView 0", "past the end of buffer 0"}},
        {"StrideSmallerThanElement",
         [](auto& b) { b.doc["bufferViews"][0]["byteStride"] = 4; },
         {"byteStride 4"}},
        {"IndexPastVertexCount",
         [](auto& b) {
             const int view = b.doc["accessors"][4]["bufferView"];
             const std::size_t offset = b.doc["bufferViews"][view]["byteOffset"];
             const std::uint16_t bad = 60;
             std::memcpy(b.bin.data() + offset + 2, &bad, 2);
         },
         {"mesh 0 primitive 0 index 1 is 60", "6 vertices"}},
        {"NodeCycle",
         [](auto& b) {
             b.doc["nodes"][2]["children"] = {1};
             b.doc["scenes"][0]["nodes"] = {0};
         },
         {"cycle"}},
        {"NodeWithTwoParents",
         [](auto& b) { b.doc["nodes"][0]["children"] = {2}; },
         {"node 2 has two parents"}},
        {"AllZeroWeights",
         [](auto& b) {
             const int view = b.doc["accessors"][3]["bufferView"];
             const std::size_t offset = b.doc["bufferViews"][view]["byteOffset"];
             std::memset(b.bin.data() + offset + 16 * 3, 0, 16); // vertex 3
         },
         {"vertex 3 has all-zero or NaN skin weights"}},
        {"NaNWeights",
         [](auto& b) {
             const int view = b.doc["accessors"][3]["bufferView"];
             const std::size_t offset = b.doc["bufferViews"][view]["byteOffset"];
             const float nan = std::numeric_limits<float>::quiet_NaN();
             std::memcpy(b.bin.data() + offset + 16 * 4, &nan, 4); // vertex 4
         },
         {"WEIGHTS_0", "element 4 is not finite"}},
        {"UnsupportedRequiredExtension", // geometry the engine cannot read
         [](auto& b) {
             b.doc["extensionsUsed"] = {"KHR_gaussian_splatting"};
             b.doc["extensionsRequired"] = {"KHR_gaussian_splatting"};
         },
         {"extensionsRequired lists KHR_gaussian_splatting"}},
        {"TooManyInfluenceSets",
         [](auto& b) {
             auto& attributes = b.doc["meshes"][0]["primitives"][0]["attributes"];
             attributes["JOINTS_1"] = attributes["JOINTS_0"];
             attributes["WEIGHTS_1"] = attributes["WEIGHTS_0"];
             attributes["JOINTS_2"] = attributes["JOINTS_0"];
             attributes["WEIGHTS_2"] = attributes["WEIGHTS_0"];
         },
         {"JOINTS_2", "over the engine's limit"}},
        {"AbsurdSparseCount",
         [](auto& b) {
             // 2^27 VEC3 elements with no bufferView: 1.5 GiB from a file of a few KB.
             b.doc["accessors"].push_back(
                 {{"componentType", 5126},
                  {"count", 134217728},
                  {"type", "VEC3"},
                  {"sparse",
                   {{"count", 1},
                    {"indices", {{"bufferView", 4}, {"componentType", 5123}}},
                    {"values", {{"bufferView", 0}}}}}});
             b.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = 10;
         },
         {"accessor 10", "more memory than a file of this size can justify"}},
        {"AbsurdAccessorCount",
         [](auto& b) { b.doc["accessors"][0]["count"] = 4000000000ull; },
         {"accessor 0", "over the limit"}},
        {"DecreasingKeyTimes",
         [](auto& b) {
             const int view = b.doc["accessors"][7]["bufferView"];
             const std::size_t offset = b.doc["bufferViews"][view]["byteOffset"];
             const float t = -1.0f;
             std::memcpy(b.bin.data() + offset + 4, &t, 4);
         },
         {"animation 0 sampler 0 input time 1 decreases"}},
        {"AnimationTargetOutOfRange",
         [](auto& b) { b.doc["animations"][0]["channels"][0]["target"]["node"] = 17; },
         {"animation 0 channel 0 target", "node 17"}},
        {"WeightsChannelOnNodeWithoutMorphs",
         [](auto& b) { b.doc["animations"][0]["channels"][1]["target"]["node"] = 1; },
         {"animates the weights of node 1, which has no morph targets"}},
        {"MorphWeightCountMismatch",
         [](auto& b) {
             b.doc["meshes"][0]["weights"] = {0.0, 1.0};
         },
         {"mesh 0 has 2 default weights for 1 morph targets"}},
        {"MissingPosition",
         [](auto& b) { b.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); },
         {"mesh 0 primitive 0 has no POSITION"}},
        {"UndefinedPrimitiveMode",
         [](auto& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 9; },
         {"mesh 0 primitive 0 has mode 9, which glTF does not define"}},
        {"AnotherMajorVersion",
         [](auto& b) { b.doc["asset"]["version"] = "3.0"; },
         {"asset.version 3.0: glTF 3 is not glTF 2"}},
        {"NewerMinVersion",
         [](auto& b) { b.doc["asset"]["minVersion"] = "2.1"; },
         {"asset.minVersion 2.1: the file needs a glTF newer than 2.0"}},
        {"InverseBindTooShort",
         [](auto& b) { b.doc["accessors"][6]["count"] = 1; },
         {"skin 0 inverseBindMatrices has 1 matrices for 2 joints"}},
        {"ImageNotDecodable",
         [](auto& b) {
             // A PNG signature, then no valid chunk.
             addImage(b,
                      {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 'n', 'o', 't', ' ', 'a', 'n'});
         },
         {"image 0 could not be decoded"},
         test::GltfFormat::Glb},
        {"ImageNeitherPngNorJpeg",
         [](auto& b) {
             addImage(b, {'P', '5', '\n', '5', '5', '\n', '6', '7', '6', '7'});
         },
         {"image 0 is neither PNG, JPEG, WebP nor KTX2"},
         test::GltfFormat::Glb},
        {"ImageZlibStreamNeverEnds",
         [](auto& b) { addImage(b, endlessPng()); },
         {"image 0: a PNG chunk runs past the end of the data"},
         test::GltfFormat::Glb},
        {"ImageZlibStreamCutShort",
         [](auto& b) { addImage(b, truncatedIdatPng()); },
         {"image 0: PNG image data is not a complete zlib stream"},
         test::GltfFormat::Glb},
        {"ImageHeaderClaimsGigapixels",
         [](auto& b) { addImage(b, pngClaiming(16000, 16000)); },
         {"image 0: 16000x16000 pixels cannot come from"},
         test::GltfFormat::Glb},
        {"ImageHeaderOverTextureLimit", // stb's probe once made it "unknown image type"
         [](auto& b) { addImage(b, pngClaiming(60000, 60000)); },
         {"image 0 is 60000x60000, over the limit of 16384"},
         test::GltfFormat::Glb},
        {"ImageOverTextureLimit",
         [](auto& b) {
             addImage(b, test::makePng(16385, 1, {9, 9, 9, 255}));
         },
         {"image 0 is 16385x1, over the limit of 16384"},
         test::GltfFormat::Glb},
        {"TooManyMorphTargets",
         [](auto& b) {
             auto& targets = b.doc["meshes"][0]["primitives"][0]["targets"];
             while (targets.size() <= core::limits::kMaxMorphTargets)
                 targets.push_back(targets[0]);
             b.doc["meshes"][0].erase("weights");
         },
         {"mesh 0 primitive 0", "4097 morph targets", "4096"}},
        {"ByteTexcoordWithoutQuantization", // read as it is, it tiled the texture 127 times
         [](auto& b) {
             const std::vector<std::int8_t> uv = {0, 127, 127, 0, 64, 64, 0, 0, 127, 127, 64, 0};
             b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
                 b.addAccessor(uv, 5120, "VEC2", false);
         },
         {"mesh 0 primitive 0 TEXCOORD_0 (accessor ",
          "is BYTE, not normalized, which glTF does "
          "not allow for TEXCOORD_0 unless the file uses KHR_mesh_quantization"}},
        {"JointsNormalized",
         [](auto& b) {
             const int joints = b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"];
             b.doc["accessors"][std::size_t(joints)]["normalized"] = true;
         },
         {"mesh 0 primitive 0 JOINTS_0 (accessor ", ", normalized, which glTF does not allow for "
                                                    "JOINTS_0"}},
        {"BadIor",
         [](auto& b) {
             b.doc["materials"] = {{{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}}};
         },
         {"material 0 ior"}},
        {"ClearcoatOverOne",
         [](auto& b) {
             b.doc["materials"] = {
                 {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 2.0}}}}}}};
         },
         {"material 0 clearcoatFactor is 2.000000, outside [0.000000, 1.000000]"}},
        {"SheenTextureMissing",
         [](auto& b) {
             b.doc["materials"] = {
                 {{"extensions",
                   {{"KHR_materials_sheen", {{"sheenColorTexture", {{"index", 4}}}}}}}}};
         },
         {"material 0 sheenColorTexture references texture 4, file has 0 textures"}},
        {"IridescenceIorBelowOne",
         [](auto& b) {
             b.doc["materials"] = {
                 {{"extensions", {{"KHR_materials_iridescence", {{"iridescenceIor", 0.5}}}}}}};
         },
         {"material 0 iridescenceIor is 0.500000, outside [1.000000"}},
        {"LightOfAnUnknownType",
         [](auto& b) {
             b.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "area"}}}}}}};
         },
         {"KHR_lights_punctual light 0 type \"area\" is not directional, point or spot"}},
        {"SpotConeInsideOut",
         [](auto& b) {
             b.doc["extensions"] = {
                 {"KHR_lights_punctual",
                  {{"lights",
                    {{{"type", "spot"},
                      {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.2}}}}}}}}};
         },
         {"KHR_lights_punctual light 0 spot cone angles", "must satisfy 0 <= inner < outer"}},
        {"NodeNamesAMissingLight",
         [](auto& b) {
             b.doc["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 2}}}};
         },
         {"node 0 KHR_lights_punctual light 2 is not a light of the file's 0"}},
    };
    return all;
}

void PrintTo(const MalformedCase& c, std::ostream* os) {
    *os << c.name;
}

class Malformed : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(Malformed, FailsNamingFileAndElement) {
    const MalformedCase& c = GetParam();
    test::TempDir dir;
    test::GltfBuilder builder = test::twoJointModel();
    c.breakIt(builder);
    const auto path = builder.save(dir.path(), c.name, c.format);
    // scripts/fuzz seeds the glTF fuzzer with these files (external .bin files aside).
    if (const char* seeds = std::getenv("GLASS_FUZZ_SEED_DIR"); seeds && *seeds)
        std::filesystem::copy_file(path, std::filesystem::path(seeds) / path.filename(),
                                   std::filesystem::copy_options::overwrite_existing);
    const auto model = asset::loadGltf(path);
    ASSERT_FALSE(model.ok()) << c.name << " loaded but should not";
    const std::string& message = model.error().message;
    EXPECT_NE(message.find("asset::loadGltf(): " + path.filename().string() + ": "),
              std::string::npos)
        << message;
    for (const std::string& part : c.expected)
        EXPECT_NE(message.find(part), std::string::npos)
            << "missing '" << part << "' in: " << message;
}

INSTANTIATE_TEST_SUITE_P(Asset, Malformed, ::testing::ValuesIn(cases()),
                         [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(Malformed, ValidBaseModelLoadsInEveryContainer) {
    test::TempDir dir;
    const test::GltfBuilder builder = test::twoJointModel();
    for (auto format :
         {test::GltfFormat::DataUri, test::GltfFormat::ExternalBin, test::GltfFormat::Glb}) {
        const auto model = asset::loadGltf(builder.save(dir.path(), "valid", format));
        ASSERT_TRUE(model.ok()) << model.error().message;
        EXPECT_EQ(model->meshes[0].primitives[0].vertexCount(), 6u);
        EXPECT_EQ(model->skins[0].joints.size(), 2u);
    }
}

// What the engine can do without loads, with a warning naming it.
TEST(Degrade, PointsAndLinesPrimitivesAreLeftOutWithAWarning) {
    test::TempDir dir;
    test::GltfBuilder builder = test::twoJointModel();
    auto& primitives = builder.doc["meshes"][0]["primitives"];
    for (int mode : {0, 1, 3}) { // POINTS, LINES, LINE_STRIP beside the triangles
        nlohmann::json other = primitives[0];
        other["mode"] = mode;
        primitives.push_back(other);
    }
    const auto model = asset::loadGltf(builder.save(dir.path(), "modes"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->meshes[0].primitives.size(), 1u) << "the triangles stay";
    ASSERT_EQ(model->warnings.size(), 3u);
    EXPECT_NE(model->warnings[0].find("mesh 0 'strip' primitive 1 has mode POINTS: skipped"),
              std::string::npos)
        << model->warnings[0];
    EXPECT_NE(model->warnings[2].find("primitive 3 has mode LINE_STRIP"), std::string::npos);
    EXPECT_EQ(model->meshes[0].morphTargetCount(), 1u);
}

TEST(Degrade, ARequiredMaterialExtensionTheEngineLacksIsAWarning) {
    // A material extension leaves the geometry whole: the file loads without it, whether it is
    // required or only used.
    test::TempDir dir;
    test::GltfBuilder builder = test::twoJointModel();
    builder.doc["extensionsUsed"] =
        builder.doc["extensionsRequired"] = {"KHR_materials_diffuse_transmission"};
    const auto model = asset::loadGltf(builder.save(dir.path(), "diffuse"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->warnings.size(), 1u);
    EXPECT_EQ(model->warnings[0], "extensionsUsed lists KHR_materials_diffuse_transmission, which "
                                  "this engine does not implement: loaded without it");
}

TEST(Degrade, BoundsThatAreNotTheDataAreNamed) {
    // The validator's ACCESSOR_MAX_MISMATCH: the data is what the engine reads, so the file
    // loads, with a warning naming the accessor and both bounds.
    test::TempDir dir;
    test::GltfBuilder builder = test::twoJointModel();
    const int position = builder.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    auto& accessor = builder.doc["accessors"][std::size_t(position)];
    ASSERT_TRUE(accessor.contains("max"));
    accessor["max"][1] = accessor["max"][1].get<double>() + 0.5;
    const auto model = asset::loadGltf(builder.save(dir.path(), "bounds"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->warnings.size(), 1u);
    EXPECT_NE(model->warnings[0].find("mesh 0 primitive 0 POSITION (accessor " +
                                      std::to_string(position) + ") declares max ["),
              std::string::npos)
        << model->warnings[0];
    EXPECT_NE(model->warnings[0].find("its data's is ["), std::string::npos) << model->warnings[0];
    const auto clean = asset::loadGltf(test::twoJointModel().save(dir.path(), "clean"));
    ASSERT_TRUE(clean.ok());
    EXPECT_TRUE(clean->warnings.empty());
}

/** One triangle with quantized positions (KHR_mesh_quantization), SHORT, normalized or not,
 *  its bounds declared as the data's raw integers. */
test::GltfBuilder quantizedTriangle(bool normalized) {
    test::GltfBuilder b;
    const std::vector<std::int16_t> positions = {0, 0, 0, 32767, 0, -32768, 0, 16384, 0};
    const int pos = b.addAccessor(positions, 5122, "VEC3", normalized);
    b.doc["accessors"][std::size_t(pos)]["min"] = {0, 0, -32768};
    b.doc["accessors"][std::size_t(pos)]["max"] = {32767, 16384, 0};
    b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}}}}}};
    b.doc["nodes"] = {{{"mesh", 0}}};
    b.doc["scenes"] = {{{"nodes", {0}}}};
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    return b;
}

TEST(Degrade, QuantizedPositionsWhoseDataPassesTheirBoundsAreNamed) {
    // The validator's ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND: a normalized accessor's bounds are its
    // raw integers (-32768 is -1, as -32767 is), and the data past them is named.
    test::TempDir dir;
    for (bool normalized : {false, true}) {
        const auto clean = asset::loadGltf(quantizedTriangle(normalized).save(dir.path(), "q"));
        ASSERT_TRUE(clean.ok()) << clean.error().message;
        EXPECT_TRUE(clean->warnings.empty()) << clean->warnings[0];
        test::GltfBuilder past = quantizedTriangle(normalized);
        past.doc["accessors"][0]["max"] = {30000, 16384, 0};
        const auto model = asset::loadGltf(past.save(dir.path(), "past"));
        ASSERT_TRUE(model.ok()) << model.error().message;
        ASSERT_EQ(model->warnings.size(), 1u) << (normalized ? "normalized" : "not normalized");
        EXPECT_NE(model->warnings[0].find("mesh 0 primitive 0 POSITION (accessor 0) declares max "
                                          "[30000, 16384, 0], its data's is [32767, 16384, 0]"),
                  std::string::npos)
            << model->warnings[0];
    }
}

TEST(Degrade, AnIntegerAccessorsFractionalBoundsAreNamed) {
    // The validator's ARRAY_TYPE_MISMATCH: bounds of integers with fractions. The engine reads
    // bounds from the data, so the file loads with one warning per bound.
    test::TempDir dir;
    test::GltfBuilder b = quantizedTriangle(true);
    b.doc["accessors"][0]["min"] = {-0.5, 0, -32768};
    b.doc["accessors"][0]["max"] = {32767.5, 16384, 0.25};
    const auto model = asset::loadGltf(b.save(dir.path(), "fractional"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->warnings.size(), 2u);
    EXPECT_EQ(model->warnings[0],
              "accessor 0 (SHORT) declares min [-0.5, 0, -32768], but an integer accessor's "
              "bounds are whole numbers: its data's own are used");
    EXPECT_NE(model->warnings[1].find("accessor 0 (SHORT) declares max [32767.5, 16384, 0.25]"),
              std::string::npos)
        << model->warnings[1];
}

TEST(Degrade, ExtensionsUsedButNotRequiredLoadWithAWarningAndALater2xLoads) {
    test::TempDir dir;
    test::GltfBuilder builder = test::twoJointModel();
    builder.doc["extensionsUsed"] = {"KHR_materials_diffuse_transmission", "KHR_materials_ior"};
    builder.doc["asset"]["version"] = "2.1";
    const auto model = asset::loadGltf(builder.save(dir.path(), "used"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->warnings.size(), 1u) << "KHR_materials_ior is implemented";
    EXPECT_EQ(model->warnings[0], "extensionsUsed lists KHR_materials_diffuse_transmission, "
                                  "which this engine does not implement: loaded without it");
    const auto clean = asset::loadGltf(test::twoJointModel().save(dir.path(), "clean"));
    ASSERT_TRUE(clean.ok());
    EXPECT_TRUE(clean->warnings.empty());
}

TEST(Malformed, MissingExternalBuffer) {
    test::TempDir dir;
    const auto path =
        test::twoJointModel().save(dir.path(), "external", test::GltfFormat::ExternalBin);
    std::filesystem::remove(dir / "external.bin");
    const auto model = asset::loadGltf(path);
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("external.gltf"), std::string::npos)
        << model.error().message;
    EXPECT_NE(model.error().message.find("external.bin"), std::string::npos)
        << model.error().message;
}

TEST(Malformed, MissingModelFile) {
    test::TempDir dir;
    const auto model = asset::loadGltf(dir / "nothing.glb");
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("nothing.glb"), std::string::npos);
}

std::string readAll(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeAll(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

TEST(Malformed, TruncatedGlb) {
    test::TempDir dir;
    const auto path = test::twoJointModel().save(dir.path(), "truncated", test::GltfFormat::Glb);
    const std::string bytes = readAll(path);
    for (std::size_t keep : {std::size_t(6), std::size_t(30), bytes.size() / 2, bytes.size() - 4}) {
        writeAll(path, bytes.substr(0, keep));
        const auto model = asset::loadGltf(path);
        ASSERT_FALSE(model.ok()) << "kept " << keep << " of " << bytes.size() << " bytes";
        EXPECT_NE(model.error().message.find("truncated.glb"), std::string::npos);
    }
}

TEST(Malformed, CorruptGlbHeader) {
    test::TempDir dir;
    const auto path = test::twoJointModel().save(dir.path(), "corrupt", test::GltfFormat::Glb);
    std::string bytes = readAll(path);
    bytes[4] = 7; // version 7
    writeAll(path, bytes);
    auto model = asset::loadGltf(path);
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("corrupt.glb"), std::string::npos);

    bytes = readAll(path);
    bytes[4] = 2;
    bytes[12] = char(0xFF); // JSON chunk length far past the file
    bytes[13] = char(0xFF);
    writeAll(path, bytes);
    model = asset::loadGltf(path);
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("corrupt.glb"), std::string::npos);
}

TEST(Malformed, NotJson) {
    test::TempDir dir;
    writeAll(dir / "garbage.gltf", "{ this is not json");
    const auto model = asset::loadGltf(dir / "garbage.gltf");
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("garbage.gltf"), std::string::npos);
}

} // namespace
