// glTF as files are shipped: meshopt- and Draco-compressed geometry, WebP and KTX2 images,
// texture transforms, unlit and specular-glossiness materials. Each file is made here from the
// two-joint model with the real encoders (libmeshoptimizer, libdraco, libwebp), then loaded whole
// or broken in one way; sizes a stream claims are refused before anything is allocated.
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/deform/CpuDeformer.h"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

#include <glm/gtc/matrix_transform.hpp>

namespace {

using Json = nlohmann::json;

/** The two-joint model's float data of accessor `index`, as the builder wrote it. */
std::vector<float> floatsOf(const test::GltfBuilder& b, int index) {
    const Json& accessor = b.doc["accessors"][std::size_t(index)];
    const Json& view = b.doc["bufferViews"][accessor["bufferView"].get<std::size_t>()];
    const std::size_t offset = view.value("byteOffset", 0);
    const std::size_t count = accessor["count"].get<std::size_t>() *
                              std::size_t(test::GltfBuilder::componentsOf(accessor["type"]));
    std::vector<float> out(count);
    std::memcpy(out.data(), b.bin.data() + offset, count * sizeof(float));
    return out;
}

/** The model's positions, deformed at `time` of clip 0, in world space. */
std::vector<glm::dvec3> deformed(const scene::Model& model, double time) {
    std::vector<glm::dvec3> out;
    for (const auto& instance : deform::deformScene(model, anim::evaluate(model, 0, time)))
        for (const auto& primitive : instance.primitives)
            for (const glm::dvec3& p : primitive.positions)
                out.push_back(glm::dvec3(instance.meshToWorld * glm::dvec4(p, 1.0)));
    return out;
}

// --- EXT_meshopt_compression ------------------------------------------------------------------

/** The two-joint model with its POSITION view meshopt-compressed into buffer 0 and the view
 *  itself moved to a fallback buffer with no data, as gltfpack -cf writes it. */
test::GltfBuilder meshoptModel(const char* extension = "EXT_meshopt_compression") {
    test::GltfBuilder b = test::twoJointModel();
    const int position = b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    const std::vector<float> positions = floatsOf(b, position);
    std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(6, 12));
    encoded.resize(
        meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), positions.data(), 6, 12));
    const int compressed = b.addView(encoded.data(), encoded.size());
    const Json compressedView = b.doc["bufferViews"][std::size_t(compressed)];
    b.doc["buffers"] = {{},
                        {{"byteLength", 72}, {"extensions", {{extension, {{"fallback", true}}}}}}};
    Json& view = b.doc["bufferViews"][b.doc["accessors"][position]["bufferView"].get<int>()];
    view = {{"buffer", 1},
            {"byteOffset", 0},
            {"byteLength", 72},
            {"byteStride", 12},
            {"extensions",
             {{extension,
               {{"buffer", 0},
                {"byteOffset", compressedView.value("byteOffset", 0)},
                {"byteLength", encoded.size()},
                {"byteStride", 12},
                {"count", 6},
                {"mode", "ATTRIBUTES"}}}}}};
    b.doc["extensionsUsed"] = {extension};
    return b;
}

Json& meshoptOf(test::GltfBuilder& b) {
    const int position = b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    return b.doc["bufferViews"][b.doc["accessors"][position]["bufferView"].get<int>()]["extensions"]
                ["EXT_meshopt_compression"];
}

TEST(Meshopt, CompressedViewWithAFallbackBufferDecodesExactlyInEveryContainer) {
    test::TempDir dir;
    const auto plain = asset::loadGltf(test::twoJointModel().save(dir.path(), "plain"));
    ASSERT_TRUE(plain.ok());
    for (const char* extension : {"EXT_meshopt_compression", "KHR_meshopt_compression"})
        for (auto format : {test::GltfFormat::DataUri, test::GltfFormat::Glb}) {
            const auto model =
                asset::loadGltf(meshoptModel(extension).save(dir.path(), "m", format));
            ASSERT_TRUE(model.ok()) << model.error().message;
            EXPECT_TRUE(model->warnings.empty());
            for (double t : {0.0, 0.5, 1.0})
                EXPECT_EQ(deformed(*model, t), deformed(*plain, t)) << extension;
        }
}

