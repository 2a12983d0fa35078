// The render module's table of shared numbers, from the enums that define them.
#include "engine/render/Shared.h"

#include "engine/render/FrameInfo.h"
#include "engine/render/Lighting.h"
#include "engine/render/MaterialTextures.h"
#include "engine/render/Shadows.h"
#include "engine/scene/Light.h"
#include "engine/scene/Model.h"

namespace render {

namespace {

using gl::Shared;
using Light = scene::Light::Type;
using Slot = MaterialTextures::Slot;

constexpr Shared kTable[] = {
    Shared::integer("LIGHT_DIRECTIONAL", int(Light::Directional)),
    Shared::integer("LIGHT_POINT", int(Light::Point)),
    Shared::integer("LIGHT_SPOT", int(Light::Spot)),
    Shared::integer("SHEEN_TABLE_SIZE", kSheenTableSize),
    Shared::integer("MAX_SHADOW_VIEWS", int(kMaxShadowViews)),
    Shared::real("NO_GLASS", kNoGlass),
    Shared::integer("SLOT_BASE_COLOR", Slot::BaseColor),
    Shared::integer("SLOT_METALLIC_ROUGHNESS", Slot::MetallicRoughness),
    Shared::integer("SLOT_NORMAL", Slot::Normal),
    Shared::integer("SLOT_OCCLUSION", Slot::Occlusion),
    Shared::integer("SLOT_EMISSIVE", Slot::Emissive),
    Shared::integer("SLOT_SPECULAR", Slot::Specular),
    Shared::integer("SLOT_SPECULAR_COLOR", Slot::SpecularColor),
    Shared::integer("SLOT_CLEARCOAT", Slot::Clearcoat),
    Shared::integer("SLOT_CLEARCOAT_ROUGHNESS", Slot::ClearcoatRoughness),
    Shared::integer("SLOT_CLEARCOAT_NORMAL", Slot::ClearcoatNormal),
    Shared::integer("SLOT_SHEEN_COLOR", Slot::SheenColor),
    Shared::integer("SLOT_SHEEN_ROUGHNESS", Slot::SheenRoughness),
    Shared::integer("SLOT_IRIDESCENCE", Slot::Iridescence),
    Shared::integer("SLOT_IRIDESCENCE_THICKNESS", Slot::IridescenceThickness),
    Shared::integer("SLOT_ANISOTROPY", Slot::Anisotropy),
    Shared::integer("SLOT_TRANSMISSION", Slot::Transmission),
    Shared::integer("SLOT_THICKNESS", Slot::Thickness),
    Shared::integer("SLOTS", Slot::kSlotCount),
    Shared::integer("LAYER_CLEARCOAT", scene::Material::kClearcoatLayer),
    Shared::integer("LAYER_SHEEN", scene::Material::kSheenLayer),
    Shared::integer("LAYER_IRIDESCENCE", scene::Material::kIridescenceLayer),
    Shared::integer("LAYER_ANISOTROPY", scene::Material::kAnisotropyLayer),
    Shared::bits("MOTION_ENVIRONMENT", std::uint32_t(MotionKind::Environment)),
    Shared::bits("MOTION_GROUND", std::uint32_t(MotionKind::Ground)),
    Shared::bits("MOTION_OPAQUE", std::uint32_t(MotionKind::Opaque)),
    Shared::bits("MOTION_GLASS", std::uint32_t(MotionKind::Glass)),
    Shared::bits("MOTION_THROUGH_GLASS", std::uint32_t(MotionKind::ThroughGlass)),
    Shared::bits("MOTION_KIND_SHIFT", kMotionKindShift),
    Shared::bits("MOTION_OBJECT_MASK", kMotionObjectMask),
    Shared::integer("TEMPORAL_VIEW_REJECTED", int(TemporalSettings::View::Rejected)),
    Shared::integer("TEMPORAL_VIEW_MOTION", int(TemporalSettings::View::Motion)),
};
static_assert(gl::distinct(kTable));

} // namespace

std::span<const gl::Shared> sharedTable() {
    return kTable;
}

} // namespace render
