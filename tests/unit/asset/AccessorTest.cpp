// Accessor decoding through the loader: byte strides, normalized integers, sparse accessors,
// non-indexed and strip primitives, generated normals and tangents, data in .glb.
#include "support/TestSupport.h"

#include "engine/asset/GltfLoader.h"
#include "engine/render/Lighting.h"
#include "engine/scene/World.h"

namespace {

/** A one-triangle mesh whose attributes the test replaces. */
test::GltfBuilder triangle() {
    test::GltfBuilder b;
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int pos = b.addAccessor(positions, 5126, "VEC3");
    b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}}}}}};
    b.doc["nodes"] = {{{"mesh", 0}}};
    b.doc["scenes"] = {{{"nodes", {0}}}};
    return b;
}

TEST(Accessor, InterleavedWithByteStride) {
    test::GltfBuilder b;
    // position (12 bytes) + normal (12 bytes) interleaved, stride 24.
    const std::vector<float> interleaved = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
    const int view = b.addView(interleaved.data(), interleaved.size() * 4, 24);
    b.doc["accessors"] = {
        {{"bufferView", view}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
        {{"bufferView", view},
         {"byteOffset", 12},
         {"componentType", 5126},
         {"count", 3},
         {"type", "VEC3"}}};
    b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}}}}}};
    b.doc["nodes"] = {{{"mesh", 0}}};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "strided"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Primitive& p = model->meshes[0].primitives[0];
    ASSERT_EQ(p.vertexCount(), 3u);
    EXPECT_EQ(p.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(p.positions[2], glm::vec3(0, 1, 0));
    EXPECT_EQ(p.normals[2], glm::vec3(0, 0, 1));
    EXPECT_FALSE(p.flatNormals);
    EXPECT_EQ(p.indices, (std::vector<std::uint32_t>{0, 1, 2})); // non-indexed
}

TEST(Accessor, NormalizedIntegerComponentTypes) {
    test::GltfBuilder b = triangle();
    const std::vector<std::uint8_t> uvBytes = {0, 255, 255, 0, 51, 102}; // UNSIGNED_BYTE
    const std::vector<std::uint16_t> uvShorts = {0, 65535, 32768, 0, 13107, 65535};
    const std::vector<std::int8_t> normals = {0, 0, 127, 0, 0, 127, 0, -128, 0};
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        b.addAccessor(uvBytes, 5121, "VEC2", true);
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] =
        b.addAccessor(uvShorts, 5123, "VEC2", true);
    b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        b.addAccessor(normals, 5120, "VEC3", true);
    b.doc["extensionsUsed"] =
        b.doc["extensionsRequired"] = {"KHR_mesh_quantization"}; // BYTE normals
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "normalized", test::GltfFormat::Glb));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Primitive& p = model->meshes[0].primitives[0];
    EXPECT_FLOAT_EQ(p.uv0[0].y, 1.0f);
    EXPECT_FLOAT_EQ(p.uv0[2].x, 0.2f);
    EXPECT_FLOAT_EQ(p.uv0[2].y, 0.4f);
    EXPECT_FLOAT_EQ(p.uv1[1].x, 32768.0f / 65535.0f);
    EXPECT_FLOAT_EQ(p.uv1[2].x, 0.2f);
    EXPECT_FLOAT_EQ(p.normals[0].z, 1.0f);
    EXPECT_FLOAT_EQ(p.normals[2].y, -1.0f); // -128 clamps to -1
}

