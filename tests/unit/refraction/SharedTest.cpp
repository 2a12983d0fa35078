// The registry of shared numbers as the engine, the renderer and the refraction plugin fill it:
// every table registers beside the others, the shaders spell no binding or unit as a number, and
// the enum defines are the Settings enums' values. No GL context.
#include "Shared.h"
#include "Settings.h"

#include "engine/gl/Program.h"
#include "engine/gl/Shaders.h"
#include "engine/render/Shared.h"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <string>

std::span<const gl::ShaderFile> refractionShaderFiles();

namespace {

/** Every define the three tables give the shaders, by name. */
std::map<std::string, std::string> registeredDefines() {
    gl::Registry registry;
    EXPECT_TRUE(registry.add("render", render::sharedTable()).ok());
    const core::Status plugin = registry.add("refraction", refraction::sharedTable());
    EXPECT_TRUE(plugin.ok()) << plugin.error().message;
    std::map<std::string, std::string> defines;
    for (const std::string& d : registry.defines())
        defines[d.substr(0, d.find(' '))] = d.substr(d.find(' ') + 1);
    return defines;
}

TEST(Shared, TheEngineRenderAndPluginTablesRegisterTogether) {
    const auto defines = registeredDefines();
    EXPECT_EQ(defines.at("LIGHTING_BINDING"), "16");
    EXPECT_EQ(defines.at("GLASS_MATERIALS_BINDING"), "25");
    EXPECT_EQ(defines.at("OPAQUE_TAG"), "0x80000000u");
    EXPECT_EQ(defines.at("SLOTS"), "17");
    for (const gl::Shared& s : refraction::sharedTable()) {
        if (s.kind == gl::Shared::Kind::Storage) {
            EXPECT_GE(s.value, gl::slot::kFirstPluginBinding) << s.define;
        }
    }
}

TEST(Shared, NoShaderSpellsABindingOrAUnitAsANumber) {
    // A layout's binding names a registered slot (..._BINDING, ..._UNIT), never a literal.
    const std::regex literal(R"(binding\s*=\s*[0-9])");
    const std::regex named(R"(binding\s*=\s*([A-Z_]+)(\s*\+\s*[0-9]+)?\s*\))");
    const auto defines = registeredDefines();
    int layouts = 0;
    for (const auto files : {engineShaderFiles(), refractionShaderFiles()})
        for (const gl::ShaderFile& f : files) {
            const std::string text = f.source;
            EXPECT_FALSE(std::regex_search(text, literal)) << f.name << " spells a binding";
            for (auto it = std::sregex_iterator(text.begin(), text.end(), named);
                 it != std::sregex_iterator(); ++it, ++layouts)
                EXPECT_TRUE(defines.count((*it)[1].str())) << f.name << ": " << (*it)[1].str();
        }
    EXPECT_GT(layouts, 40); // the check saw the layouts it guards
}

TEST(Shared, TheEnumDefinesAreTheSettingsValues) {
    const auto defines = registeredDefines();
    using S = refraction::Settings;
    auto value = [&](const char* name) { return std::stoi(defines.at(name)); };
    EXPECT_EQ(value("METHOD_SIR"), int(S::Method::Sir));
    EXPECT_EQ(value("METHOD_HYBRID"), int(S::Method::Hybrid));
    EXPECT_EQ(value("FRESNEL_OFF"), int(S::Fresnel::Off));
    EXPECT_EQ(value("TIR_REFLECT"), int(S::Tir::Reflect));
    EXPECT_EQ(value("DISPERSION_SEARCH_PER_CHANNEL"), int(S::DispersionSearch::PerChannel));
    EXPECT_EQ(value("SURFACES_TWO_SURFACE"), int(S::Surfaces::TwoSurface));
    EXPECT_EQ(value("HYBRID_OUTLINE"), S::kHandOutline);
    EXPECT_EQ(value("DEBUG_NONE"), 0);
    // Every choice of every enum parameter is a define, in the order decode() reads them.
    for (const plugin::Parameter& p : S::parameterTable())
        for (std::size_t i = 0; i < p.choices.size(); ++i) {
            std::string name = p.name + "_" + p.choices[i];
            for (char& c : name)
                c = std::isalnum(static_cast<unsigned char>(c))
                        ? char(std::toupper(static_cast<unsigned char>(c)))
                        : '_';
            ASSERT_TRUE(defines.count(name)) << name;
            EXPECT_EQ(value(name.c_str()), int(i)) << name;
        }
}

} // namespace
