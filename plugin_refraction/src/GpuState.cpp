// GpuState's caches: each model's sides at rest, the BVH's parts.
#include "GpuState.h"

#include "model/Optics.h"

#include <algorithm>

namespace refraction {

double GpuState::glassExtent(const scene::Character& character) {
    auto& [model, rest] = sides[character.model.get()];
    if (model.lock() != character.model) { // new, or another model at a freed one's address
        model = character.model;
        rest = restSides(*character.model);
    }
    return refraction::glassExtent(rest, character);
}

int GpuState::Glass::find(const Part& part) const {
    const auto at = std::find(parts.begin(), parts.end(), part);
    return at == parts.end() ? -1 : int(at - parts.begin());
}

} // namespace refraction
