// RAII buffers, textures, framebuffers, vertex arrays and timer queries.
#include "BindingCheck.h"
#include "engine/core/Check.h"
#include "engine/gl/Buffer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Query.h"
#include "engine/gl/Texture.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstring>
#include <utility>

namespace gl {
namespace {

struct FormatInfo {
    GLenum internal, format, type;
};

FormatInfo info(Format f) {
    switch (f) {
    case Format::RGBA8:
        return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::SRGB8_A8:
        return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::RGBA16F:
        return {GL_RGBA16F, GL_RGBA, GL_FLOAT};
    case Format::RGBA32F:
        return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case Format::R32F:
        return {GL_R32F, GL_RED, GL_FLOAT};
    case Format::RG32F:
        return {GL_RG32F, GL_RG, GL_FLOAT};
    case Format::R32UI:
        return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
    case Format::RG32UI:
        return {GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT};
    case Format::RGBA32UI:
        return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT};
    case Format::Depth32F:
        return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    }
    return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
}

int fullChain(glm::ivec2 size) {
    int levels = 1;
    for (int s = std::max(size.x, size.y); s > 1; s /= 2)
        ++levels;
    return levels;
}

} // namespace

bool isDepth(Format f) {
    return f == Format::Depth32F;
}

bool isInteger(Format f) {
    return f == Format::R32UI || f == Format::RG32UI || f == Format::RGBA32UI;
}

// ---- Buffer

