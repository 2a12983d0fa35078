// The registry of shared numbers: its tables, their checks against each other and their GLSL
// defines.
#include "engine/gl/Registry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace gl {

namespace {

const char* kindName(Shared::Kind kind) {
    switch (kind) {
    case Shared::Kind::Storage:
        return "storage binding";
    case Shared::Kind::Image:
        return "image unit";
    case Shared::Kind::Texture:
        return "texture unit";
    default:
        return "constant";
    }
}

bool isSlot(Shared::Kind kind) {
    return kind == Shared::Kind::Storage || kind == Shared::Kind::Image ||
           kind == Shared::Kind::Texture;
}

std::string describe(const std::string& owner, const Shared& s) {
    std::string text = owner + "'s " + s.define;
    if (isSlot(s.kind)) {
        char range[48];
        if (s.count > 1)
            std::snprintf(range, sizeof range, " (%ss %.0f-%.0f)", kindName(s.kind), s.value,
                          s.value + s.count - 1);
        else
            std::snprintf(range, sizeof range, " (%s %.0f)", kindName(s.kind), s.value);
        text += range;
    }
    return text;
}

} // namespace

std::string Shared::glsl() const {
    char text[128];
    switch (kind) {
    case Kind::Uint:
        std::snprintf(text, sizeof text, "%s 0x%08Xu", define, unsigned(value));
        break;
    case Kind::Float:
        std::snprintf(text, sizeof text, "%s %.9g", define, value);
        if (!std::strpbrk(text + std::strlen(define) + 1, ".e"))
            std::strcat(text, ".0");
        break;
    default:
        std::snprintf(text, sizeof text, "%s %lld", define, (long long)std::llround(value));
        break;
    }
    return text;
}

Shared Registry::Entry::shared() const {
    Shared s(kind, define.c_str(), value);
    s.count = count;
    return s;
}

Registry::Registry() {
    const core::Status engine = add("engine", slot::kEngineTable);
    (void)engine; // distinct by its static_assert
}

core::Status Registry::add(const std::string& owner, std::span<const Shared> table) {
    // The same owner's same table again (a second instance of a plugin, or its module beside
    // the linked copy): the same numbers, nothing to add.
    std::size_t known = 0;
    for (const Entry& e : mEntries)
        if (e.owner == owner && known < table.size() && e.define == table[known].define &&
            e.value == table[known].value && e.kind == table[known].kind)
            ++known;
    if (known == table.size() && known > 0)
        return {};
    for (std::size_t i = 0; i < table.size(); ++i) {
        const Shared& s = table[i];
        for (std::size_t j = 0; j < i; ++j)
            if (std::strcmp(table[j].define, s.define) == 0)
                return core::Error{"gl::Registry: " + owner + " registers " + s.define + " twice"};
        for (const Entry& e : mEntries) {
            const Shared o = e.shared();
            const bool sameName = e.define == s.define;
            const bool overlap = isSlot(s.kind) && o.kind == s.kind &&
                                 s.value < o.value + o.count && o.value < s.value + s.count;
            if (sameName || overlap)
                return core::Error{"gl::Registry: " + describe(owner, s) +
                                   (sameName ? " is named like " : " overlaps ") +
                                   describe(e.owner, o)};
        }
    }
    for (const Shared& s : table)
        mEntries.push_back({owner, s.define, s.kind, s.value, s.count});
    return {};
}

std::vector<std::string> Registry::defines() const {
    std::vector<std::string> out;
    out.reserve(mEntries.size());
    for (const Entry& e : mEntries)
        out.push_back(e.shared().glsl());
    return out;
}

std::uint32_t Registry::highestStorage() const {
    std::uint32_t highest = 0;
    for (const Entry& e : mEntries)
        if (e.kind == Shared::Kind::Storage)
            highest = std::max(highest, std::uint32_t(e.value));
    return highest;
}

} // namespace gl
