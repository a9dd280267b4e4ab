#include "tile_grid.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace meadow::runtime {

TileGrid::TileGrid(const HeightField& field, float tileSize_m, float reach_m)
    : minXZ_(field.minXZ_m),
      tileSize_(tileSize_m),
      reach_(reach_m),
      heightRanges_(tileHeightRanges(field, tileSize_m)) {}

void TileGrid::boxOf(TileKey t, glm::vec3& lo, glm::vec3& hi) const {
    const cv::Vec2f h = heightRanges_.at<cv::Vec2f>(static_cast<int>(t.z), static_cast<int>(t.x));
    const glm::vec2 xz = minXZ_ + glm::vec2(t.x, t.z) * tileSize_;
    lo = glm::vec3(xz.x - reach_, h[0] - reach_, xz.y - reach_);
    hi = glm::vec3(xz.x + tileSize_ + reach_, h[1] + reach_, xz.y + tileSize_ + reach_);
}

float TileGrid::distanceTo(TileKey t, glm::vec3 p) const {
    glm::vec3 lo, hi;
    boxOf(t, lo, hi);
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::vec3(0.f)));
}

std::vector<TileKey> TileGrid::tilesNear(glm::vec3 p, float radius_m) const {
    const float r = radius_m + reach_;
    const auto column = [&](float x) { return (x - minXZ_.x) / tileSize_; };
    const auto row = [&](float z) { return (z - minXZ_.y) / tileSize_; };
    const int x0 = std::max(0, static_cast<int>(std::floor(column(p.x - r))));
    const int x1 = std::min(tilesX() - 1, static_cast<int>(std::floor(column(p.x + r))));
    const int z0 = std::max(0, static_cast<int>(std::floor(row(p.z - r))));
    const int z1 = std::min(tilesZ() - 1, static_cast<int>(std::floor(row(p.z + r))));
    std::vector<std::pair<float, TileKey>> found;
    for (int z = z0; z <= z1; ++z)
        for (int x = x0; x <= x1; ++x) {
            const TileKey t{static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(z)};
            const float d = distanceTo(t, p);
            if (d <= radius_m) found.emplace_back(d, t);
        }
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<TileKey> tiles;
    tiles.reserve(found.size());
    for (const auto& f : found) tiles.push_back(f.second);
    return tiles;
}

namespace {
// True when all eight corners lie beyond one clip plane (the box is then outside the frustum).
bool boxOutsideFrustum(const glm::mat4& clipFromWorld, glm::vec3 lo, glm::vec3 hi) {
    int outside[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 q = clipFromWorld * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y,
                                                      i & 4 ? hi.z : lo.z, 1.f);
        outside[0] += q.x < -q.w;
        outside[1] += q.x > q.w;
        outside[2] += q.y < -q.w;
        outside[3] += q.y > q.w;
        outside[4] += q.z < -q.w;
        outside[5] += q.z > q.w;
    }
    return std::any_of(std::begin(outside), std::end(outside), [](int n) { return n == 8; });
}
}  // namespace

std::vector<TileKey> TileGrid::tilesInView(glm::vec3 camera, const glm::mat4& clipFromWorld,
                                           float radius_m) const {
    std::vector<TileKey> tiles = tilesNear(camera, radius_m);
    std::erase_if(tiles, [&](TileKey t) {
        glm::vec3 lo, hi;
        boxOf(t, lo, hi);
        return boxOutsideFrustum(clipFromWorld, lo, hi);
    });
    return tiles;
}

TilePool::TilePool(std::size_t slots, float releaseAfter_s)
    : slots_(slots), releaseAfter_s_(releaseAfter_s) {
    for (std::size_t i = slots; i-- > 0;) free_.push_back(static_cast<std::uint32_t>(i));
}

TilePool::Update TilePool::update(const std::vector<TileKey>& needed, float time_s) {
    Update u;
    for (TileKey t : needed) {
        auto it = active_.find(keyOf(t));
        if (it != active_.end()) {
            it->second.lastNeeded_s = time_s;
        } else if (!free_.empty()) {
            const std::uint32_t slot = free_.back();
            free_.pop_back();
            active_.emplace(keyOf(t), Active{slot, time_s});
            u.activated.emplace_back(t, slot);
        } else {
            ++u.refused;
        }
    }
    for (auto it = active_.begin(); it != active_.end();) {
        if (time_s - it->second.lastNeeded_s > releaseAfter_s_ ||
            time_s < it->second.lastNeeded_s) {
            u.released.push_back({static_cast<std::uint32_t>(it->first & 0xffffffffu),
                                  static_cast<std::uint32_t>(it->first >> 32)});
            free_.push_back(it->second.slot);
            it = active_.erase(it);
        } else {
            ++it;
        }
    }
    // The lowest free slot is taken next, so the slots in use stay packed at the front.
    std::sort(free_.begin(), free_.end(), std::greater<>());
    return u;
}

std::optional<std::uint32_t> TilePool::slotOf(TileKey t) const {
    const auto it = active_.find(keyOf(t));
    if (it == active_.end()) return std::nullopt;
    return it->second.slot;
}

std::uint32_t TilePool::slotsInUse() const {
    std::uint32_t end = 0;
    for (const auto& [key, a] : active_) end = std::max(end, a.slot + 1);
    return end;
}

float recoveryTime_s(float etaDecay_per_s, float minStiffness_per_s) {
    const float etaGone_s = etaDecay_per_s > 0.f ? 1.f / etaDecay_per_s : 0.f;
    return etaGone_s + std::log(1000.f) / std::max(minStiffness_per_s, 1e-3f);
}

}  // namespace meadow::runtime
