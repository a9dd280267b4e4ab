#include "tiled_field.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "culling_reference.h"
#include "culling_scene_pass.h"
#include "gl/buffers.h"
#include "gl/dispatch.h"
#include "ground_maps.h"
#include "meadow/runtime/error.h"
#include "physics_reference.h"
#include "physics_scene_pass.h"
#include "tile_patch.h"

namespace meadow::runtime {
namespace {

// The density map on the GPU: resampled to at most this many texels a side, and at least one
// per kDensityTexel_m, so the GPU's bilinear filter blurs a black-to-white edge over no more
// than that (a 1 km terrain: 0.5 m texels).
constexpr int kMaxDensitySide_px = 2048;
constexpr float kDensityTexel_m = 0.5f;

gl::ProgramSource tileProgramSource(const char* label, const char* file, bool culling) {
    std::vector<std::string> common = {"shared/physics_params.h"};
    if (culling) common.push_back("shared/cull_params.h");
    common.insert(common.end(),
                  {"shared/tiling_types.h", "common_dispatch.glsl", "common_physics.glsl"});
    if (culling) common.insert(common.end(), {"common_culling.glsl", "common_culling_depth.glsl"});
    common.push_back("common_tiles.glsl");
    return {.label = label,
            .stages = {{GL_COMPUTE_SHADER, file}},
            .commonFiles = common,
            .defines = {}};
}

// The scene's density map resampled over the terrain's rectangle (each map keeps its own
// extent in the scene file); white without one.
cv::Mat densityOverTerrain(const SceneDescription& scene) {
    if (!scene.blades.densityMap) return cv::Mat(1, 1, CV_32F, cv::Scalar(1.f));
    const DensityMap& map = *scene.blades.densityMap;
    const cv::Mat image = loadDensityMap(map);
    const TerrainDescription& t = *scene.terrain;
    const glm::vec2 extent = t.maxXZ_m - t.minXZ_m;
    const auto side = [](int image_px, float extent_m) {
        return std::min(
            kMaxDensitySide_px,
            std::max({image_px, 2, static_cast<int>(std::ceil(extent_m / kDensityTexel_m))}));
    };
    const int cols = side(image.cols, extent.x);
    const int rows = side(image.rows, extent.y);
    cv::Mat out(rows, cols, CV_32F);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const float x = t.minXZ_m.x + (t.maxXZ_m.x - t.minXZ_m.x) * (c + 0.5f) / cols;
            const float z = t.minXZ_m.y + (t.maxXZ_m.y - t.minXZ_m.y) * (r + 0.5f) / rows;
            out.at<float>(r, c) = image.at<float>(texelAt(map, image.size(), {x, 0.f, z}));
        }
    return out;
}

gl::Texture floatTexture(const cv::Mat& image) {
    gl::Texture t = gl::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, GL_R32F, image.cols, image.rows);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(t.id(), 0, 0, 0, image.cols, image.rows, GL_RED, GL_FLOAT, image.data);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

}  // namespace

std::uint32_t tiledDrawCapacity(const TilingDescription& tiling) {
    const auto chunk = static_cast<std::uint32_t>(BLADE_DRAW_CHUNK);
    return (static_cast<std::uint32_t>(tiling.maxDrawnBlades) + chunk - 1) / chunk * chunk;
}

