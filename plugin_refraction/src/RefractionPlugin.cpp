// The refraction plugin's frame-graph hook.
#include "refraction/RefractionPlugin.h"

namespace refraction {

RefractionPlugin::RefractionPlugin() = default;

core::Status RefractionPlugin::initialize(gl::ShaderLibrary&) { return {}; }

void RefractionPlugin::addPasses(plugin::Stage, fg::FrameGraph&, fg::Blackboard&) {}

std::unique_ptr<plugin::Plugin> createPlugin() { return std::make_unique<RefractionPlugin>(); }

} // namespace refraction
