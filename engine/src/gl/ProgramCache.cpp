// gl::ProgramCache: the key is the stages' names and the sorted defines, one per line.
#include "engine/gl/ProgramCache.h"

#include <algorithm>
#include <utility>

namespace gl {
namespace {

std::string variantKey(const std::vector<std::string>& stages, std::vector<std::string>& defines) {
    std::sort(defines.begin(), defines.end());
    std::string key;
    for (const std::string& stage : stages)
        key += stage + '\n';
    key += '\n';
    for (const std::string& define : defines)
        key += define + '\n';
    return key;
}

} // namespace

core::Result<const Program*> ProgramCache::graphics(const std::string& vertex,
                                                    const std::string& fragment,
                                                    std::vector<std::string> defines) {
    defines.insert(defines.end(), mExtraDefines.begin(), mExtraDefines.end());
    return kept(variantKey({vertex, fragment}, defines),
                [&] { return Program::graphics(mLibrary, vertex, fragment, defines); });
}

core::Result<const Program*> ProgramCache::compute(const std::string& name,
                                                   std::vector<std::string> defines) {
    defines.insert(defines.end(), mExtraDefines.begin(), mExtraDefines.end());
    return kept(variantKey({name}, defines),
                [&] { return Program::compute(mLibrary, name, defines); });
}

std::vector<std::string> ProgramCache::keys() const {
    std::vector<std::string> keys;
    for (const auto& [key, program] : mPrograms)
        keys.push_back(key);
    return keys;
}

core::Result<const Program*>
ProgramCache::kept(const std::string& key, const std::function<core::Result<Program>()>& compile) {
    if (auto found = mPrograms.find(key); found != mPrograms.end())
        return found->second.get();
    auto program = compile();
    if (!program)
        return program.error();
    auto& slot = mPrograms[key] = std::make_unique<Program>(std::move(*program));
    return slot.get();
}

} // namespace gl