TiledField::TiledField(GlContext& context, const SceneDescription& scene, const HeightField& field,
                       std::vector<gpu::TileInstanceGpu> patch)
    : context_(context),
      scene_(scene),
      patch_(std::move(patch)),
      grid_(field, scene.tiling->tileSize_m, tallestBlade_m(patch_)),
      pool_(static_cast<std::size_t>(scene.tiling->poolTiles),
            recoveryTime_s(scene.physics.collisionDecay_per_s, scene.blades.stiffness.x)),
      emitProgram_(tileProgramSource("tile blades", "tiles_emit.comp", true)),
      activateProgram_(tileProgramSource("tile activation", "tile_activate.comp", false)),
      physics_(context),
      instances_(gl::bufferFor(patch_.size(), patch_.data())),
      // One slot more than the pool: settledTile()'s scratch.
      poolBlades_(gl::bufferFor<gpu::BladeGpu>((pool_.capacity() + 1) * patch_.size())),
      poolRests_(gl::bufferFor<gpu::BladeRestGpu>((pool_.capacity() + 1) * patch_.size())),
      tilingUbo_(gl::bufferFor<gpu::TilingParamsGpu>(1)),
      physicsUbo_(gl::bufferFor<gpu::PhysicsParamsGpu>(1)),
      cullUbo_(gl::bufferFor<gpu::CullParamsGpu>(1)),
      height_(floatTexture(field.height_m)),
      drawCapacity_(tiledDrawCapacity(*scene.tiling)) {
    const cv::Mat density = densityOverTerrain(scene);
    density_ = floatTexture(density);
    densityBytes_ = density.total() * sizeof(float);
    heightBytes_ = field.height_m.total() * sizeof(float);
    // Each tile plants the patch's blades whose threshold is below its density: on average the
    // patch times the mean density over the tile.
    cv::Mat perTile;
    cv::resize(density, perTile, cv::Size(grid_.tilesX(), grid_.tilesZ()), 0, 0, cv::INTER_AREA);
    instancedBlades_ =
        static_cast<std::uint64_t>(std::llround(cv::sum(perTile)[0] * patch_.size()));
    slices_ = buildFarFieldSlices(patch_, scene);
    uploadSlices();
    context_.checkErrors("TiledField: uploading the patch and the terrain");
}

void TiledField::uploadSlices() {
    const cv::Mat& first = slices_.layers.front();
    const int levels =
        1 + static_cast<int>(std::floor(std::log2(std::max(first.cols, first.rows))));
    slicesTexture_ = gl::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint id = slicesTexture_.id();
    const auto layers = static_cast<GLsizei>(slices_.layers.size());
    glTextureStorage3D(id, levels, GL_RGBA8, first.cols, first.rows, layers);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (GLsizei i = 0; i < layers; ++i)
        glTextureSubImage3D(id, 0, 0, 0, i, first.cols, first.rows, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                            slices_.layers[static_cast<std::size_t>(i)].data);
    glGenerateTextureMipmap(id);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    // A full mip chain adds a third to the base level.
    slicesBytes_ = static_cast<std::size_t>(layers) * first.total() * 4 * 4 / 3;
}

void TiledField::bindForShading() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, TILING_UBO_BINDING, tilingUbo_.id());
    glBindTextureUnit(TERRAIN_HEIGHT_TEXTURE_UNIT, height_.id());
    glBindTextureUnit(TERRAIN_DENSITY_TEXTURE_UNIT, density_.id());
    glBindTextureUnit(FAR_FIELD_TEXTURE_UNIT, slicesTexture_.id());
}

std::size_t TiledField::gpuBytes() const {
    return patch_.size() * sizeof(gpu::TileInstanceGpu) +
           (pool_.capacity() + 1) * patch_.size() *
               (sizeof(gpu::BladeGpu) + sizeof(gpu::BladeRestGpu)) +
           tileCapacity_ * sizeof(gpu::TileDrawGpu) + densityBytes_ + heightBytes_ + slicesBytes_ +
           sizeof(gpu::TilingParamsGpu) + sizeof(gpu::PhysicsParamsGpu) +
           sizeof(gpu::CullParamsGpu);
}

