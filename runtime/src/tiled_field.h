#pragma once
// Tile instancing on the GPU (Fan & Sheng, Sec. 4.5; scene.h, TilingDescription): the shared
// patch, the terrain's height and density textures, the pool of simulated tiles, and the two
// passes of a frame: simulate (fill newly active pool slots, step the physics of the active
// ones) and emit (make this frame's near blades into the draw buffers of SceneGpu, which the
// blade draw reads as if they were stored blades).
#include <cstdint>
#include <memory>
#include <vector>

#include "far_field.h"
#include "gl/gl_object.h"
#include "gl/shader_program.h"
#include "meadow/runtime/gl_context.h"
#include "physics_pass.h"
#include "renderer_passes.h"
#include "shared/tiling_types.h"
#include "terrain.h"
#include "tile_grid.h"

namespace meadow::runtime {

class TiledField {
public:
    TiledField(GlContext& context, const SceneDescription& scene, const HeightField& field,
               std::vector<gpu::TileInstanceGpu> patch);

    // Starts and stops the simulation of tiles (near the camera, near a collider) and steps the
    // physics of the simulated ones to this frame's time.
    void simulate(const PassInputs& in);
    // This frame's near blades into in.gpu's blade, rest and visible-index buffers and its draw
    // command (at most the scene's max_drawn_blades; culled and thinned ones counted in cullStats).
    void emit(const PassInputs& in);

    // Blades planted on the whole terrain: the patch on every tile, thinned by the density map.
    [[nodiscard]] std::uint64_t instancedBlades() const { return instancedBlades_; }
    [[nodiscard]] std::size_t patchBlades() const { return patch_.size(); }
    [[nodiscard]] std::size_t tilesDrawn() const { return tilesDrawn_; }
    [[nodiscard]] const TilePool& pool() const { return pool_; }
    [[nodiscard]] const TileGrid& grid() const { return grid_; }
    // GPU memory this object holds (patch, pool, textures, tile list), bytes.
    [[nodiscard]] std::size_t gpuBytes() const;
    // The simulated blades of a tile (empty when it is not simulated); waits for the GPU.
    [[nodiscard]] std::vector<gpu::BladeGpu> readSimulatedTile(TileKey tile) const;
    // The blades of a tile as emit() would draw them unsimulated at this instant (same shader
    // code, every blade, no thinning or culling), for tests; waits for the GPU.
    [[nodiscard]] std::vector<gpu::BladeGpu> settledTile(TileKey tile, const PassInputs& in);
    // Binds what the terrain's shading reads: the tiling parameters, the height and density
    // textures and the far field's slices.
    void bindForShading() const;
    [[nodiscard]] bool hasFarField() const { return scene_.tiling->farField; }
    [[nodiscard]] const FarFieldSlices& farField() const { return slices_; }
    [[nodiscard]] const gl::Texture& heightTexture() const { return height_; }
    [[nodiscard]] const gl::Texture& densityTexture() const { return density_; }
    [[nodiscard]] const gl::Buffer& tilingParams() const { return tilingUbo_; }

private:
    void uploadTiles(const std::vector<gpu::TileDrawGpu>& tiles);
    // The tiling parameters for tileCount listed tiles, and the physics parameters (this
    // frame's wind) the settled pose reads.
    void uploadParams(const PassInputs& in, std::uint32_t tileCount);
    void bindShared() const;
    void uploadSlices();
    // Fills each (tile, slot) pair's pool slot with the tile's settled blades.
    void activate(const PassInputs& in,
                  const std::vector<std::pair<TileKey, std::uint32_t>>& tiles);
    [[nodiscard]] std::vector<gpu::BladeGpu> readPoolSlot(std::uint32_t slot) const;

    GlContext& context_;
    const SceneDescription& scene_;
    std::vector<gpu::TileInstanceGpu> patch_;
    TileGrid grid_;
    TilePool pool_;
    gl::ShaderProgram emitProgram_, activateProgram_;
    PhysicsPass physics_;
    gl::Buffer instances_, tiles_, poolBlades_, poolRests_;
    gl::Buffer tilingUbo_, physicsUbo_, cullUbo_;
    gl::Texture height_, density_;
    FarFieldSlices slices_;
    gl::Texture slicesTexture_;
    std::size_t slicesBytes_ = 0;
    std::size_t tileCapacity_ = 0;
    std::size_t densityBytes_ = 0, heightBytes_ = 0;
    std::uint64_t instancedBlades_ = 0;
    std::size_t tilesDrawn_ = 0;
    std::uint32_t drawCapacity_ = 0;
};

// The draw buffers a tiled scene needs: max_drawn_blades rounded up to whole draw chunks.
[[nodiscard]] std::uint32_t tiledDrawCapacity(const TilingDescription& tiling);

}  // namespace meadow::runtime