TEST(Meshopt, ClaimsTheCodecCannotProduceAreRefusedBeforeDecoding) {
    test::TempDir dir;
    test::GltfBuilder b = meshoptModel();
    meshoptOf(b)["count"] = 1 << 26; // 768 MiB from a few dozen bytes
    const auto model = asset::loadGltf(b.save(dir.path(), "huge"));
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("huge.gltf: bufferView 0 EXT_meshopt_compression claims "
                                         "805306368 decoded bytes from"),
              std::string::npos)
        << model.error().message;
}

TEST(Meshopt, MalformedExtensionsFailNamingTheView) {
    test::TempDir dir;
    const std::pair<std::function<void(Json&)>, std::string> cases[] = {
        {[](Json& e) { e["count"] = 7; }, "but the bufferView's byteLength is 72"},
        {[](Json& e) { e["byteLength"] = 3; }, "stream is corrupt (meshopt error"},
        {[](Json& e) { e["byteStride"] = 6; }, "byteStride 6 must be a multiple of 4"},
        {[](Json& e) { e["mode"] = "POINTS"; }, "mode 'POINTS' is not ATTRIBUTES"},
        {[](Json& e) { e["filter"] = "QUATERNION"; }, "QUATERNION filter needs byteStride 8"},
        {[](Json& e) { e["buffer"] = 9; }, "references buffer 9"},
        {[](Json& e) { e["byteOffset"] = 1 << 20; }, "runs past the end of buffer 0"}};
    for (const auto& [breakIt, expected] : cases) {
        test::GltfBuilder b = meshoptModel();
        breakIt(meshoptOf(b));
        const auto model = asset::loadGltf(b.save(dir.path(), "broken"));
        ASSERT_FALSE(model.ok()) << expected;
        EXPECT_NE(model.error().message.find("broken.gltf: bufferView 0 EXT_meshopt_compression"),
                  std::string::npos)
            << model.error().message;
        EXPECT_NE(model.error().message.find(expected), std::string::npos) << model.error().message;
    }
}

TEST(Meshopt, AFallbackBufferIsNamedWhereItWouldBeRead) {
    test::TempDir dir;
    // A view that is not compressed would read the fallback buffer, whose data is never loaded.
    test::GltfBuilder plainView = meshoptModel();
    const int position = plainView.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    plainView.doc["bufferViews"][plainView.doc["accessors"][position]["bufferView"].get<int>()]
        .erase("extensions");
    const auto read = asset::loadGltf(plainView.save(dir.path(), "plainview"));
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("plainview.gltf: bufferView 0 reads buffer 1, a meshopt "
                                        "fallback buffer (72 bytes declared, never loaded)"),
              std::string::npos)
        << read.error().message;
    // A compressed view whose stream is in the fallback buffer, which holds no data.
    for (const char* extension : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
        test::GltfBuilder source = meshoptModel(extension);
        const int view = source.doc["accessors"][position]["bufferView"].get<int>();
        source.doc["bufferViews"][std::size_t(view)]["extensions"][extension]["buffer"] = 1;
        const auto model = asset::loadGltf(source.save(dir.path(), "source"));
        ASSERT_FALSE(model.ok());
        EXPECT_NE(model.error().message.find(
                      "source.gltf: bufferView " + std::to_string(view) + " " + extension +
                      " takes its compressed stream from buffer 1, a meshopt fallback buffer (72 "
                      "bytes declared, never loaded)"),
                  std::string::npos)
            << model.error().message;
    }
    // A buffer with neither data nor the fallback flag (the extension lost by an exporter).
    test::GltfBuilder lost = meshoptModel();
    lost.doc["buffers"][1].erase("extensions");
    for (auto format : {test::GltfFormat::DataUri, test::GltfFormat::Glb}) {
        const auto model = asset::loadGltf(lost.save(dir.path(), "lost", format));
        ASSERT_FALSE(model.ok());
        EXPECT_NE(model.error().message.find("buffer 1 has no uri: only a GLB's first buffer"),
                  std::string::npos)
            << model.error().message;
    }
}

