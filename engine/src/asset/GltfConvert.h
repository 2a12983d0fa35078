// Private to the asset module: the steps of loadGltf(), each turning validated tinygltf data into
// engine-owned scene data. Each step throws detail::LoadError naming the element on bad input.
#pragma once

#include "AccessorReader.h"
#include "engine/scene/Model.h"

#include <tiny_gltf.h>

#include <set>

namespace asset::detail {

/** What the image callback is asked to do, and the images it kept undecoded. */
struct ImageDecoding {
    bool decode = true;
    std::set<int> ktx2; ///< images kept undecoded: KTX2 (Debian 12 has no decoder for it)
};

/** tinygltf's image callback (`userData`: an ImageDecoding): checks the image's size against
 *  the limits and what its bytes can justify before decoding PNG to RGBA of 8 or 16 bits, JPEG
 *  and WebP to RGBA8, or only records the size when decoding is off; keeps KTX2 undecoded. */
bool decodeImage(tinygltf::Image* image, int index, std::string* err, std::string* warn,
                 int requestedWidth, int requestedHeight, const unsigned char* bytes, int size,
                 void* userData);

/** asset.version must be 2.x and asset.minVersion (when present) at most 2.0. */
void checkVersion(const tinygltf::Asset& asset);

/** Index ranges of every cross reference except accessors (checked when read), the node
 *  hierarchy (single parent, no cycles, scene roots are roots), extensionsRequired, limits. */
void validateStructure(const tinygltf::Model& model);

/** Nodes with local transforms and hierarchy links; matrices decomposed into TRS. */
std::vector<scene::Node> convertNodes(const tinygltf::Model& model);

/** Mesh `index`: primitives with attributes, indices, morph targets; generated normals and
 *  tangents where needed (tangents when `materials` gives the primitive a normal map).
 *  Attribute formats glTF does not allow are refused. POINTS and LINES primitives are left
 *  out, and min or max bounds that are not the data's (but for the `lossy` accessors, which
 *  Draco decoded) named, each with a line in `warnings`. */
scene::Mesh convertMesh(const tinygltf::Model& model, const AccessorReader& reader, int index,
                        const std::vector<scene::Material>& materials, const std::set<int>& lossy,
                        std::vector<std::string>& warnings);

/** A warning for each min or max of an integer accessor that is not whole numbers (the
 *  validator's ARRAY_TYPE_MISMATCH): the engine reads bounds from the data, so it loads. */
void fractionalBoundsWarnings(const tinygltf::Model& model, std::vector<std::string>& warnings);

/** A KHR_materials_ extension: one the engine lacks loads without it, with a warning, even
 *  when the file requires it. */
bool isMaterialExtension(const std::string& extension);

/** KHR_materials_variants: the file's variant names (none without the extension). */
std::vector<std::string> variantNames(const tinygltf::Model& model);

/** Skin `index` with inverse bind matrices (identity when absent). */
scene::Skin convertSkin(const tinygltf::Model& model, const AccessorReader& reader, int index);

/** Animation `index`; weight channels are checked against the target node's morph count. */
scene::Animation convertAnimation(const tinygltf::Model& model, const AccessorReader& reader,
                                  std::vector<std::string>& warnings,
                                  int index, const std::vector<scene::Mesh>& meshes);

/** Material `index` with metallic-roughness, the KHR glass extensions, KHR_materials_unlit,
 *  KHR_texture_transform on every slot, and KHR_materials_pbrSpecularGlossiness converted
 *  (what the conversion drops is a line in `warnings`). */
scene::Material convertMaterial(const tinygltf::Model& model, int index,
                                std::vector<std::string>& warnings);

/** Texture `index` with its image: EXT_texture_webp's source where given; for
 *  KHR_texture_basisu the PNG or JPEG fallback, or none with a line in `warnings` when only the
 *  KTX2 image (in `undecoded`) is there. */
scene::Texture convertTexture(const tinygltf::Model& model, int index,
                              const std::set<int>& undecoded, std::vector<std::string>& warnings);

scene::Camera convertCamera(const tinygltf::Model& model, int index);
/** KHR_lights_punctual light `index`, checked (type, colour, cone angles). */
scene::Light convertLight(const tinygltf::Model& model, int index);

/** Joints with non-zero weight index into the node's skin; zero-weight joints are set to 0. */
void validateSkinnedMeshes(const scene::Model& model);

} // namespace asset::detail
