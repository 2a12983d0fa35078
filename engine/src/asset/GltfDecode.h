// Private to the asset module: geometry compression (KHR_draco_mesh_compression,
// EXT_meshopt_compression and its KHR_ twin) undone before the file's accessors are read, so that
// the rest of the loader sees plain buffer views.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <vector>

namespace asset::detail {

/** KHR_animation_pointer: the extension, the extras key where a rewritten channel keeps its
 *  pointer, and the paths of a channel whose pointer the engine does not play (skipped with a
 *  warning) or that has no pointer string (refused). */
inline constexpr const char* kAnimationPointer = "KHR_animation_pointer";
inline constexpr const char* kPointerExtra = "glass_animation_pointer";
inline constexpr const char* kSkippedPointer = "glass_skipped_pointer";
inline constexpr const char* kMalformedPointer = "glass_malformed_pointer";

/** The file rewritten where tinygltf 2.7 cannot parse what compression leaves: a Draco
 *  primitive's indices accessor has no bufferView (the index moves into the extension object,
 *  where decodeCompressedGeometry takes it back) and a meshopt fallback buffer may have no data
 *  at all (it gets one zero byte: the decoded views replace it); and where it drops what it
 *  does not know: KHR_animation_pointer channels (rewritePointerChannels). nullopt when the file
 *  uses none of these extensions, so other files are parsed from their own bytes. */
std::optional<std::vector<std::uint8_t>> prepareForParser(std::span<const std::uint8_t> bytes,
                                                          bool isBinary);

/** Decodes every meshopt-compressed buffer view and every Draco-compressed primitive into new
 *  buffers, pointing the views and accessors at them. Decoded sizes are checked against the
 *  limits, and what the compressed bytes could justify, before anything is allocated; errors
 *  name the buffer view, or the mesh and primitive. Returns the accessors Draco decoded: its
 *  quantisation moves their data off the min and max the file declares. */
std::set<int> decodeCompressedGeometry(tinygltf::Model& model);

} // namespace asset::detail
