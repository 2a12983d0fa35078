// A world of characters: loaded models placed any number of times, each with its own transform,
// performance (clip layers, crossfades, root motion) and glass mode. Plain data; the scene file
// format (asset::loadScene) fills it.
#pragma once

#include "engine/scene/Model.h"
#include "engine/scene/Node.h"
#include "engine/scene/Performance.h"

#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace scene {

/** How a character's primitives are chosen as glass: as the file's materials say
 *  (KHR_materials_transmission), every primitive, or none. */
enum class GlassMode { Auto, All, None };

/** Per-character overrides of the glass plugin's material values; unset: the material's. */
struct GlassOverrides {
    std::optional<float> ior;
    std::optional<glm::vec3> tint;
    std::optional<float> dispersion; ///< 20 / Abbe number
    bool operator==(const GlassOverrides&) const = default;
};

/** One placement of a model. The model is shared by every character that places it. */
struct Character {
    std::string name;                   ///< for lists and errors
    std::shared_ptr<const Model> model; ///< never null in a loaded world
    /** The model's path as loaded (a scene file's relative paths resolved against its folder)
     *  or builtin:...; saving writes it relative to the new file's folder. */
    std::string modelPath;
    /** Model space to world space, as glTF nodes spell it (translation, rotation, scale). */
    Trs placement;
    /** What it plays: anim::evaluate() poses the model from it and the scene time. */
    Performance performance;
    int variant = -1; ///< index into model->variants; -1: the file's default materials
    GlassMode glass = GlassMode::Auto;
    GlassOverrides overrides;

    /** The character's world matrix (translation * rotation * scale). */
    glm::dmat4 transform() const { return placement.matrix(); }
    /** Plays `clip` alone (-1: the rest pose), from scene time 0, repeating. */
    void play(int clip) { performance = Performance::single(clip); }
    /** The first layer's clip when it names one of the model's clips, else -1. */
    int mainClip() const { return model ? performance.mainClip(*model) : -1; }
    /** Scene seconds after which what it plays repeats (Performance::period()). */
    double period() const { return model ? performance.period(*model) : 0.0; }
};

/** A character's file camera: the camera on node `node` of character `character`'s model, as
 *  the character's performance moves it. */
struct CameraThrough {
    std::size_t character = 0;
    int node = -1;
    bool operator==(const CameraThrough&) const = default;
};

/** A camera a scene file places: at `position`, looking at `target`, vertical field of view
 *  `yfov` in radians; or, with `through`, a character's file camera (the placement then where
 *  it stood when the scene was saved). */
struct WorldCamera {
    glm::vec3 position{0.0f, 1.0f, 4.0f};
    glm::vec3 target{0.0f};
    float yfov = 0.7f;
    std::optional<CameraThrough> through{};
};

struct World {
    std::vector<Character> characters;
    std::optional<std::string> environment; ///< an HDR path (absolute once loaded); else the sky
    bool ground = false;
    std::optional<WorldCamera> camera; ///< else the tools frame every character
    /** Lights the scene file places (its characters' own lights come with their models). */
    std::vector<PlacedLight> lights;

    /** The longest Character::period() of the characters; 0 when none plays a clip. */
    double longestPeriod() const;
    /** Whether every character's pose repeats (Performance::repeats()): a viewer's clock may
     *  wrap at longestPeriod() without a jump. */
    bool repeats() const;
    /** Scene seconds a timeline shows: the longest period, past the last transition's end
     *  where there is one. */
    double timeline() const;
};

/** A world of one character placing `model` at the origin, playing clip `clip` (-1: the rest
 *  pose) from scene time 0; `path` is its model path (for saving) and its name's source. */
World singleCharacterWorld(std::shared_ptr<const Model> model, int clip = -1,
                           std::string path = {});

} // namespace scene