TEST(Accessor, SparseSubstitutesOnZerosAndOnData) {
    test::GltfBuilder b = triangle();
    const std::vector<std::uint16_t> sparseIndices = {1, 2};
    const std::vector<float> sparseValues = {0, 0, 2, 0, 0, 3};
    const int iv = b.addView(sparseIndices.data(), 4);
    const int vv = b.addView(sparseValues.data(), 24);
    const nlohmann::json sparse = {{"count", 2},
                                   {"indices", {{"bufferView", iv}, {"componentType", 5123}}},
                                   {"values", {{"bufferView", vv}}}};
    // Morph target without a bufferView: zeros, then the sparse values.
    b.doc["accessors"].push_back(
        {{"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"sparse", sparse}});
    b.doc["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 1}}};
    // The base positions also get a sparse override on top of their buffer data.
    b.doc["accessors"][0]["sparse"] = sparse;
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "sparse"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Primitive& p = model->meshes[0].primitives[0];
    // No NORMAL in the file: flat normals, vertices unwelded (here already one triangle).
    EXPECT_TRUE(p.flatNormals);
    EXPECT_EQ(p.positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(p.positions[1], glm::vec3(0, 0, 2));
    EXPECT_EQ(p.positions[2], glm::vec3(0, 0, 3));
    ASSERT_EQ(p.targets.size(), 1u);
    EXPECT_EQ(p.targets[0].positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(p.targets[0].positions[2], glm::vec3(0, 0, 3));
}

TEST(Accessor, StripsAndFansBecomeLists) {
    for (int mode : {5, 6}) {
        test::GltfBuilder b;
        const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
        const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        b.doc["meshes"] = {{{"primitives",
                             {{{"attributes",
                                {{"POSITION", b.addAccessor(positions, 5126, "VEC3")},
                                 {"NORMAL", b.addAccessor(normals, 5126, "VEC3")}}},
                               {"mode", mode}}}}}};
        test::TempDir dir;
        const auto model = asset::loadGltf(b.save(dir.path(), "strip"));
        ASSERT_TRUE(model.ok()) << model.error().message;
        const auto& indices = model->meshes[0].primitives[0].indices;
        if (mode == 5)
            EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2})); // glTF 3.7.2.1
        else
            EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    }
}

TEST(Accessor, FlatNormalsUnweldSharedVertices) {
    test::GltfBuilder b;
    // Two triangles folded along x: flat normals must differ per face at the shared edge.
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, -1};
    const std::vector<std::uint16_t> indices = {0, 1, 2, 1, 0, 3};
    b.doc["meshes"] = {{{"primitives",
                         {{{"attributes", {{"POSITION", b.addAccessor(positions, 5126, "VEC3")}}},
                           {"indices", b.addAccessor(indices, 5123, "SCALAR")}}}}}};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "flat"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Primitive& p = model->meshes[0].primitives[0];
    EXPECT_EQ(p.vertexCount(), 6u);
    EXPECT_EQ(p.sourceVertexCount, 4u);
    EXPECT_EQ(p.normals[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(p.normals[3], glm::vec3(0, -1, 0));
}

TEST(Accessor, TangentsGeneratedForNormalMap) {
    test::GltfBuilder b = triangle();
    const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::vector<float> uv = {0, 0, 1, 0, 0, -1}; // v runs against +y: handedness -1
    auto& attributes = b.doc["meshes"][0]["primitives"][0]["attributes"];
    attributes["NORMAL"] = b.addAccessor(normals, 5126, "VEC3");
    attributes["TEXCOORD_0"] = b.addAccessor(uv, 5126, "VEC2");
    const std::vector<std::uint8_t> png = test::makePng(1, 1, {128, 128, 255, 255});
    const int imageView = b.addView(png.data(), png.size());
    b.doc["images"] = {{{"bufferView", imageView}, {"mimeType", "image/png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"normalTexture", {{"index", 0}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "normalmap", test::GltfFormat::Glb));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Primitive& p = model->meshes[0].primitives[0];
    ASSERT_TRUE(p.generatedTangents);
    ASSERT_EQ(p.tangents.size(), 3u);
    EXPECT_NEAR(p.tangents[0].x, 1.0f, 1e-6f);
    EXPECT_NEAR(p.tangents[0].w, -1.0f, 1e-6f);
    ASSERT_EQ(model->images.size(), 1u);
    EXPECT_EQ(model->images[0].width, 1);
    EXPECT_EQ(model->images[0].pixels.size(), 4u);
}

TEST(Accessor, GlassExtensionsAreRead) {
    test::GltfBuilder b = triangle();
    b.doc["materials"] = {{{"name", "glass"},
                           {"extensions",
                            {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}},
                             {"KHR_materials_volume",
                              {{"thicknessFactor", 0.2},
                               {"attenuationDistance", 2.0},
                               {"attenuationColor", {0.5, 0.8, 1.0}}}},
                             {"KHR_materials_ior", {{"ior", 1.33}}},
                             {"KHR_materials_dispersion", {{"dispersion", 0.1}}},
                             {"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}};
    b.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume",
                               "KHR_materials_ior", "KHR_materials_dispersion",
                               "KHR_materials_emissive_strength"};
    b.doc["extensionsRequired"] = {"KHR_materials_volume"};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "glass"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Material& m = model->materials[0];
    EXPECT_TRUE(m.isTransmissive());
    EXPECT_FLOAT_EQ(m.transmissionFactor, 0.9f);
    EXPECT_FLOAT_EQ(m.thicknessFactor, 0.2f);
    EXPECT_FLOAT_EQ(m.attenuationDistance, 2.0f);
    EXPECT_FLOAT_EQ(m.attenuationColor.g, 0.8f);
    EXPECT_FLOAT_EQ(m.ior, 1.33f);
    EXPECT_FLOAT_EQ(m.dispersion, 0.1f);
    EXPECT_FLOAT_EQ(m.emissiveStrength, 4.0f);
}

TEST(Accessor, SurfaceLayerExtensionsAreRead) {
    // KHR_materials_clearcoat, _sheen, _iridescence and _anisotropy with their factors and a
    // texture each; the anisotropy gives the primitive generated tangents.
    test::GltfBuilder b = triangle();
    auto& attributes = b.doc["meshes"][0]["primitives"][0]["attributes"];
    attributes["NORMAL"] =
        b.addAccessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, 5126, "VEC3");
    attributes["TEXCOORD_0"] = b.addAccessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2");
    const std::vector<std::uint8_t> png = test::makePng(1, 1, {128, 128, 255, 255});
    b.doc["images"] = {
        {{"bufferView", b.addView(png.data(), png.size())}, {"mimeType", "image/png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"extensions",
                            {{"KHR_materials_clearcoat",
                              {{"clearcoatFactor", 0.7},
                               {"clearcoatRoughnessFactor", 0.2},
                               {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
                             {"KHR_materials_sheen",
                              {{"sheenColorFactor", {0.9, 0.4, 0.1}},
                               {"sheenRoughnessFactor", 0.6},
                               {"sheenColorTexture", {{"index", 0}, {"texCoord", 1}}}}},
                             {"KHR_materials_iridescence",
                              {{"iridescenceFactor", 1.0},
                               {"iridescenceIor", 1.8},
                               {"iridescenceThicknessMinimum", 200},
                               {"iridescenceThicknessMaximum", 500},
                               {"iridescenceThicknessTexture", {{"index", 0}}}}},
                             {"KHR_materials_anisotropy",
                              {{"anisotropyStrength", 0.6},
                               {"anisotropyRotation", 1.5},
                               {"anisotropyTexture", {{"index", 0}}}}}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_sheen",
                               "KHR_materials_iridescence", "KHR_materials_anisotropy"};
    b.doc["extensionsRequired"] = {"KHR_materials_clearcoat", "KHR_materials_iridescence"};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "layers", test::GltfFormat::Glb));
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_TRUE(model->warnings.empty()) << model->warnings.front();
    const scene::Material& m = model->materials[0];
    EXPECT_TRUE(m.hasClearcoat);
    EXPECT_FLOAT_EQ(m.clearcoatFactor, 0.7f);
    EXPECT_FLOAT_EQ(m.clearcoatRoughnessFactor, 0.2f);
    EXPECT_EQ(m.clearcoatNormalTexture.texture, 0);
    EXPECT_FLOAT_EQ(m.clearcoatNormalTexture.scale, 0.5f);
    EXPECT_TRUE(m.hasSheen);
    EXPECT_FLOAT_EQ(m.sheenColorFactor.g, 0.4f);
    EXPECT_FLOAT_EQ(m.sheenRoughnessFactor, 0.6f);
    EXPECT_EQ(m.sheenColorTexture.texCoord, 1);
    EXPECT_TRUE(m.hasIridescence);
    EXPECT_FLOAT_EQ(m.iridescenceIor, 1.8f);
    EXPECT_FLOAT_EQ(m.iridescenceThicknessMinimum, 200.0f);
    EXPECT_FLOAT_EQ(m.iridescenceThicknessMaximum, 500.0f);
    EXPECT_TRUE(m.iridescenceThicknessTexture.present());
    EXPECT_TRUE(m.hasAnisotropy);
    EXPECT_FLOAT_EQ(m.anisotropyStrength, 0.6f);
    EXPECT_FLOAT_EQ(m.anisotropyRotation, 1.5f);
    EXPECT_TRUE(m.anisotropyTexture.present());
    EXPECT_TRUE(model->meshes[0].primitives[0].generatedTangents);
}

TEST(Accessor, PunctualLightsArePlacedOnTheirNodes) {
    // KHR_lights_punctual: a spot on a node turned to look down +x, a point light with a range,
    // a directional light; render::worldLights places them in world space.
    test::GltfBuilder b = triangle();
    b.doc["extensions"] = {{"KHR_lights_punctual",
                            {{"lights",
                              {{{"type", "spot"},
                                {"color", {1.0, 0.5, 0.25}},
                                {"intensity", 20},
                                {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.4}}}},
                               {{"type", "point"}, {"intensity", 5}, {"range", 3}},
                               {{"type", "directional"}}}}}}};
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    // -z turned to +x: a quarter turn about +y (quaternion [0, -sin 45, 0, cos 45])
    b.doc["nodes"].push_back({{"translation", {0, 2, 0}},
                              {"rotation", {0, -0.7071068, 0, 0.7071068}},
                              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc["nodes"].push_back(
        {{"translation", {1, 1, 1}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    b.doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    b.doc["scenes"][0]["nodes"] = {0, 1, 2, 3};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "lights"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_TRUE(model->warnings.empty()) << model->warnings.front();
    ASSERT_EQ(model->lights.size(), 3u);
    EXPECT_EQ(model->lights[0].type, scene::Light::Type::Spot);
    EXPECT_FLOAT_EQ(model->lights[0].outerConeAngle, 0.4f);
    EXPECT_FLOAT_EQ(model->lights[1].range, 3.0f);
    EXPECT_EQ(model->lights[2].type, scene::Light::Type::Directional);
    EXPECT_EQ(model->nodes[1].light, 0);
    scene::World world = scene::singleCharacterWorld(std::make_shared<const scene::Model>(*model));
    world.characters[0].placement.translation = {10.0, 0.0, 0.0};
    const auto lights = render::worldLights(world, 0.0);
    ASSERT_EQ(lights.size(), 3u);
    EXPECT_NEAR(lights[0].position.x, 10.0f, 1e-5f);
    EXPECT_NEAR(lights[0].position.y, 2.0f, 1e-5f);
    EXPECT_NEAR(lights[0].direction.x, 1.0f, 1e-5f);
    EXPECT_NEAR(lights[1].position.z, 1.0f, 1e-5f);
    EXPECT_NEAR(lights[2].direction.z, -1.0f, 1e-5f);
}

TEST(Accessor, MatrixNodeAndCamera) {
    test::GltfBuilder b = triangle();
    // Scale 2 then translate (1,2,3), column-major.
    b.doc["nodes"][0]["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
    b.doc["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
    b.doc["nodes"].push_back({{"camera", 0}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    test::TempDir dir;
    const auto model = asset::loadGltf(b.save(dir.path(), "matrix"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Node& node = model->nodes[0];
    EXPECT_TRUE(node.hasMatrix);
    EXPECT_NEAR(node.rest.scale.y, 2.0, 1e-12);
    EXPECT_NEAR(node.rest.translation.z, 3.0, 1e-12);
    EXPECT_EQ(node.restMatrix[3][1], 2.0);
    ASSERT_EQ(model->cameras.size(), 1u);
    EXPECT_DOUBLE_EQ(model->cameras[0].yfov, 0.7);
}

} // namespace
