#pragma once
// The tiles of a tiled scene on the CPU: which tiles are near and in view this frame (culling
// per tile comes before culling per blade), and which are simulated (TilePool). Needs no GL.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <unordered_map>
#include <vector>

#include "terrain.h"

namespace meadow::runtime {

struct TileKey {
    std::uint32_t x = 0;  // column from the terrain's min corner
    std::uint32_t z = 0;  // row
    friend bool operator==(TileKey, TileKey) = default;
};

class TileGrid {
public:
    // reach_m: how far a blade can get from its root (its height): the tiles' boxes include it.
    TileGrid(const HeightField& field, float tileSize_m, float reach_m);

    [[nodiscard]] int tilesX() const { return heightRanges_.cols; }
    [[nodiscard]] int tilesZ() const { return heightRanges_.rows; }
    [[nodiscard]] float tileSize_m() const { return tileSize_; }
    // Every pose a blade of the tile can take lies in this box.
    void boxOf(TileKey tile, glm::vec3& min_m, glm::vec3& max_m) const;
    // Distance from p to the tile's box (0 inside).
    [[nodiscard]] float distanceTo(TileKey tile, glm::vec3 p_m) const;
    // The tiles whose box comes within radius_m of p, nearest first.
    [[nodiscard]] std::vector<TileKey> tilesNear(glm::vec3 p_m, float radius_m) const;
    // The tiles within radius_m of the camera whose box is not wholly outside the frustum,
    // nearest first.
    [[nodiscard]] std::vector<TileKey> tilesInView(glm::vec3 camera_m,
                                                   const glm::mat4& clipFromWorld,
                                                   float radius_m) const;

private:
    glm::vec2 minXZ_;
    float tileSize_;
    float reach_;
    cv::Mat heightRanges_;  // CV_32FC2 (min, max) per tile
};

// Pool slots of per-blade physics state (Fan & Sheng: simulation only in tiles that need it). A
// tile gets a slot when it is first needed and keeps it until it has not been needed for
// `releaseAfter_s`, the time its blades take to come back to rest; a tile needed while every
// slot is taken is drawn unsimulated.
class TilePool {
public:
    TilePool(std::size_t slots, float releaseAfter_s);

    struct Update {
        std::vector<std::pair<TileKey, std::uint32_t>> activated;  // tile, its new slot
        std::vector<TileKey> released;
        std::size_t refused = 0;  // needed tiles left without a slot
    };
    // `needed`: this frame's tiles that should be simulated, most important first.
    Update update(const std::vector<TileKey>& needed, float time_s);

    [[nodiscard]] std::optional<std::uint32_t> slotOf(TileKey tile) const;
    [[nodiscard]] std::size_t activeCount() const { return active_.size(); }
    [[nodiscard]] std::size_t capacity() const { return slots_; }
    // One past the highest slot in use: the physics pass runs over slots [0, this).
    [[nodiscard]] std::uint32_t slotsInUse() const;

private:
    struct Active {
        std::uint32_t slot;
        float lastNeeded_s;
    };
    static std::uint64_t keyOf(TileKey t) { return (std::uint64_t{t.z} << 32) | t.x; }
    std::size_t slots_;
    float releaseAfter_s_;
    std::vector<std::uint32_t> free_;  // the lowest slot last, so it is taken first
    std::unordered_map<std::uint64_t, Active> active_;
};

// How long a blade pressed flat takes to stand again: the collision strength fades at
// etaDecay_per_s (weakening the recovery until it has gone), then the bend halves every
// ln 2 / s; after ln(1000) / s it is a thousandth of what it was.
[[nodiscard]] float recoveryTime_s(float etaDecay_per_s, float minStiffness_per_s);

}  // namespace meadow::runtime
