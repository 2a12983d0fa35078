// Pipeline state, draws, dispatches, bindings and barriers.
#include "engine/gl/Commands.h"

#include "BindingCheck.h"

#include "engine/core/Check.h"

#include <epoxy/gl.h>

#include <utility>

namespace gl {

void apply(const PipelineState& s) {
    if (s.cull == Cull::None) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(s.cull == Cull::Back ? GL_BACK : GL_FRONT);
    }
    if (s.depthTest)
        glEnable(GL_DEPTH_TEST);
    else
        glDisable(GL_DEPTH_TEST);
    glDepthMask(s.depthWrite ? GL_TRUE : GL_FALSE);
    static const GLenum funcs[] = {GL_ALWAYS, GL_LESS, GL_LEQUAL, GL_GREATER, GL_GEQUAL, GL_EQUAL};
    glDepthFunc(funcs[int(s.depthFunc)]);
    if (s.blend == Blend::None) {
        glDisable(GL_BLEND);
    } else {
        glEnable(GL_BLEND);
        if (s.blend == Blend::AddMinAlpha)
            glBlendEquationSeparate(GL_FUNC_ADD, GL_MIN);
        else
            glBlendEquation(s.blend == Blend::Max ? GL_MAX : GL_FUNC_ADD);
        if (s.blend == Blend::Alpha)
            glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE,
                                GL_ONE_MINUS_SRC_ALPHA);
        else
            glBlendFunc(GL_ONE, GL_ONE);
    }
    glFrontFace(s.clockwise ? GL_CW : GL_CCW);
    if (s.depthBiasSlope != 0.0f || s.depthBiasUnits != 0.0f) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(s.depthBiasSlope, s.depthBiasUnits);
    } else {
        glDisable(GL_POLYGON_OFFSET_FILL);
    }
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void setViewport(const glm::ivec4& rect) {
    glViewport(rect.x, rect.y, rect.z, rect.w);
}

Sampler::Sampler(Filter filter, Wrap wrap, bool compareDepth) {
    glCreateSamplers(1, &mId);
    const GLint mag = filter == Filter::Nearest ? GL_NEAREST : GL_LINEAR;
    const GLint min = filter == Filter::LinearMipmap ? GL_LINEAR_MIPMAP_LINEAR : mag;
    static const GLint wraps[] = {GL_REPEAT, GL_CLAMP_TO_EDGE, GL_MIRRORED_REPEAT};
    glSamplerParameteri(mId, GL_TEXTURE_MAG_FILTER, mag);
    glSamplerParameteri(mId, GL_TEXTURE_MIN_FILTER, min);
    glSamplerParameteri(mId, GL_TEXTURE_WRAP_S, wraps[int(wrap)]);
    glSamplerParameteri(mId, GL_TEXTURE_WRAP_T, wraps[int(wrap)]);
    if (compareDepth) {
        glSamplerParameteri(mId, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(mId, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
}

Sampler::~Sampler() {
    if (mId)
        glDeleteSamplers(1, &mId);
}

Sampler::Sampler(Sampler&& other) noexcept : mId(std::exchange(other.mId, 0)) {}

Sampler& Sampler::operator=(Sampler&& other) noexcept {
    if (this != &other) {
        if (mId)
            glDeleteSamplers(1, &mId);
        mId = std::exchange(other.mId, 0);
    }
    return *this;
}

void Sampler::bind(const TextureSlot& slot) const {
    glBindSampler(slot.index, mId);
}

void clearColor(int index, const glm::vec4& color) {
    glColorMaski(GLuint(index), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearBufferfv(GL_COLOR, index, &color.x);
}

void clearColorUint(int index, std::uint32_t value) {
    glColorMaski(GLuint(index), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const GLuint values[4] = {value, value, value, value};
    glClearBufferuiv(GL_COLOR, index, values);
}

void clearDepth(float depth) {
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_DEPTH, 0, &depth);
}

void drawIndexed(std::uint32_t indexCount) {
    detail::checkBindings("gl::drawIndexed");
    glDrawElements(GL_TRIANGLES, GLsizei(indexCount), GL_UNSIGNED_INT, nullptr);
}

void drawArrays(std::uint32_t vertexCount) {
    detail::checkBindings("gl::drawArrays");
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(vertexCount));
}

void dispatch(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    detail::checkDispatch("gl::dispatch");
    glDispatchCompute(x, y, z);
}

void dispatchIndirect(const Buffer& groups, std::size_t offset) {
    detail::checkDispatch("gl::dispatchIndirect");
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, groups.id());
    glDispatchComputeIndirect(GLintptr(offset));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

std::uint32_t maxStorageBindings() {
    GLint count = 0;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &count);
    return std::uint32_t(count);
}

void bindStorage(const StorageSlot& slot, const Buffer& buffer) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, slot.index, buffer.id());
    detail::recordStorage(slot, buffer.id());
}

void bindTexture(const TextureSlot& slot, const Texture& texture, std::uint32_t element) {
    ENGINE_CHECK(element < slot.count, "gl::bindTexture(): unit past the registered run");
    glBindTextureUnit(slot.index + element, texture.id());
}

void copyTexture(const Texture& source, const Texture& destination) {
    ENGINE_CHECK(source.desc().size == destination.desc().size &&
                     source.desc().format == destination.desc().format,
                 "gl::copyTexture(): the textures differ in size or format");
    glCopyImageSubData(source.id(), GL_TEXTURE_2D, 0, 0, 0, 0, destination.id(), GL_TEXTURE_2D, 0,
                       0, 0, 0, source.desc().size.x, source.desc().size.y, 1);
}

void bindImage(const ImageSlot& slot, const Texture& texture, int level, bool write) {
    GLenum format = GL_RGBA32F;
    switch (texture.desc().format) {
    case Format::RGBA16F:
        format = GL_RGBA16F;
        break;
    case Format::R32F:
        format = GL_R32F;
        break;
    case Format::RG32F:
        format = GL_RG32F;
        break;
    case Format::R32UI:
        format = GL_R32UI;
        break;
    case Format::RG32UI:
        format = GL_RG32UI;
        break;
    case Format::RGBA32UI:
        format = GL_RGBA32UI;
        break;
    case Format::RGBA8:
        format = GL_RGBA8;
        break;
    default:
        break;
    }
    glBindImageTexture(slot.index, texture.id(), level, GL_FALSE, 0,
                       write ? GL_READ_WRITE : GL_READ_ONLY, format);
}

void memoryBarrier(std::uint32_t b) {
    GLbitfield bits = 0;
    if (b & BarrierStorage)
        bits |= GL_SHADER_STORAGE_BARRIER_BIT;
    if (b & BarrierVertex)
        bits |= GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                GL_SHADER_STORAGE_BARRIER_BIT;
    if (b & BarrierTexture)
        bits |= GL_TEXTURE_FETCH_BARRIER_BIT;
    if (b & BarrierImage)
        bits |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    if (b & BarrierFramebuffer)
        bits |= GL_FRAMEBUFFER_BARRIER_BIT;
    if (b & BarrierBufferUpdate)
        bits |= GL_BUFFER_UPDATE_BARRIER_BIT;
    if (b & BarrierCommand)
        bits |= GL_COMMAND_BARRIER_BIT;
    if (b == BarrierAll)
        bits = GL_ALL_BARRIER_BITS;
    glMemoryBarrier(bits);
    detail::recordSynchronised(); // (llvmpipe finishes on any barrier)
}

void finish() {
    glFinish();
    detail::recordSynchronised();
}

} // namespace gl
