// Shared test helpers: where ../shared is, temporary directories, and a small glTF writer that
// tests use to make valid and deliberately malformed files of their own.
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace test {

/** ../shared beside the checkout (or $GLASS_SHARED_DIR), or an empty path when there is none. */
std::filesystem::path sharedDir();

/** Skips the current test with a clear reason when ../shared is absent (a user's clone). */
#define GLASS_REQUIRE_SHARED()                                                                     \
    do {                                                                                           \
        if (::test::sharedDir().empty())                                                           \
            GTEST_SKIP() << "../shared/assets is not beside this checkout (a user's clone): the "  \
                            "third-party sample models are not available";                         \
    } while (false)

/** A fresh directory under the system temp dir, removed with everything in it on destruction. */
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return mPath; }
    std::filesystem::path operator/(const std::string& name) const { return mPath / name; }

private:
    std::filesystem::path mPath;
};

enum class GltfFormat { DataUri, ExternalBin, Glb };

/** Builds a glTF document and its binary buffer in memory; tests then mutate `doc` freely
 *  (that is how malformed files are made) and save it. */
class GltfBuilder {
public:
    GltfBuilder();

    nlohmann::json doc;
    std::vector<std::uint8_t> bin;

    /** Appends raw bytes (4-byte aligned) as a new bufferView on buffer 0; returns its index. */
    int addView(const void* data, std::size_t bytes, int byteStride = 0);

    /** Appends `values` as one accessor of `type` ("SCALAR", "VEC3", ...) and GL component
     *  type (5126 FLOAT, 5123 UNSIGNED_SHORT, ...); returns the accessor index. */
    template <class T>
    int addAccessor(const std::vector<T>& values, int componentType, const std::string& type,
                    bool normalized = false) {
        const int components = componentsOf(type);
        const int view = addView(values.data(), values.size() * sizeof(T));
        nlohmann::json a = {{"bufferView", view},
                            {"componentType", componentType},
                            {"count", values.size() / std::size_t(components)},
                            {"type", type}};
        if (normalized)
            a["normalized"] = true;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }

    /** Writes `directory/name` (.gltf for DataUri/ExternalBin, .glb for Glb) and, for
     *  ExternalBin, `name`.bin beside it. Returns the model's path. */
    std::filesystem::path save(const std::filesystem::path& directory, const std::string& name,
                               GltfFormat format = GltfFormat::DataUri) const;

    static int componentsOf(const std::string& type);
};

/** A valid skinned, morphing, animated triangle strip, small enough to compute by hand:
 *  vertices (0,0,0) (1,0,0) (2,0,0) (0,1,0) (1,1,0) (2,1,0); node 0 carries mesh 0 and skin 0;
 *  skin joints are node 1 (root, at the origin) and node 2 (child of 1, at x = 1);
 *  vertices at x=0 follow joint 0 only, x=1 half/half, x=2 joint 1 only; one morph target moves
 *  every vertex by +1 in z; animation 0 rotates node 2 about +z from 0 to 90 degrees over 1 s
 *  (LINEAR) and drives the morph weight from 0 to 1. */
GltfBuilder twoJointModel();
/** twoJointModel() with its skinned mesh node instanced three times (EXT_mesh_gpu_instancing):
 *  at the origin, moved 2 along +x, and turned a quarter about +y, doubled and moved 3 along
 *  +z. */
GltfBuilder instancedTwoJointModel();
/** twoJointModel() with its channels as KHR_animation_pointer pointers (the rotation's
 *  `rotationPointer`, the weights' /nodes/0/weights), and more over the clip's second: material
 *  0's metallic factor (0 -> 1), its alpha cutoff (which the engine does not play), a spot
 *  light's intensity (0 -> 1), colour ((1, 1, 1) -> (0, 1, 0.5)) and outer cone (0.6 -> 1), the
 *  base colour texture's offset ((0, 0) -> (0.5, 0.25)) and a camera's yfov (0.6 -> 1). */
GltfBuilder pointerTwoJointModel(const std::string& rotationPointer = "/nodes/2/rotation");

/** A glass sphere (the built-in one's mesh, TEXCOORD_0) whose base colour is a 16x16
 *  checker through a KHR_texture_transform, lit by a spot light of the file, and a clip of
 *  KHR_animation_pointer channels over a second: IOR 1.2 -> 1.8, transmission 1 -> 0.6, the
 *  texture's offset (0.1, 0) -> (0.35, 0.2), the spot's intensity 8 -> 30 and colour white ->
 *  (1, 0.55, 0.2). */
GltfBuilder pointerGlassSphereModel();

/** A PNG file's bytes for a width x height RGBA8 image: `rgba` is every texel's, or one texel's
 *  repeated over them all. */
std::vector<std::uint8_t> makePng(int width, int height, std::vector<std::uint8_t> rgba);

/** Writes a width x height Radiance HDR file filled with one linear RGB colour. */
void writeHdr(const std::filesystem::path& path, int width, int height, float r, float g, float b);

/** Runs a shell command and returns its exit status; stdout and stderr into `output`. */
int runCommand(const std::string& command, std::string* output = nullptr);

} // namespace test
