// RAII GL buffer object (used as SSBO, UBO, index or vertex buffer).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gl {

/** Immutable-size buffer storage (glNamedBufferStorage, dynamic). Move-only; deletes on
 *  destruction. Sizes in bytes. */
class Buffer {
public:
    Buffer() = default;
    /** Allocates `bytes` bytes, filled from `data` when given (else zeros). */
    explicit Buffer(std::size_t bytes, const void* data = nullptr);
    template <class T>
    explicit Buffer(std::span<const T> values) : Buffer(values.size_bytes(), values.data()) {}
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    /** Writes `bytes` at `offset`; the range must lie inside the buffer. */
    void update(std::size_t offset, std::size_t bytes, const void* data);
    template <class T> void update(std::span<const T> values, std::size_t offset = 0) {
        update(offset, values.size_bytes(), values.data());
    }
    /** Sets `count` 32-bit words from byte `offset` to `value` on the GPU (a clear: unlike
     *  update(), never waits for earlier draws that read the buffer). */
    void fill(std::size_t offset, std::size_t count, std::uint32_t value);
    /** Copies `bytes` from `sourceOffset` to `offset` on the GPU, within this buffer (the two
     *  ranges apart; shader writes to the source need BarrierBufferUpdate first). */
    void copy(std::size_t sourceOffset, std::size_t offset, std::size_t bytes);
    /** Copies all of `source` (no larger than this buffer) to the start of this one, on the GPU
     *  (shader writes to the source need BarrierBufferUpdate first). */
    void copyFrom(const Buffer& source);
    /** Reads the buffer back (synchronises with the GPU: tests, tools and one-time set-up). */
    std::vector<std::uint8_t> download(std::size_t offset = 0, std::size_t bytes = SIZE_MAX) const;

    std::uint32_t id() const { return mId; }
    std::size_t size() const { return mSize; }
    explicit operator bool() const { return mId != 0; }

private:
    std::uint32_t mId = 0;
    std::size_t mSize = 0;
};

} // namespace gl
