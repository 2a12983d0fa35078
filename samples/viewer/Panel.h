// glass-viewer's Dear ImGui panel: the scene's characters, animation, camera, environment, lights,
// every plugin's parameters (from its ParameterSet, then its own panel hook), A/B split, timings,
// presets and screenshots.
#pragma once

#include "engine/plugin/ParameterSet.h"
#include "engine/scene/World.h"

namespace viewer {

class Viewer;

class Panel {
public:
    /** Draws the panel for this frame (between ImGui::NewFrame and ImGui::Render). */
    static void draw(Viewer& viewer);
    /** The panel's width in a window `windowWidth` pixels wide (docked at the right edge). */
    static int width(int windowWidth);

private:
    static void scene(Viewer& v);
    static void character(Viewer& v, scene::Character& c);
    /** The selected character's clips: the clip and its clock, crossfades, root motion, hold,
     *  layers. */
    static void performance(Viewer& v, scene::Character& c);
    static void layers(scene::Character& c, const std::vector<std::string>& clips);
    static void morphWeights(scene::Character& c);
    static void animation(Viewer& v);
    static void camera(Viewer& v);
    /** The characters' files' cameras, each a choice to look through. */
    static void fileCameras(Viewer& v);
    static void environment(Viewer& v);
    static void temporal(Viewer& v);
    static void lights(Viewer& v);
    static void plugins(Viewer& v);
    static void split(Viewer& v);
    static void timings(Viewer& v);
    static void presets(Viewer& v);
    static void screenshot(Viewer& v);
};

/** One widget for one parameter, chosen by its type: slider (logarithmic over wide ranges),
 *  checkbox, combo or colour editor, with its help as a tooltip. True when it changed. */
bool parameterWidget(plugin::ParameterSet& parameters, const plugin::Parameter& parameter);

} // namespace viewer
