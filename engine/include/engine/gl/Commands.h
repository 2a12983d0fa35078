// Pipeline state and draw/dispatch commands: the only way code outside gl/ touches GL state.
#pragma once

#include "engine/gl/Buffer.h"
#include "engine/gl/Registry.h"
#include "engine/gl/Texture.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace gl {

enum class Cull : std::uint8_t { None, Back, Front };
enum class DepthFunc : std::uint8_t { Always, Less, LessEqual, Greater, GreaterEqual, Equal };
/** Alpha: over; Additive: one + one; Max: per-channel maximum of source and destination (min/max
 *  gathering, e.g. the nearest and farthest surface of a pixel in one pass). */
/** Blending: none, over (alpha), added, the maximum, or added in RGB and the minimum in alpha (a
 *  sum and a nearest distance in one target). */
enum class Blend : std::uint8_t { None, Alpha, Additive, Max, AddMinAlpha };

/** Fixed-function state for a draw; apply() sets all of it, so passes never inherit state. */
struct PipelineState {
    Cull cull = Cull::Back;
    bool depthTest = true;
    bool depthWrite = true;
    DepthFunc depthFunc = DepthFunc::Less;
    Blend blend = Blend::None;
    /** Front faces wind clockwise on screen (a mirrored mesh: glTF reverses its winding). */
    bool clockwise = false;
    /** Polygon offset pushing depths away: by the slope and by the format's smallest step. */
    float depthBiasSlope = 0.0f, depthBiasUnits = 0.0f;
};

void apply(const PipelineState& state);

/** Draws into rectangle `rect` (x, y, width, height; GL's bottom-up rows) of the bound
 *  framebuffer (a tile of an atlas; clears still clear it whole). */
void setViewport(const glm::ivec4& rect);

/** A sampler object: how a unit reads whichever texture is bound there, over the texture's own
 *  sampling. `compareDepth`: a depth texture read as a shadow sampler, the reference depth less
 *  or equal to the stored one passing. */
class Sampler {
public:
    Sampler(Filter filter, Wrap wrap, bool compareDepth);
    ~Sampler();
    Sampler(Sampler&& other) noexcept;
    Sampler& operator=(Sampler&& other) noexcept;
    Sampler(const Sampler&) = delete;
    Sampler& operator=(const Sampler&) = delete;
    /** Binds to the first unit of `slot`. */
    void bind(const TextureSlot& slot) const;

private:
    std::uint32_t mId = 0;
};

/** Clears the bound framebuffer's colour attachment `index` to `color`. */
void clearColor(int index, const glm::vec4& color);
/** Clears colour attachment `index` of an unsigned-integer format to `value`. */
void clearColorUint(int index, std::uint32_t value);
void clearDepth(float depth);

/** A vertex array with only an index buffer: vertex shaders pull attributes from SSBOs. */
class VertexArray {
public:
    VertexArray();
    ~VertexArray();
    VertexArray(VertexArray&& other) noexcept;
    VertexArray& operator=(VertexArray&& other) noexcept;
    VertexArray(const VertexArray&) = delete;
    VertexArray& operator=(const VertexArray&) = delete;
    void setIndexBuffer(const Buffer& indices);
    void bind() const;

private:
    std::uint32_t mId = 0;
};

/** Draws `indexCount` 32-bit indices from the bound vertex array as triangles. */
void drawIndexed(std::uint32_t indexCount);
/** Draws `vertexCount` vertices with no index buffer (full-screen triangle: 3). */
void drawArrays(std::uint32_t vertexCount);
void dispatch(std::uint32_t x, std::uint32_t y = 1, std::uint32_t z = 1);
/** Dispatches the work groups that three 32-bit words of `groups` at byte `offset` count, as
 *  the GPU left them (no read back). */
void dispatchIndirect(const Buffer& groups, std::size_t offset);

/** GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS of the current context. */
std::uint32_t maxStorageBindings();
/** Binds `buffer` at its registered storage binding (gl/Registry.h: the only way to bind one). */
void bindStorage(const StorageSlot& slot, const Buffer& buffer);
/** Binds `texture` to unit `element` of the run `slot`. */
void bindTexture(const TextureSlot& slot, const Texture& texture, std::uint32_t element = 0);
void bindImage(const ImageSlot& slot, const Texture& texture, int level, bool write);
/** Copies level 0 of `source` into `destination` (same size and format): a copy, no draw
 *  (between formats: Framebuffer::blitColorFrom). */
void copyTexture(const Texture& source, const Texture& destination);

enum Barrier : std::uint32_t {
    BarrierStorage = 1u << 0,      ///< SSBO writes -> SSBO reads
    BarrierVertex = 1u << 1,       ///< SSBO writes -> vertex pulling / index reads
    BarrierTexture = 1u << 2,      ///< image writes -> texture fetches
    BarrierImage = 1u << 3,        ///< image writes -> image loads
    BarrierFramebuffer = 1u << 4,  ///< image writes -> framebuffer
    BarrierBufferUpdate = 1u << 5, ///< SSBO writes -> buffer reads back (Buffer::download)
    BarrierCommand = 1u << 6,      ///< SSBO writes -> indirect command arguments
    BarrierAll = 0xFFFFFFFFu,
};
void memoryBarrier(std::uint32_t barriers);

/** Blocks until the GPU has finished all work: tools and tests, and loading (a compute pass
 *  reading mip levels just generated: render/Environment.cpp). */
void finish();

} // namespace gl