TEST(Meshopt, AVertexCodecNewerThanTheLibraryIsNamed) {
    test::TempDir dir;
    test::GltfBuilder b = meshoptModel();
    b.bin[meshoptOf(b).value("byteOffset", std::size_t(0))] = 0xA1; // version 1's header byte
    const auto model = asset::loadGltf(b.save(dir.path(), "v1"));
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("the stream is in version 1 of meshopt's vertex codec"),
              std::string::npos)
        << model.error().message;
}

// --- KHR_draco_mesh_compression -----------------------------------------------------------

/** The two-joint model's triangles, positions, joints and weights Draco-encoded (sequential,
 *  lossless: no quantisation) into one view; the primitive's accessors lose their views. */
test::GltfBuilder dracoModel() {
    test::GltfBuilder b = test::twoJointModel();
    Json& primitive = b.doc["meshes"][0]["primitives"][0];
    draco::Mesh mesh;
    mesh.set_num_points(6);
    const std::uint32_t triangles[4][3] = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
    for (const auto& t : triangles)
        mesh.AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
    Json ids;
    for (const char* semantic : {"POSITION", "NORMAL", "WEIGHTS_0"}) {
        const std::vector<float> values = floatsOf(b, primitive["attributes"][semantic]);
        const int components = int(values.size() / 6);
        draco::GeometryAttribute attribute;
        attribute.Init(std::string(semantic) == "POSITION" ? draco::GeometryAttribute::POSITION
                       : std::string(semantic) == "NORMAL" ? draco::GeometryAttribute::NORMAL
                                                           : draco::GeometryAttribute::GENERIC,
                       nullptr, std::uint8_t(components), draco::DT_FLOAT32, false,
                       sizeof(float) * std::size_t(components), 0);
        const int id = mesh.AddAttribute(attribute, true, 6);
        for (int v = 0; v < 6; ++v)
            mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v),
                                                  &values[std::size_t(v * components)]);
        ids[semantic] = mesh.attribute(id)->unique_id();
        b.doc["accessors"][primitive["attributes"][semantic].get<int>()].erase("bufferView");
    }
    draco::Encoder encoder;
    encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    draco::EncoderBuffer buffer;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(mesh, &buffer).ok());
    const int view = b.addView(buffer.data(), buffer.size());
    b.doc["accessors"][primitive["indices"].get<int>()].erase("bufferView");
    primitive["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", view},
                                                             {"attributes", ids}};
    b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    return b;
}

TEST(Draco, CompressedPrimitiveDeformsLikeTheOriginalInEveryContainer) {
    test::TempDir dir;
    const auto plain = asset::loadGltf(test::twoJointModel().save(dir.path(), "plain"));
    ASSERT_TRUE(plain.ok());
    for (auto format : {test::GltfFormat::DataUri, test::GltfFormat::Glb}) {
        const auto model = asset::loadGltf(dracoModel().save(dir.path(), "d", format));
        ASSERT_TRUE(model.ok()) << model.error().message;
        EXPECT_EQ(model->meshes[0].primitives[0].indices, plain->meshes[0].primitives[0].indices);
        for (double t : {0.0, 0.5, 1.0})
            EXPECT_EQ(deformed(*model, t), deformed(*plain, t));
    }
}

