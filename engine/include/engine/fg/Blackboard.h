// Named values shared between features that add passes to one frame: resource handles (scene
// colour, depth), camera, deformed geometry, environment. Typed by the caller.
#pragma once

#include "engine/core/Check.h"

#include <any>
#include <map>
#include <string>

namespace fg {

class Blackboard {
public:
    template <class T> void put(const std::string& name, T value) {
        mValues[name] = std::move(value);
    }

    /** The value under `name` if present and of type T, else nullptr. */
    template <class T> const T* find(const std::string& name) const {
        const auto it = mValues.find(name);
        return it == mValues.end() ? nullptr : std::any_cast<T>(&it->second);
    }

    /** The value under `name`; absence or another type is a programming error (aborts). */
    template <class T> const T& get(const std::string& name) const {
        const T* value = find<T>(name);
        ENGINE_CHECK(value != nullptr, "blackboard has no '" + name + "' of the requested type");
        return *value;
    }

    bool contains(const std::string& name) const { return mValues.count(name) > 0; }

private:
    std::map<std::string, std::any> mValues;
};

} // namespace fg
