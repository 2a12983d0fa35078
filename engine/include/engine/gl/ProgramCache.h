// Programs compiled once per variant: keyed by their stages' sources and their defines.
#pragma once

#include "engine/gl/Program.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gl {

/** Compiles each program variant the first time it is asked for and keeps it for the cache's
 *  life: a variant is its stages' shader names and its defines (in any order), so asking again,
 *  from any pass, in any frame, compiles nothing. The programs it returns stay valid (and at
 *  the same address) until the cache is destroyed. Compiling needs the GL context current. */
class ProgramCache {
public:
    explicit ProgramCache(const ShaderLibrary& library) : mLibrary(library) {}

    /** The vertex + fragment program of `vertex` and `fragment` under `defines`. Errors as
     *  Program::graphics's; a failed variant is not kept (asking again tries again). */
    core::Result<const Program*> graphics(const std::string& vertex, const std::string& fragment,
                                          std::vector<std::string> defines = {});
    /** The compute program of `name` under `defines`. */
    core::Result<const Program*> compute(const std::string& name,
                                         std::vector<std::string> defines = {});
    /** Defines added to every variant asked for from now on, part of its key (measurement
     *  builds: RenderSettings::skippedSteps). */
    void setExtraDefines(std::vector<std::string> defines) { mExtraDefines = std::move(defines); }
    /** How many variants have been compiled (and kept) so far. */
    std::size_t size() const { return mPrograms.size(); }
    /** Each kept variant's key: its stages' names a line each, an empty line, then its
     *  defines sorted, a line each. */
    std::vector<std::string> keys() const;

private:
    /** The program under `key`, compiled by `compile` where there is none yet. */
    core::Result<const Program*> kept(const std::string& key,
                                      const std::function<core::Result<Program>()>& compile);

    const ShaderLibrary& mLibrary;
    std::map<std::string, std::unique_ptr<Program>> mPrograms;
    std::vector<std::string> mExtraDefines;
};

} // namespace gl