void TiledField::uploadTiles(const std::vector<gpu::TileDrawGpu>& tiles) {
    if (tiles.size() > tileCapacity_) {
        tileCapacity_ = std::max(tiles.size(), tileCapacity_ * 2);
        tiles_ = gl::bufferFor<gpu::TileDrawGpu>(tileCapacity_);
    }
    // The previous dispatch may still read the list.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!tiles.empty())
        glNamedBufferSubData(tiles_.id(), 0,
                             static_cast<GLsizeiptr>(tiles.size() * sizeof(gpu::TileDrawGpu)),
                             tiles.data());
}

void TiledField::uploadParams(const PassInputs& in, std::uint32_t tileCount) {
    const TilingDescription& t = *scene_.tiling;
    const TerrainDescription& terrain = *scene_.terrain;
    gpu::TilingParamsGpu p{};
    p.tile = glm::vec4(t.tileSize_m, t.nearDistance_m, t.transition_m, t.fullDensityDistance_m);
    p.terrain = glm::vec4(terrain.minXZ_m, terrain.maxXZ_m - terrain.minXZ_m);
    p.counts = glm::uvec4(tileCount, static_cast<std::uint32_t>(patch_.size()), drawCapacity_, 1u);
    const gpu::PhysicsParamsGpu physics =
        // The settled pose has no time step; the wind is this frame's.
        packPhysicsParams(physicsSettingsOf(scene_, in.frame), 0.f, in.time_s, 0u, 0u);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glNamedBufferSubData(tilingUbo_.id(), 0, sizeof p, &p);
    glNamedBufferSubData(physicsUbo_.id(), 0, sizeof physics, &physics);
}

void TiledField::bindShared() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, PHYSICS_UBO_BINDING, physicsUbo_.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, TILING_UBO_BINDING, tilingUbo_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TILE_INSTANCE_SSBO_BINDING, instances_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TILE_DRAW_SSBO_BINDING, tiles_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TILE_POOL_BLADE_SSBO_BINDING, poolBlades_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TILE_POOL_REST_SSBO_BINDING, poolRests_.id());
    glBindTextureUnit(TERRAIN_HEIGHT_TEXTURE_UNIT, height_.id());
    glBindTextureUnit(TERRAIN_DENSITY_TEXTURE_UNIT, density_.id());
}

