// The refraction plugin: renders the engine's deforming glTF characters as glass (DIR, ISR, SIR).
// This first version plugs into the frame graph and adds no pass yet; the methods follow.
#pragma once

#include "engine/plugin/Plugin.h"

#include <memory>

namespace refraction {

class RefractionPlugin final : public plugin::Plugin {
public:
    RefractionPlugin();
    const char* name() const override { return "refraction"; }
    core::Status initialize(gl::ShaderLibrary& shaders) override;
    void addPasses(plugin::Stage stage, fg::FrameGraph& graph, fg::Blackboard& blackboard) override;
    plugin::ParameterSet& parameters() override { return mParameters; }

private:
    plugin::ParameterSet mParameters;
};

/** For hosts that link the plugin statically instead of loading the module. */
std::unique_ptr<plugin::Plugin> createPlugin();

} // namespace refraction