Buffer::Buffer(std::size_t bytes, const void* data) : mSize(bytes) {
    glCreateBuffers(1, &mId);
    glNamedBufferStorage(mId, GLsizeiptr(std::max<std::size_t>(bytes, 4)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    if (data && bytes)
        glNamedBufferSubData(mId, 0, GLsizeiptr(bytes), data);
    else {
        const std::uint32_t zero = 0;
        glClearNamedBufferData(mId, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
}

Buffer::~Buffer() {
    if (mId)
        glDeleteBuffers(1, &mId);
}

Buffer::Buffer(Buffer&& o) noexcept
    : mId(std::exchange(o.mId, 0)), mSize(std::exchange(o.mSize, 0)) {}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        if (mId)
            glDeleteBuffers(1, &mId);
        mId = std::exchange(o.mId, 0);
        mSize = std::exchange(o.mSize, 0);
    }
    return *this;
}

void Buffer::update(std::size_t offset, std::size_t bytes, const void* data) {
    ENGINE_CHECK(offset <= mSize && bytes <= mSize - offset, "Buffer::update() past the end");
    if (bytes)
        glNamedBufferSubData(mId, GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::fill(std::size_t offset, std::size_t count, std::uint32_t value) {
    ENGINE_CHECK(offset % 4 == 0 && offset <= mSize && count * 4 <= mSize - offset,
                 "Buffer::fill() past the end or unaligned");
    if (count)
        glClearNamedBufferSubData(mId, GL_R32UI, GLintptr(offset), GLsizeiptr(count * 4),
                                  GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}

void Buffer::copyFrom(const Buffer& source) {
    ENGINE_CHECK(source.mSize <= mSize && source.mId != mId, "Buffer::copyFrom() past the end");
    if (source.mSize)
        glCopyNamedBufferSubData(source.mId, mId, 0, 0, GLsizeiptr(source.mSize));
}

void Buffer::copy(std::size_t sourceOffset, std::size_t offset, std::size_t bytes) {
    ENGINE_CHECK(sourceOffset <= mSize && bytes <= mSize - sourceOffset && offset <= mSize &&
                     bytes <= mSize - offset &&
                     (sourceOffset + bytes <= offset || offset + bytes <= sourceOffset),
                 "Buffer::copy() past the end or onto itself");
    if (bytes)
        glCopyNamedBufferSubData(mId, mId, GLintptr(sourceOffset), GLintptr(offset),
                                 GLsizeiptr(bytes));
}

std::vector<std::uint8_t> Buffer::download(std::size_t offset, std::size_t bytes) const {
    ENGINE_CHECK(offset <= mSize, "Buffer::download() past the end");
    bytes = std::min(bytes, mSize - offset);
    std::vector<std::uint8_t> out(bytes);
    if (bytes)
        glGetNamedBufferSubData(mId, GLintptr(offset), GLsizeiptr(bytes), out.data());
    return out;
}

// ---- Texture

Texture::Texture(const TextureDesc& desc) : mDesc(desc) {
    ENGINE_CHECK(desc.size.x > 0 && desc.size.y > 0 && desc.size.x <= maxSize() &&
                     desc.size.y <= maxSize(),
                 "texture size outside 1..GL_MAX_TEXTURE_SIZE");
    if (mDesc.levels <= 0)
        mDesc.levels = fullChain(desc.size);
    glCreateTextures(GL_TEXTURE_2D, 1, &mId);
    glTextureStorage2D(mId, mDesc.levels, info(desc.format).internal, desc.size.x, desc.size.y);
    // An integer texture filtered is incomplete, and texelFetch then reads (0, 0, 0, 1).
    setSampling(isInteger(desc.format) ? Filter::Nearest
                : mDesc.levels > 1     ? Filter::LinearMipmap
                                       : Filter::Linear,
                Wrap::Clamp);
}

Texture::~Texture() {
    if (mId)
        glDeleteTextures(1, &mId);
}

Texture::Texture(Texture&& o) noexcept : mId(std::exchange(o.mId, 0)), mDesc(o.mDesc) {}

Texture& Texture::operator=(Texture&& o) noexcept {
    if (this != &o) {
        if (mId)
            glDeleteTextures(1, &mId);
        mId = std::exchange(o.mId, 0);
        mDesc = o.mDesc;
    }
    return *this;
}

glm::ivec2 Texture::size(int level) const {
    return glm::max(mDesc.size >> level, glm::ivec2(1));
}

int Texture::maxSize() {
    GLint size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
    return size;
}

void Texture::upload(int level, const void* data) {
    const FormatInfo f = info(mDesc.format);
    const glm::ivec2 s = size(level);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(mId, level, 0, 0, s.x, s.y, f.format, f.type, data);
}

void Texture::generateMipmaps() {
    glGenerateTextureMipmap(mId);
    detail::recordMipmaps();
}

void Texture::setSampling(Filter filter, Wrap wrap) {
    const GLint mag = filter == Filter::Nearest ? GL_NEAREST : GL_LINEAR;
    const GLint min = filter == Filter::Nearest  ? GL_NEAREST
                      : filter == Filter::Linear ? GL_LINEAR
                                                 : GL_LINEAR_MIPMAP_LINEAR;
    const GLint w = wrap == Wrap::Repeat  ? GL_REPEAT
                    : wrap == Wrap::Clamp ? GL_CLAMP_TO_EDGE
                                          : GL_MIRRORED_REPEAT;
    glTextureParameteri(mId, GL_TEXTURE_MAG_FILTER, mag);
    glTextureParameteri(mId, GL_TEXTURE_MIN_FILTER, min);
    glTextureParameteri(mId, GL_TEXTURE_WRAP_S, w);
    glTextureParameteri(mId, GL_TEXTURE_WRAP_T, w);
}

std::vector<float> Texture::downloadFloat(int level) const {
    const glm::ivec2 s = size(level);
    const bool depth = isDepth(mDesc.format);
    std::vector<float> out(std::size_t(s.x) * std::size_t(s.y) * (depth ? 1u : 4u));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(mId, level, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT,
                      GLsizei(out.size() * sizeof(float)), out.data());
    return out;
}

std::vector<std::uint32_t> Texture::downloadUint(int level) const {
    const glm::ivec2 s = size(level);
    std::vector<std::uint32_t> out(std::size_t(s.x) * std::size_t(s.y) * 4u);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(mId, level, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(out.size() * sizeof(std::uint32_t)), out.data());
    return out;
}

std::vector<std::uint8_t> Texture::downloadRgba8(int level) const {
    const glm::ivec2 s = size(level);
    std::vector<std::uint8_t> out(std::size_t(s.x) * std::size_t(s.y) * 4u);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(mId, level, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
    return out;
}

// ---- Framebuffer

Framebuffer::Framebuffer() {
    glCreateFramebuffers(1, &mId);
}

Framebuffer::~Framebuffer() {
    if (mId)
        glDeleteFramebuffers(1, &mId);
}

Framebuffer::Framebuffer(Framebuffer&& o) noexcept : mId(std::exchange(o.mId, 0)), mSize(o.mSize) {}

Framebuffer& Framebuffer::operator=(Framebuffer&& o) noexcept {
    if (this != &o) {
        if (mId)
            glDeleteFramebuffers(1, &mId);
        mId = std::exchange(o.mId, 0);
        mSize = o.mSize;
    }
    return *this;
}

core::Status Framebuffer::attach(const char* name, const std::vector<const Texture*>& colors,
                                 const Texture* depth, int level) {
    std::vector<GLenum> drawBuffers;
    for (std::size_t i = 0; i < colors.size(); ++i) {
        glNamedFramebufferTexture(mId, GLenum(GL_COLOR_ATTACHMENT0 + i), colors[i]->id(), level);
        drawBuffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
        mSize = colors[i]->size(level);
    }
    for (std::size_t i = colors.size(); i < 8; ++i)
        glNamedFramebufferTexture(mId, GLenum(GL_COLOR_ATTACHMENT0 + i), 0, 0);
    glNamedFramebufferTexture(mId, GL_DEPTH_ATTACHMENT, depth ? depth->id() : 0, depth ? level : 0);
    if (depth)
        mSize = depth->size(level);
    if (drawBuffers.empty())
        glNamedFramebufferDrawBuffer(mId, GL_NONE);
    else
        glNamedFramebufferDrawBuffers(mId, GLsizei(drawBuffers.size()), drawBuffers.data());
    const GLenum status = glCheckNamedFramebufferStatus(mId, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(status));
        return core::Error{std::string("gl::Framebuffer::attach(): '") + name +
                           "' is incomplete (status " + code + ")"};
    }
    return {};
}

void Framebuffer::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, mId);
    glViewport(0, 0, mSize.x, mSize.y);
}

core::Status Framebuffer::bindTargets(const char* name, const std::vector<const Texture*>& colors,
                                      const Texture* depth) {
    if (auto attached = attach(name, colors, depth); !attached)
        return attached;
    bind();
    return {};
}

void Framebuffer::bindDefault(glm::ivec2 size) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, size.x, size.y);
}

void Framebuffer::blitToDefault(glm::ivec4 source, glm::ivec4 destination) const {
    const bool scaled = source.z != destination.z || source.w != destination.w;
    glBlitNamedFramebuffer(mId, 0, source.x, source.y, source.x + source.z, source.y + source.w,
                           destination.x, destination.y, destination.x + destination.z,
                           destination.y + destination.w, GL_COLOR_BUFFER_BIT,
                           scaled ? GL_LINEAR : GL_NEAREST);
}

void Framebuffer::blitColorFrom(const Framebuffer& source, glm::ivec2 size) const {
    glBlitNamedFramebuffer(source.mId, mId, 0, 0, size.x, size.y, 0, 0, size.x, size.y,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

std::vector<std::uint8_t> Framebuffer::readDefault(glm::ivec2 size) {
    std::vector<std::uint8_t> pixels(std::size_t(size.x) * std::size_t(size.y) * 4u);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    return flipRows(std::move(pixels), size);
}

// ---- VertexArray

VertexArray::VertexArray() {
    glCreateVertexArrays(1, &mId);
}

VertexArray::~VertexArray() {
    if (mId)
        glDeleteVertexArrays(1, &mId);
}

VertexArray::VertexArray(VertexArray&& o) noexcept : mId(std::exchange(o.mId, 0)) {}

VertexArray& VertexArray::operator=(VertexArray&& o) noexcept {
    if (this != &o) {
        if (mId)
            glDeleteVertexArrays(1, &mId);
        mId = std::exchange(o.mId, 0);
    }
    return *this;
}

void VertexArray::setIndexBuffer(const Buffer& indices) {
    glVertexArrayElementBuffer(mId, indices.id());
}

void VertexArray::bind() const {
    glBindVertexArray(mId);
}

// ---- TimerQuery

TimerQuery::TimerQuery() {
    glCreateQueries(GL_TIMESTAMP, 2, mIds);
}

TimerQuery::~TimerQuery() {
    if (mIds[0])
        glDeleteQueries(2, mIds);
}

TimerQuery::TimerQuery(TimerQuery&& o) noexcept : mIssued(o.mIssued) {
    std::swap(mIds, o.mIds);
}

TimerQuery& TimerQuery::operator=(TimerQuery&& o) noexcept {
    if (this != &o) {
        std::swap(mIds, o.mIds);
        std::swap(mIssued, o.mIssued);
    }
    return *this;
}

void TimerQuery::begin() {
    glQueryCounter(mIds[0], GL_TIMESTAMP);
}

void TimerQuery::end() {
    glQueryCounter(mIds[1], GL_TIMESTAMP);
    mIssued = true;
}

std::optional<std::uint64_t> TimerQuery::resultNs(bool wait) const {
    if (!mIssued)
        return std::nullopt;
    if (!wait) {
        GLint available = 0;
        glGetQueryObjectiv(mIds[1], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available)
            return std::nullopt;
    }
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(mIds[0], GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(mIds[1], GL_QUERY_RESULT, &end);
    return end > begin ? std::uint64_t(end - begin) : std::uint64_t(0);
}

// ---- Fence

Fence::~Fence() {
    if (mSync)
        glDeleteSync(static_cast<GLsync>(mSync));
}

Fence::Fence(Fence&& o) noexcept {
    std::swap(mSync, o.mSync);
}

Fence& Fence::operator=(Fence&& o) noexcept {
    if (this != &o)
        std::swap(mSync, o.mSync);
    return *this;
}

void Fence::insert() {
    if (mSync)
        glDeleteSync(static_cast<GLsync>(mSync));
    mSync = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

bool Fence::passed() const {
    if (!mSync)
        return false;
    // No flush: the frame's end flushes anyway, and a flush mid-frame would cost a CPU
    // rasteriser the batching of what follows.
    const GLenum state = glClientWaitSync(static_cast<GLsync>(mSync), 0, 0);
    return state == GL_ALREADY_SIGNALED || state == GL_CONDITION_SATISFIED;
}

} // namespace gl
