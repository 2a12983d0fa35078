// Shader assembly (#include, defines) and program compilation/linking.
#include "engine/gl/Program.h"

#include "BindingCheck.h"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <utility>

namespace gl {
namespace {

core::Status expand(const std::map<std::string, std::string>& files, const std::string& name,
                    std::vector<std::string>& stack, std::string& out) {
    const auto it = files.find(name);
    if (it == files.end()) {
        std::string chain;
        for (const auto& s : stack)
            chain += s + " -> ";
        return core::Error{"gl::ShaderLibrary: no shader file '" + name + "'" +
                           (stack.empty() ? "" : " (included from " + chain + name + ")")};
    }
    for (const auto& s : stack)
        if (s == name)
            return core::Error{"gl::ShaderLibrary: include cycle through '" + name + "'"};
    stack.push_back(name);
    std::istringstream in(it->second);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        const auto start = line.find_first_not_of(" \t");
        if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
            const auto open = line.find('"', start);
            const auto close = line.find('"', open + 1);
            if (open == std::string::npos || close == std::string::npos)
                return core::Error{"gl::ShaderLibrary: " + name + ":" + std::to_string(number) +
                                   ": malformed #include"};
            auto status = expand(files, line.substr(open + 1, close - open - 1), stack, out);
            if (!status)
                return status;
            continue;
        }
        out += line;
        out += '\n';
    }
    stack.pop_back();
    return {};
}

core::Result<std::uint32_t> compile(GLenum stage, const std::string& name,
                                    const std::string& source) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        return core::Error{"gl::Program: " + name + " does not compile: " + log};
    }
    return std::uint32_t(shader);
}

core::Status link(const std::string& name, const std::vector<std::uint32_t>& shaders,
                  std::uint32_t& out) {
    out = glCreateProgram();
    for (std::uint32_t s : shaders)
        glAttachShader(out, s);
    glLinkProgram(out);
    for (std::uint32_t s : shaders)
        glDeleteShader(s);
    GLint ok = 0;
    glGetProgramiv(out, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(out, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(out, length, nullptr, log.data());
        glDeleteProgram(out);
        out = 0;
        return core::Error{"gl::Program: " + name + " does not link: " + log};
    }
    return {};
}

/** "refraction/passes/walk.frag.glsl" -> "walk". */
std::string programStem(const std::string& file) {
    std::string stem = std::filesystem::path(file).filename().string();
    return stem.substr(0, stem.find('.'));
}

/** FNV-1a over every stage's source, 48 bits in hex: a dumped variant's name. */
std::string sourceHash(const std::vector<StageSource>& stages) {
    std::uint64_t hash = 14695981039346656037ull;
    const auto mix = [&hash](char c) {
        hash ^= std::uint8_t(c);
        hash *= 1099511628211ull;
    };
    for (const StageSource& stage : stages) {
        for (const char c : stage.source)
            mix(c);
        mix('\0');
    }
    char text[16];
    std::snprintf(text, sizeof text, "%012llx", (unsigned long long)(hash >> 16));
    return text;
}

} // namespace

ShaderLibrary::ShaderLibrary() {
    if (const char* directory = std::getenv("GLASS_DUMP_SHADERS"); directory && *directory)
        mDumpDirectory = directory;
}

core::Status ShaderLibrary::dump(const std::string& name,
                                 const std::vector<StageSource>& stages) const {
    if (mDumpDirectory.empty())
        return {};
    std::error_code ec;
    std::filesystem::create_directories(mDumpDirectory, ec);
    if (ec)
        return core::Error{"gl::ShaderLibrary: cannot create " + mDumpDirectory.string() + ": " +
                           ec.message()};
    const std::string program = programStem(name) + "-" + sourceHash(stages);
    for (const StageSource& stage : stages) {
        const auto path = mDumpDirectory / (program + "." + stage.extension);
        if (std::filesystem::exists(path))
            continue;
        // written beside it and renamed: processes dumping the same variant at once each
        // leave a whole file
        const auto partial = path.string() + "." + std::to_string(getpid()) + ".part";
        {
            std::ofstream out(partial, std::ios::binary);
            out << stage.source;
            if (!out.flush()) {
                std::filesystem::remove(partial, ec);
                return core::Error{"gl::ShaderLibrary: cannot write " + partial};
            }
        }
        std::filesystem::rename(partial, path, ec);
        if (ec) {
            const std::string reason = ec.message();
            std::filesystem::remove(partial, ec);
            return core::Error{"gl::ShaderLibrary: cannot write " + path.string() + ": " + reason};
        }
    }
    return {};
}