void TiledField::activate(const PassInputs& in,
                          const std::vector<std::pair<TileKey, std::uint32_t>>& tiles) {
    if (tiles.empty()) return;
    std::vector<gpu::TileDrawGpu> list;
    for (const auto& [tile, slot] : tiles) list.push_back({glm::uvec4(tile.x, tile.z, slot, 0u)});
    uploadTiles(list);
    uploadParams(in, static_cast<std::uint32_t>(list.size()));
    bindShared();
    activateProgram_.use();
    const auto blades = static_cast<std::uint32_t>(list.size() * patch_.size());
    gl::dispatchGroups((blades + BLADE_WORKGROUP_SIZE - 1) / BLADE_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void TiledField::simulate(const PassInputs& in) {
    if (!scene_.physics.enabled) return;
    const TilingDescription& t = *scene_.tiling;
    // Nearest to the camera first: when the pool is full, the nearest tiles are simulated.
    std::vector<TileKey> needed =
        grid_.tilesNear(glm::vec3(in.frame.cameraPosition_time), t.activeDistance_m);
    std::vector<CollisionSphere> spheres;
    collidersAt(in.scene, in.gpu, in.time_s, spheres);
    for (const CollisionSphere& s : spheres)
        for (TileKey k : grid_.tilesNear(s.center_m, s.radius_m + t.activeDistance_m))
            if (std::find(needed.begin(), needed.end(), k) == needed.end()) needed.push_back(k);
    activate(in, pool_.update(needed, in.time_s).activated);

    const std::uint32_t blades = pool_.slotsInUse() * static_cast<std::uint32_t>(patch_.size());
    if (blades == 0) return;
    const PhysicsSubsteps steps = physicsSubsteps(scene_.blades.stiffness.y, in.deltaTime_s);
    const PhysicsSettings settings = physicsSettingsOf(scene_, in.frame);
    const float start_s = in.time_s - static_cast<float>(steps.count) * steps.step_s;
    for (int k = 1; k <= steps.count; ++k) {
        const float t_s = start_s + static_cast<float>(k) * steps.step_s;
        collidersAt(in.scene, in.gpu, t_s, spheres);
        physics_.dispatch(poolBlades_, poolRests_, blades, spheres, settings, steps.step_s, t_s);
    }
}

void TiledField::emit(const PassInputs& in) {
    const TilingDescription& t = *scene_.tiling;
    const glm::vec3 camera(in.frame.cameraPosition_time);
    // Tiles are culled before their blades, by the same switch.
    const std::vector<TileKey> tiles =
        scene_.culling.frustum ? grid_.tilesInView(camera, in.frame.clipFromWorld, t.nearDistance_m)
                               : grid_.tilesNear(camera, t.nearDistance_m);
    std::vector<gpu::TileDrawGpu> list;
    list.reserve(tiles.size());
    for (TileKey k : tiles) {
        const auto slot = pool_.slotOf(k);
        list.push_back({glm::uvec4(k.x, k.z, slot ? *slot : TILE_NOT_SIMULATED, 0u)});
    }
    tilesDrawn_ = list.size();
    uploadTiles(list);
    uploadParams(in, static_cast<std::uint32_t>(list.size()));

    CullSettings cull = cullSettingsOf(scene_);
    cull.distance = false;  // thinning by threshold replaces Eq. (15)
    const auto width = static_cast<std::uint32_t>(in.frame.viewport_px.x);
    const auto height = static_cast<std::uint32_t>(in.frame.viewport_px.y);
    const gpu::CullParamsGpu cullParams =
        packCullParams(cull, in.frame.clipFromWorld, camera, in.frame.viewport_px.z,
                       in.frame.viewport_px.w, 0u, width, height);
    glNamedBufferSubData(cullUbo_.id(), 0, sizeof cullParams, &cullParams);
    const gpu::DrawCommandGpu reset{0u, 1u, 0u, 0u};
    glNamedBufferSubData(in.gpu.drawCommand.id(), 0, sizeof reset, &reset);
    const std::uint32_t zero = 0;
    glClearNamedBufferSubData(in.gpu.cullStats.id(), GL_R32UI, 0, sizeof(gpu::CullStatsGpu),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    if (list.empty()) return;

    in.gpu.bindAll();
    bindShared();
    glBindBufferBase(GL_UNIFORM_BUFFER, CULL_UBO_BINDING, cullUbo_.id());
    glBindTextureUnit(CULL_DEPTH_TEXTURE_UNIT, in.depth.id());
    emitProgram_.use();
    gl::dispatchGroups(
        static_cast<std::uint32_t>(list.size() * patch_.size() / BLADE_WORKGROUP_SIZE));
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
    context_.checkErrors("TiledField::emit");
}

std::vector<gpu::BladeGpu> TiledField::readPoolSlot(std::uint32_t slot) const {
    std::vector<gpu::BladeGpu> out(patch_.size());
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(
        poolBlades_.id(), static_cast<GLintptr>(slot * patch_.size() * sizeof(gpu::BladeGpu)),
        static_cast<GLsizeiptr>(out.size() * sizeof(gpu::BladeGpu)), out.data());
    return out;
}

std::vector<gpu::BladeGpu> TiledField::readSimulatedTile(TileKey tile) const {
    const auto slot = pool_.slotOf(tile);
    return slot ? readPoolSlot(*slot) : std::vector<gpu::BladeGpu>{};
}

std::vector<gpu::BladeGpu> TiledField::settledTile(TileKey tile, const PassInputs& in) {
    const auto scratch = static_cast<std::uint32_t>(pool_.capacity());
    activate(in, {{tile, scratch}});
    return readPoolSlot(scratch);
}

}  // namespace meadow::runtime
