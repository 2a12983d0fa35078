// The draw-time binding check: a program's storage blocks against the slots bound for them.
#include "BindingCheck.h"

#include "engine/core/Log.h"
#include "engine/gl/Debug.h"

#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <vector>

namespace gl {

namespace {

struct Block {
    std::string name;
    std::uint32_t binding;
};

struct ProgramBlocks {
    std::string name;
    std::vector<Block> blocks;
};

struct Bound {
    std::string define, block; // copies: a plugin module's constants may be unloaded
    std::uint32_t buffer = 0;
};

struct State {
    bool enabled = false;
    std::map<std::uint32_t, ProgramBlocks> programs;
    std::map<std::uint32_t, Bound> storage; // by binding
    bool mipmapsPending = false;            // generated since the last finish or barrier
};

State& state() {
    static State s = [] {
        State initial;
#ifndef NDEBUG
        initial.enabled = true;
#endif
        const char* env = std::getenv("GLASS_GL_CHECKS");
        if (env && *env)
            initial.enabled = std::strcmp(env, "0") != 0;
        return initial;
    }();
    return s;
}

void fail(const std::string& message) {
    reportError("gl binding check: " + message);
}

} // namespace

void setBindingChecks(bool enabled) {
    state().enabled = enabled;
}

bool bindingChecks() {
    return state().enabled;
}

namespace detail {

void recordProgram(std::uint32_t id, const std::string& name) {
    ProgramBlocks program{name, {}};
    GLint count = 0;
    glGetProgramInterfaceiv(id, GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count; ++i) {
        char text[128] = {};
        glGetProgramResourceName(id, GL_SHADER_STORAGE_BLOCK, GLuint(i), sizeof text, nullptr,
                                 text);
        const GLenum property = GL_BUFFER_BINDING;
        GLint binding = 0;
        glGetProgramResourceiv(id, GL_SHADER_STORAGE_BLOCK, GLuint(i), 1, &property, 1, nullptr,
                               &binding);
        program.blocks.push_back({text, std::uint32_t(binding)});
    }
    state().programs[id] = std::move(program);
}

void forgetProgram(std::uint32_t id) {
    state().programs.erase(id);
}

void recordStorage(const StorageSlot& slot, std::uint32_t buffer) {
    State& s = state();
    if (!s.enabled)
        return;
    Bound& bound = s.storage[slot.index];
    bound.define = slot.define;
    bound.block = slot.block;
    bound.buffer = buffer;
}

void checkBindings(const char* command) {
    State& s = state();
    if (!s.enabled)
        return;
    GLint current = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    const auto program = s.programs.find(std::uint32_t(current));
    if (program == s.programs.end())
        return; // not built through gl::Program (OpenSubdiv's evaluators)
    for (const Block& block : program->second.blocks) {
        const std::string where = std::string(command) + " with " + program->second.name +
                                  ": block " + block.name + " at binding " +
                                  std::to_string(block.binding);
        const auto bound = s.storage.find(block.binding);
        if (bound == s.storage.end()) {
            fail(where + " has no buffer bound through the registry");
            continue;
        }
        if (bound->second.block != block.name) {
            fail(where + " is " + bound->second.define + ", registered for block " +
                 bound->second.block);
            continue;
        }
        GLint actual = 0;
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, block.binding, &actual);
        if (std::uint32_t(actual) != bound->second.buffer || actual == 0)
            fail(where + " holds buffer " + std::to_string(actual) + ", not the buffer " +
                 std::to_string(bound->second.buffer) + " bound for " + bound->second.define +
                 " (bound over by code outside the registry, or deleted)");
    }
}

void recordMipmaps() {
    state().mipmapsPending = true;
}

void recordSynchronised() {
    state().mipmapsPending = false;
}

void checkDispatch(const char* command) {
    checkBindings(command);
    State& s = state();
    if (s.enabled && s.mipmapsPending) {
        fail(std::string(command) + " after a mipmap generation with no finish or memory "
                                    "barrier between: llvmpipe's compute does not wait for the "
                                    "levels (gl::finish or gl::memoryBarrier first)");
        s.mipmapsPending = false; // reported once
    }
}

} // namespace detail
} // namespace gl
