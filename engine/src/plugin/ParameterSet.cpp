// Parameter declarations and values.
#include "engine/plugin/ParameterSet.h"

#include "engine/core/Check.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace plugin {

void ParameterSet::declare(Parameter parameter) {
    ENGINE_CHECK(find(parameter.name) == nullptr,
                 "parameter '" + parameter.name + "' declared twice");
    const double d = parameter.defaultValue;
    mValues.push_back({d, d, d});
    mDeclarations.push_back(std::move(parameter));
}

const Parameter* ParameterSet::find(const std::string& name) const {
    for (const Parameter& p : mDeclarations)
        if (p.name == name)
            return &p;
    return nullptr;
}

std::size_t ParameterSet::index(const std::string& name) const {
    for (std::size_t i = 0; i < mDeclarations.size(); ++i)
        if (mDeclarations[i].name == name)
            return i;
    ENGINE_CHECK(false, "no parameter '" + name + "'");
    return 0;
}

core::Status ParameterSet::set(const std::string& name, const std::string& value) {
    core::Status assigned = assign(name, value);
    if (assigned)
        ++mRevision;
    return assigned;
}

core::Status ParameterSet::assign(const std::string& name, const std::string& value) {
    const Parameter* p = find(name);
    if (!p) {
        std::string known;
        for (const Parameter& d : mDeclarations)
            known += (known.empty() ? "" : ", ") + d.name;
        return core::Error{"unknown parameter '" + name + "' (known: " + known + ")"};
    }
    const std::size_t i = index(name);
    switch (p->type) {
    case Parameter::Type::Bool:
        if (value == "on" || value == "true" || value == "1")
            mValues[i] = {1.0, 1.0, 1.0};
        else if (value == "off" || value == "false" || value == "0")
            mValues[i] = {0.0, 0.0, 0.0};
        else
            return core::Error{"parameter '" + name + "' takes on/off, got '" + value + "'"};
        return {};
    case Parameter::Type::Enum: {
        const auto it = std::find(p->choices.begin(), p->choices.end(), value);
        if (it == p->choices.end()) {
            std::string choices;
            for (const auto& c : p->choices)
                choices += (choices.empty() ? "" : "|") + c;
            return core::Error{"parameter '" + name + "' takes " + choices + ", got '" + value +
                               "'"};
        }
        const double index = double(it - p->choices.begin());
        mValues[i] = {index, index, index};
        return {};
    }
    case Parameter::Type::Color: {
        std::array<double, 3> rgb{};
        std::size_t start = 0;
        for (int c = 0; c < 3; ++c) {
            const std::size_t comma = value.find(',', start);
            if ((c < 2) == (comma == std::string::npos))
                return core::Error{"parameter '" + name + "' takes R,G,B, got '" + value + "'"};
            const std::string part = value.substr(start, c < 2 ? comma - start : std::string::npos);
            const char* end = part.data() + part.size();
            const auto [ptr, ec] = std::from_chars(part.data(), end, rgb[std::size_t(c)]);
            if (ec != std::errc() || ptr != end ||
                !(rgb[std::size_t(c)] >= p->min && rgb[std::size_t(c)] <= p->max))
                return core::Error{"parameter '" + name + "' takes R,G,B each in [" +
                                   std::to_string(p->min) + ", " + std::to_string(p->max) +
                                   "], got '" + value + "'"};
            start = comma + 1;
        }
        mValues[i] = rgb;
        return {};
    }
    case Parameter::Type::Float:
    case Parameter::Type::Int: {
        double number = 0.0;
        const char* end = value.data() + value.size();
        const auto [ptr, ec] = std::from_chars(value.data(), end, number);
        if (ec != std::errc() || ptr != end || !std::isfinite(number))
            return core::Error{"parameter '" + name + "' takes a number, got '" + value + "'"};
        if (p->type == Parameter::Type::Int && number != std::floor(number))
            return core::Error{"parameter '" + name + "' takes an integer, got '" + value + "'"};
        if (number < p->min || number > p->max) {
            std::ostringstream range;
            range << "[" << p->min << ", " << p->max << "]";
            return core::Error{"parameter '" + name + "' must lie in " + range.str() + ", got " +
                               value};
        }
        mValues[i] = {number, number, number};
        return {};
    }
    }
    return {};
}

void ParameterSet::setNumber(const std::string& name, double value) {
    const std::size_t i = index(name);
    const Parameter& p = mDeclarations[i];
    if (p.type == Parameter::Type::Float || p.type == Parameter::Type::Int ||
        p.type == Parameter::Type::Color)
        value = std::clamp(value, p.min, p.max);
    if (p.type == Parameter::Type::Enum)
        value = std::clamp(std::round(value), 0.0, double(p.choices.size() - 1));
    if (p.type == Parameter::Type::Bool)
        value = value != 0.0 ? 1.0 : 0.0;
    mValues[i] = {value, value, value};
    ++mRevision;
}

double ParameterSet::number(const std::string& name) const {
    return mValues[index(name)][0];
}

std::array<double, 3> ParameterSet::color(const std::string& name) const {
    return mValues[index(name)];
}

const std::string& ParameterSet::choice(const std::string& name) const {
    const std::size_t i = index(name);
    ENGINE_CHECK(mDeclarations[i].type == Parameter::Type::Enum,
                 "choice() of a non-enum parameter");
    return mDeclarations[i].choices[std::size_t(mValues[i][0])];
}

std::string ParameterSet::text(const std::string& name) const {
    const std::size_t i = index(name);
    const Parameter& p = mDeclarations[i];
    switch (p.type) {
    case Parameter::Type::Bool:
        return mValues[i][0] != 0.0 ? "on" : "off";
    case Parameter::Type::Enum:
        return p.choices[std::size_t(mValues[i][0])];
    case Parameter::Type::Int:
        return std::to_string(static_cast<long long>(mValues[i][0]));
    case Parameter::Type::Float: {
        std::ostringstream s;
        s << mValues[i][0];
        return s.str();
    }
    case Parameter::Type::Color: {
        std::ostringstream s;
        s << mValues[i][0] << "," << mValues[i][1] << "," << mValues[i][2];
        return s.str();
    }
    }
    return {};
}

core::Status ParameterSet::addPreset(ParameterPreset preset) {
    for (const ParameterPreset& existing : mPresets)
        if (existing.name == preset.name)
            return core::Error{"preset '" + preset.name + "' declared twice"};
    ParameterSet trial = *this; // set() on a copy: this set's values stay as they are
    for (const auto& [name, value] : preset.values)
        if (auto checked = trial.set(name, value); !checked)
            return core::Error{"preset '" + preset.name + "': " + checked.error().message};
    mPresets.push_back(std::move(preset));
    return {};
}

core::Status ParameterSet::applyPreset(const std::string& name) {
    for (const ParameterPreset& preset : mPresets)
        if (preset.name == name) {
            for (const auto& [parameter, value] : preset.values)
                ENGINE_CHECK(set(parameter, value), "preset '" + name + "' checked when added");
            return {};
        }
    std::string known;
    for (const ParameterPreset& preset : mPresets)
        known += (known.empty() ? "" : ", ") + preset.name;
    return core::Error{"unknown preset '" + name + "' (known: " + known + ")"};
}

} // namespace plugin
