// A plugin's tunable parameters: declarations (name, type, range, default, choices) and current
// values, settable from text ("--set ior=1.5", presets) with range and type checks, and named
// presets of values a panel offers as one choice.
#pragma once

#include "engine/core/Result.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace plugin {

struct Parameter {
    enum class Type { Float, Int, Bool, Enum, Color };
    std::string name;  ///< key: lower-case, dashes ("search-steps")
    std::string label; ///< for panels
    Type type = Type::Float;
    double min = 0.0, max = 1.0; ///< Float, Int, and each Color component
    double defaultValue = 0.0;   ///< Enum: index into choices; Bool: 0 or 1; Color: grey level
    std::vector<std::string> choices{};
    std::string help{};
};

/** A named group of values a host offers as one choice (a material: its IOR and dispersion).
 *  Plain data, so that a plugin describes its presets without any UI library. */
struct ParameterPreset {
    std::string name;
    std::vector<std::pair<std::string, std::string>> values; ///< parameter, text set() accepts
};

class ParameterSet {
public:
    /** Declares a parameter; its value starts at the default. Names must be unique. */
    void declare(Parameter parameter);

    const std::vector<Parameter>& declarations() const { return mDeclarations; }

    /** Parses and sets `value` ("1.5", "8", "on"/"off"/"true"/"false", an enum choice, "r,g,b"
     *  for a colour). Fails
     *  naming the parameter on an unknown name, an unparsable value or one out of range. */
    core::Status set(const std::string& name, const std::string& value);
    /** Sets a numeric value directly (clamped to the range; Enum: index). */
    void setNumber(const std::string& name, double value);

    double number(const std::string& name) const;
    /** A Color parameter's components. */
    std::array<double, 3> color(const std::string& name) const;
    bool flag(const std::string& name) const { return number(name) != 0.0; }
    /** An Enum parameter's current choice. */
    const std::string& choice(const std::string& name) const;
    /** The value as text, in the form set() accepts. */
    std::string text(const std::string& name) const;

    const Parameter* find(const std::string& name) const;
    /** Changes with every value set: a consumer that decodes the values keeps its decoding
     *  while this stays the same. */
    std::uint64_t revision() const { return mRevision; }

    /** Adds a preset. Fails, naming the preset and the value, when a name is taken or a value
     *  would not set (unknown parameter, bad text, out of range), so applying it cannot fail. */
    core::Status addPreset(ParameterPreset preset);
    const std::vector<ParameterPreset>& presets() const { return mPresets; }
    /** Sets every value of preset `name`; fails naming it when there is none. */
    core::Status applyPreset(const std::string& name);

private:
    std::size_t index(const std::string& name) const;
    core::Status assign(const std::string& name, const std::string& value);
    std::vector<Parameter> mDeclarations;
    std::vector<std::array<double, 3>> mValues;
    std::vector<ParameterPreset> mPresets;
    std::uint64_t mRevision = 0;
};

} // namespace plugin
