// `refraction.scene_depth_tiles` (plugin::Stage::AfterOpaque, where the walk marches through the
// nearby scene): the opaque scene's nearest depth over tiles of 4 to 128 pixels, a mip chain
// (scene_depth_tiles.comp.glsl), that lets a march skip a segment no opaque part comes near.
#include "Passes.h"

#include "engine/gl/Commands.h"
#include "engine/gl/ProgramCache.h"

namespace refraction {

fg::TextureHandle addSceneDepthTilesPass(fg::FrameGraph& graph, const FrameContext& c,
                                         fg::TextureHandle sceneDepth) {
    struct Data {
        fg::TextureHandle depth, tiles;
    };
    const gl::TextureDesc desc = c.sceneTiles();
    return graph
        .addPass<Data>(
            "refraction.scene_depth_tiles",
            [&](fg::Builder& b, Data& d) {
                d.depth = b.read(sceneDepth);
                d.tiles = b.write(b.create("refraction.scene_depth_tiles", desc));
            },
            [c, levels = desc.levels](const fg::Resources& r, const Data& d,
                                      gl::Context&) -> core::Status {
                auto program =
                    c.frame->programs->compute("refraction/passes/scene_depth_tiles.comp.glsl");
                if (!program)
                    return program.error();
                const gl::Texture& tiles = r.texture(d.tiles);
                (*program)->use();
                gl::bindTexture(slot::kSceneDepth, r.texture(d.depth));
                gl::bindTexture(slot::kSceneDepthTiles, tiles);
                for (int level = 0; level < levels; ++level) {
                    const glm::ivec2 texels = glm::max(tiles.size() >> level, glm::ivec2(1));
                    (*program)->set("uLevelIndex", level);
                    gl::bindImage(gl::slot::kOutputImage, tiles, level, true);
                    gl::dispatch(std::uint32_t(texels.x + 7) / 8, std::uint32_t(texels.y + 7) / 8);
                    // the level, for the next one's fetches and the walk's
                    gl::memoryBarrier(gl::BarrierTexture);
                }
                return {};
            })
        .tiles;
}

} // namespace refraction