void ShaderLibrary::add(std::span<const ShaderFile> files) {
    for (const ShaderFile& f : files)
        mFiles[f.name] = f.source;
}

core::Status ShaderLibrary::share(const std::string& owner, std::span<const Shared> table) {
    return mRegistry.add(owner, table);
}

core::Result<std::string> ShaderLibrary::assemble(const std::string& name,
                                                  const std::vector<std::string>& defines) const {
    std::string out = "#version 450 core\n";
    for (const std::string& d : mRegistry.defines())
        out += "#define " + d + "\n";
    for (const std::string& d : defines)
        out += "#define " + d + "\n";
    out += "#line 1\n";
    std::vector<std::string> stack;
    auto status = expand(mFiles, name, stack, out);
    if (!status)
        return status.error();
    return out;
}

Program::~Program() {
    if (mId) {
        detail::forgetProgram(mId);
        glDeleteProgram(mId);
    }
}

Program::Program(Program&& o) noexcept
    : mId(std::exchange(o.mId, 0)), mLocations(std::move(o.mLocations)) {}

Program& Program::operator=(Program&& o) noexcept {
    if (this != &o) {
        if (mId) {
            detail::forgetProgram(mId);
            glDeleteProgram(mId);
        }
        mId = std::exchange(o.mId, 0);
        mLocations = std::move(o.mLocations);
    }
    return *this;
}

core::Result<Program> Program::compute(const ShaderLibrary& library, const std::string& name,
                                       const std::vector<std::string>& defines) {
    auto source = library.assemble(name, defines);
    if (!source)
        return source.error();
    auto shader = compile(GL_COMPUTE_SHADER, name, *source);
    if (!shader)
        return shader.error();
    std::uint32_t id = 0;
    auto linked = link(name, {*shader}, id);
    if (!linked)
        return linked.error();
    detail::recordProgram(id, name);
    Program program;
    program.mId = id;
    if (auto dumped = library.dump(name, {{"comp", *source}}); !dumped)
        return dumped.error();
    return program;
}

core::Result<Program> Program::graphics(const ShaderLibrary& library, const std::string& vertex,
                                        const std::string& fragment,
                                        const std::vector<std::string>& defines) {
    auto vs = library.assemble(vertex, defines);
    if (!vs)
        return vs.error();
    auto fs = library.assemble(fragment, defines);
    if (!fs)
        return fs.error();
    auto v = compile(GL_VERTEX_SHADER, vertex, *vs);
    if (!v)
        return v.error();
    auto f = compile(GL_FRAGMENT_SHADER, fragment, *fs);
    if (!f) {
        glDeleteShader(*v);
        return f.error();
    }
    std::uint32_t id = 0;
    auto linked = link(vertex + " + " + fragment, {*v, *f}, id);
    if (!linked)
        return linked.error();
    detail::recordProgram(id, vertex + " + " + fragment);
    Program program;
    program.mId = id;
    if (auto dumped = library.dump(fragment, {{"vert", *vs}, {"frag", *fs}}); !dumped)
        return dumped.error();
    return program;
}

void Program::use() const {
    glUseProgram(mId);
}

std::string Program::element(const char* array, std::size_t index) {
    // appended, not `"[" + std::string`: that trips GCC 12's -Wrestrict false positive at -O3
    // (GCC bug 105329)
    std::string name = array;
    name += '[';
    name += std::to_string(index);
    name += ']';
    return name;
}

int Program::location(const char* name) const {
    const auto it = mLocations.find(name);
    if (it != mLocations.end())
        return it->second;
    const int location = glGetUniformLocation(mId, name);
    mLocations.emplace(name, location);
    return location;
}

void Program::set(const char* n, int v) const {
    glProgramUniform1i(mId, location(n), v);
}
void Program::set(const char* n, float v) const {
    glProgramUniform1f(mId, location(n), v);
}
void Program::set(const char* n, const glm::vec2& v) const {
    glProgramUniform2fv(mId, location(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::vec3& v) const {
    glProgramUniform3fv(mId, location(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::vec4& v) const {
    glProgramUniform4fv(mId, location(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::ivec2& v) const {
    glProgramUniform2iv(mId, location(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::mat3& v) const {
    glProgramUniformMatrix3fv(mId, location(n), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(mId, location(n), 1, GL_FALSE, glm::value_ptr(v));
}

} // namespace gl