TEST(Draco, MalformedPrimitivesFailNamingMeshAndPrimitive) {
    test::TempDir dir;
    // The counts of the attributes the stream holds.
    auto setCounts = [](test::GltfBuilder& b, std::vector<const char*> semantics, std::size_t n) {
        for (const char* semantic : semantics)
            b.doc["accessors"]
                 [b.doc["meshes"][0]["primitives"][0]["attributes"][semantic].get<int>()]["count"] =
                n;
    };
    const std::pair<std::function<void(test::GltfBuilder&)>, std::string> cases[] = {
        {[&](test::GltfBuilder& b) { setCounts(b, {"POSITION"}, 7); },
         "POSITION has 7 elements, other attributes 6"},
        {[&](test::GltfBuilder& b) {
             setCounts(b, {"POSITION", "NORMAL", "WEIGHTS_0"}, 7);
         },
         "decodes to 6 vertices, its accessors claim 7"},
        {[&](test::GltfBuilder& b) {
             setCounts(b, {"POSITION", "NORMAL", "WEIGHTS_0"}, std::size_t(1) << 30);
         },
         "claims 1073741824 vertices, over the limit"},
        {[](test::GltfBuilder& b) {
             auto& e =
                 b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
             e["attributes"]["POSITION"] = 17;
         },
         "POSITION is Draco attribute 17, which the stream does not have"},
        {[](test::GltfBuilder& b) {
             auto& e =
                 b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
             e["bufferView"] = 1; // the normals: not a Draco stream
         },
         "the stream is not a Draco triangle mesh"}};
    for (const auto& [breakIt, expected] : cases) {
        test::GltfBuilder b = dracoModel();
        breakIt(b);
        const auto model = asset::loadGltf(b.save(dir.path(), "broken"));
        ASSERT_FALSE(model.ok()) << expected;
        EXPECT_NE(model.error().message.find(
                      "broken.gltf: mesh 0 primitive 0 KHR_draco_mesh_compression"),
                  std::string::npos)
            << model.error().message;
        EXPECT_NE(model.error().message.find(expected), std::string::npos) << model.error().message;
    }
}

// --- Images and materials -----------------------------------------------------------------

/** A textured two-joint model: image 0 from `bytes` (its MIME type `mime`), texture 0 on a
 *  material's base colour with `textureInfo` merged in. */
test::GltfBuilder texturedModel(const std::vector<std::uint8_t>& bytes, const std::string& mime) {
    test::GltfBuilder b = test::twoJointModel();
    const int view = b.addView(bytes.data(), bytes.size());
    b.doc["images"] = {{{"bufferView", view}, {"mimeType", mime}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return b;
}

std::vector<std::uint8_t> webp(const std::vector<std::uint8_t>& rgba, int width, int height) {
    std::uint8_t* out = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), width, height, width * 4, &out);
    std::vector<std::uint8_t> bytes(out, out + size);
    WebPFree(out);
    return bytes;
}

TEST(Images, WebpTextureDecodesToItsPixels) {
    test::TempDir dir;
    const std::vector<std::uint8_t> pixels = {255, 0, 0,   255, 0, 255, 0, 255,
                                              0,   0, 255, 255, 9, 8,   7, 255};
    // As glTF-Transform writes it: the WebP image named by EXT_texture_webp, required.
    test::GltfBuilder b = texturedModel(webp(pixels, 2, 2), "image/webp");
    b.doc["textures"][0] = {{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}};
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = {"EXT_texture_webp"};
    const auto model = asset::loadGltf(b.save(dir.path(), "webp"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->textures[0].image, 0);
    EXPECT_EQ(model->images[0].width, 2);
    EXPECT_EQ(model->images[0].pixels, pixels);

    std::vector<std::uint8_t> corrupt = webp(pixels, 2, 2);
    corrupt.resize(corrupt.size() - 6);
    const auto bad = asset::loadGltf(texturedModel(corrupt, "image/webp").save(dir.path(), "bad"));
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("bad.gltf: image 0"), std::string::npos)
        << bad.error().message;

    // A RIFF size past the data: refused whether or not the pixels are decoded (glass-inspect
    // reads the sizes alone), so that every tool gives one verdict.
    std::vector<std::uint8_t> overlong = webp(pixels, 2, 2);
    const std::uint32_t declared = std::uint32_t(overlong.size()) - 8 + 4000;
    for (int i = 0; i < 4; ++i)
        overlong[4 + std::size_t(i)] = std::uint8_t(declared >> (8 * i));
    const auto path = texturedModel(overlong, "image/webp").save(dir.path(), "riff");
    for (bool decode : {true, false}) {
        const auto riff = asset::loadGltf(path, {.decodeImages = decode});
        ASSERT_FALSE(riff.ok()) << "decode " << decode;
        EXPECT_NE(riff.error().message.find("riff.gltf: image 0 could not be decoded: its RIFF "
                                            "header declares " +
                                            std::to_string(declared + 8) +
                                            " bytes, the image has " +
                                            std::to_string(overlong.size())),
                  std::string::npos)
            << riff.error().message;
    }
}

