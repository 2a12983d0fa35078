// GLSL programs from embedded sources with #include and per-variant defines.
#pragma once

#include "engine/core/Result.h"
#include "engine/gl/Registry.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace gl {

/** One embedded GLSL file: its path under a shaders/ folder and its text. */
struct ShaderFile {
    const char* name;
    const char* source;
};

/** One stage of a program as given to GL: its extension (`vert`, `frag`, `comp`) and source. */
struct StageSource {
    const char* extension;
    std::string source;
};

/** Named GLSL sources (embedded at build time); resolves `#include "name"` recursively. Every
 *  shader it assembles gets the registry's numbers as defines (gl/Registry.h). */
class ShaderLibrary {
public:
    /** A library that writes its programs where GLASS_DUMP_SHADERS names, if it is set. */
    ShaderLibrary();
    void add(std::span<const ShaderFile> files);
    /** Registers `owner`'s table of shared numbers (Registry::add: fails on a clash). */
    core::Status share(const std::string& owner, std::span<const Shared> table);
    const Registry& registry() const { return mRegistry; }
    /** Every file's name and text (checks over the sources). */
    const std::map<std::string, std::string>& files() const { return mFiles; }
    /** `name` with includes expanded, `#version 450 core`, the registry's defines and then
     *  `defines` prepended. Fails on a missing file or an include cycle, naming the chain. */
    core::Result<std::string> assemble(const std::string& name,
                                       const std::vector<std::string>& defines) const;

    /** From now on, every program compiled (and linked) from this library also writes its
     *  stages, as given to GL, to `directory` (created): `<program>-<hash>.<vert|frag|comp>`, the
     * program named by its last stage's file and the hash taken over the sources, so identical
     * variants from any process share one name. An empty path stops it. */
    void dumpTo(std::filesystem::path directory) { mDumpDirectory = std::move(directory); }
    /** Writes `stages` of the program `name` (its last stage's file) where dumpTo says; a
     *  program already written is left as it is. Fails naming the file it cannot write. */
    core::Status dump(const std::string& name, const std::vector<StageSource>& stages) const;

private:
    std::map<std::string, std::string> mFiles;
    Registry mRegistry;
    std::filesystem::path mDumpDirectory;
};

class Program {
public:
    Program() = default;
    ~Program();
    Program(Program&& other) noexcept;
    Program& operator=(Program&& other) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    /** A compute program from `name`. Errors name the shader and carry the compiler log. */
    static core::Result<Program> compute(const ShaderLibrary& library, const std::string& name,
                                         const std::vector<std::string>& defines = {});
    /** A vertex + fragment program. */
    static core::Result<Program> graphics(const ShaderLibrary& library, const std::string& vertex,
                                          const std::string& fragment,
                                          const std::vector<std::string>& defines = {});

    void use() const;
    /** Uniform setters by name; the program must be in use. Unknown names are ignored (the
     *  compiler may drop unused uniforms). */
    void set(const char* name, int value) const;
    void set(const char* name, float value) const;
    void set(const char* name, const glm::vec2& value) const;
    void set(const char* name, const glm::vec3& value) const;
    void set(const char* name, const glm::vec4& value) const;
    void set(const char* name, const glm::ivec2& value) const;
    void set(const char* name, const glm::mat3& value) const;
    void set(const char* name, const glm::mat4& value) const;

    /** The name of element `index` of a uniform array: `array[index]`. */
    static std::string element(const char* array, std::size_t index);

    std::uint32_t id() const { return mId; }
    explicit operator bool() const { return mId != 0; }

private:
    int location(const char* name) const;
    std::uint32_t mId = 0;
    mutable std::unordered_map<std::string, int> mLocations;
};

} // namespace gl