TEST(Images, Ktx2TextureUsesItsFallbackOrLoadsWithoutItWithAWarning) {
    test::TempDir dir;
    // A KTX2 file's identifier and some bytes: recognised, never decoded.
    std::vector<std::uint8_t> ktx2 = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                      '0',  0xBB, '\r', '\n', 0x1A, '\n'};
    ktx2.resize(80, 0);
    const std::vector<std::uint8_t> pixels = {10, 20, 30, 255};
    test::GltfBuilder b = texturedModel(ktx2, "image/ktx2");
    const std::vector<std::uint8_t> fallback = webp(pixels, 1, 1);
    const int fallbackView = b.addView(fallback.data(), fallback.size());
    b.doc["images"].push_back({{"bufferView", fallbackView}, {"mimeType", "image/webp"}});
    b.doc["textures"][0] = {{"source", 1},
                            {"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}};
    b.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    const auto withFallback = asset::loadGltf(b.save(dir.path(), "fallback"));
    ASSERT_TRUE(withFallback.ok()) << withFallback.error().message;
    EXPECT_EQ(withFallback->textures[0].image, 1);
    EXPECT_TRUE(withFallback->warnings.empty());

    b.doc["textures"][0].erase("source");
    b.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    const auto without = asset::loadGltf(b.save(dir.path(), "nofallback"));
    ASSERT_TRUE(without.ok()) << without.error().message;
    EXPECT_EQ(without->textures[0].image, -1);
    ASSERT_EQ(without->warnings.size(), 1u);
    EXPECT_NE(without->warnings[0].find("texture 0 has only a KHR_texture_basisu (KTX2) image"),
              std::string::npos)
        << without->warnings[0];
}

TEST(Materials, TextureTransformBecomesTheMatrixOfItsSlot) {
    test::TempDir dir;
    test::GltfBuilder b = texturedModel(webp({1, 2, 3, 255}, 1, 1), "image/webp");
    b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
        {"KHR_texture_transform",
         {{"offset", {0.25, 0.5}}, {"rotation", 1.5707963267948966}, {"scale", {2.0, 4.0}}}}};
    b.doc["materials"][0]["occlusionTexture"] = {
        {"index", 0},
        {"texCoord", 1},
        {"extensions", {{"KHR_texture_transform", {{"texCoord", 0}, {"offset", {1.0, 0.0}}}}}}};
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    const auto model = asset::loadGltf(b.save(dir.path(), "transform"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::TextureRef& base = model->materials[0].baseColorTexture;
    // Scale, then rotate a quarter turn (u -> -v in texture space), then offset.
    const glm::vec2 u = base.apply({1.0f, 0.0f}), v = base.apply({0.0f, 1.0f});
    EXPECT_NEAR(u.x, 0.25f, 1e-6f);
    EXPECT_NEAR(u.y, 0.5f - 2.0f, 1e-6f);
    EXPECT_NEAR(v.x, 0.25f + 4.0f, 1e-6f);
    EXPECT_NEAR(v.y, 0.5f, 1e-6f);
    const scene::TextureRef& occlusion = model->materials[0].occlusionTexture;
    EXPECT_EQ(occlusion.texCoord, 0) << "the extension's texCoord wins";
    EXPECT_EQ(occlusion.apply({0.0f, 0.0f}), glm::vec2(1.0f, 0.0f));
    EXPECT_TRUE(model->warnings.empty());
}

TEST(Materials, UnlitAndSpecularGlossinessAreRead) {
    test::TempDir dir;
    test::GltfBuilder b = texturedModel(webp({1, 2, 3, 255}, 1, 1), "image/webp");
    b.doc["materials"] = {{{"extensions", {{"KHR_materials_unlit", Json::object()}}}},
                          {{"extensions",
                            {{"KHR_materials_pbrSpecularGlossiness",
                              {{"diffuseFactor", {0.5, 0.25, 1.0, 1.0}},
                               {"diffuseTexture", {{"index", 0}}},
                               {"glossinessFactor", 0.75},
                               {"specularGlossinessTexture", {{"index", 0}}}}}}}}};
    b.doc["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_pbrSpecularGlossiness"};
    b.doc["extensionsRequired"] = b.doc["extensionsUsed"];
    const auto model = asset::loadGltf(b.save(dir.path(), "materials"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_TRUE(model->materials[0].unlit);
    EXPECT_FALSE(model->materials[1].unlit);
    const scene::Material& converted = model->materials[1];
    EXPECT_EQ(converted.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
    EXPECT_EQ(converted.baseColorTexture.texture, 0);
    EXPECT_EQ(converted.metallicFactor, 0.0f);
    EXPECT_FLOAT_EQ(converted.roughnessFactor, 0.25f);
    ASSERT_EQ(model->warnings.size(), 1u);
    EXPECT_NE(model->warnings[0].find("material 1 KHR_materials_pbrSpecularGlossiness: its "
                                      "specularGlossinessTexture is not converted"),
              std::string::npos)
        << model->warnings[0];
}

// --- EXT_mesh_gpu_instancing -------------------------------------------------------------------

TEST(Instancing, EachInstanceIsAPlacementOfTheDeformedMesh) {
    // Skinned or not, the instance transform places the deformed mesh in the node's space: the
    // skinned pose of every instance is the first's, moved by its transform.
    test::TempDir dir;
    const auto model =
        asset::loadGltf(test::instancedTwoJointModel().save(dir.path(), "instanced"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_TRUE(model->warnings.empty());
    ASSERT_EQ(model->nodes[0].instances.size(), 3u);
    for (double time : {0.0, 0.7}) {
        const auto instances = deform::deformScene(*model, anim::evaluate(*model, 0, time));
        ASSERT_EQ(instances.size(), 3u);
        const auto world = [&](std::size_t k) {
            return deform::toWorld(instances[k].primitives[0], instances[k].meshToWorld).positions;
        };
        const auto first = world(0), second = world(1), third = world(2);
        for (std::size_t v = 0; v < first.size(); ++v) {
            EXPECT_NEAR(glm::distance(second[v], first[v] + glm::dvec3(2, 0, 0)), 0.0, 1e-9);
            // A quarter turn about +y takes x to -z; then scale 2 and the translation.
            const glm::dvec3 expected =
                glm::dvec3(2.0 * first[v].z, 2.0 * first[v].y, -2.0 * first[v].x) +
                glm::dvec3(0, 0, 3);
            EXPECT_NEAR(glm::distance(third[v], expected), 0.0, 1e-6) << v;
        }
    }
}

TEST(Instancing, InstancesOverTheVertexLimitAreRefused) {
    // Each instance is a placement of its own: 65,536 instances of 2,049 vertices are 2^27.
    test::GltfBuilder b;
    const std::vector<float> positions(3 * 2049, 0.0f), translations(3 * 65536, 0.0f);
    b.doc["meshes"] = {
        {{"primitives",
          {{{"attributes", {{"POSITION", b.addAccessor(positions, 5126, "VEC3")}}}}}}}};
    b.doc["nodes"] = {
        {{"mesh", 0},
         {"extensions",
          {{"EXT_mesh_gpu_instancing",
            {{"attributes", {{"TRANSLATION", b.addAccessor(translations, 5126, "VEC3")}}}}}}}}};
    b.doc["scenes"] = {{{"nodes", {0}}}};
    b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "crowd", test::GltfFormat::Glb));
    ASSERT_FALSE(model.ok());
    EXPECT_NE(model.error().message.find("crowd.glb: node 0 EXT_mesh_gpu_instancing: 65536 "
                                         "instances of 2049 vertices are over the limit"),
              std::string::npos)
        << model.error().message;
}

TEST(Instancing, MalformedInstancesFailNamingTheNode) {
    test::TempDir dir;
    const std::pair<std::function<void(test::GltfBuilder&)>, std::string> cases[] = {
        {[](test::GltfBuilder& b) {
             auto& attributes =
                 b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
             attributes["SCALE"] = b.addAccessor(std::vector<float>{1, 1, 1}, 5126, "VEC3");
         },
         "node 0 EXT_mesh_gpu_instancing SCALE has 1 instances, the other attributes 3"},
        {[](test::GltfBuilder& b) {
             auto& attributes =
                 b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
             attributes["TRANSLATION"] =
                 b.addAccessor(std::vector<std::uint16_t>{0, 0, 0, 1, 1, 1, 2, 2, 2}, 5123, "VEC3");
         },
         "node 0 EXT_mesh_gpu_instancing TRANSLATION (accessor "},
        {[](test::GltfBuilder& b) {
             b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] =
                 99;
         },
         "node 0 EXT_mesh_gpu_instancing ROTATION references accessor 99"}};
    for (const auto& [breakIt, expected] : cases) {
        test::GltfBuilder b = test::instancedTwoJointModel();
        breakIt(b);
        const auto model = asset::loadGltf(b.save(dir.path(), "broken"));
        ASSERT_FALSE(model.ok()) << expected;
        EXPECT_NE(model.error().message.find("broken.gltf: " + expected), std::string::npos)
            << model.error().message;
    }
}

// --- KHR_materials_variants --------------------------------------------------------------------

/** The two-joint model with two materials and variants "red" (material 1) and "plain" (the
 *  primitive's own, material 0, by no mapping). */
test::GltfBuilder variantModel() {
    test::GltfBuilder b = test::twoJointModel();
    b.doc["materials"] = {{{"name", "plain"}}, {{"name", "red"}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", 1}, {"variants", {0}}}};
    b.doc["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}},
                                                                 {{"name", "plain"}}};
    b.doc["extensionsUsed"] = {"KHR_materials_variants"};
    return b;
}

TEST(MaterialVariants, EachVariantNamesItsMaterials) {
    test::TempDir dir;
    const auto model = asset::loadGltf(variantModel().save(dir.path(), "variants"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_TRUE(model->warnings.empty());
    EXPECT_EQ(model->variants, (std::vector<std::string>{"red", "plain"}));
    const scene::Primitive& p = model->meshes[0].primitives[0];
    EXPECT_EQ(p.materialFor(-1), 0);
    EXPECT_EQ(p.materialFor(0), 1);
    EXPECT_EQ(p.materialFor(1), 0); // no mapping: the primitive's own
    EXPECT_EQ(model->findVariant("plain"), 1);
    EXPECT_EQ(model->findVariant("0"), 0);
    EXPECT_FALSE(model->findVariant("blue"));
}

TEST(MaterialVariants, MalformedMappingsFailNamingThePrimitive) {
    test::TempDir dir;
    const std::pair<std::function<void(Json&)>, std::string> cases[] = {
        {[](Json& m) { m[0]["material"] = 7; },
         "mesh 0 primitive 0 KHR_materials_variants mapping 0 references material 7, file has 2 "
         "materials"},
        {[](Json& m) { m[0]["variants"] = {5}; },
         "mesh 0 primitive 0 KHR_materials_variants mapping 0 names variant 5, the file has 2 "
         "variants"}};
    for (const auto& [breakIt, expected] : cases) {
        test::GltfBuilder b = variantModel();
        breakIt(b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]
                     ["mappings"]);
        const auto model = asset::loadGltf(b.save(dir.path(), "broken"));
        ASSERT_FALSE(model.ok()) << expected;
        EXPECT_NE(model.error().message.find("broken.gltf: " + expected), std::string::npos)
            << model.error().message;
    }
}

} // namespace
