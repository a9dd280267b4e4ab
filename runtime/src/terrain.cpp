#include "terrain.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace meadow::runtime {

glm::vec2 HeightField::spacing_m() const {
    return (maxXZ_m - minXZ_m) /
           glm::vec2(static_cast<float>(height_m.cols - 1), static_cast<float>(height_m.rows - 1));
}

float HeightField::heightAt(glm::vec2 xz_m) const {
    const glm::vec2 g = (xz_m - minXZ_m) / spacing_m();
    const float x = std::clamp(g.x, 0.f, static_cast<float>(height_m.cols - 1));
    const float z = std::clamp(g.y, 0.f, static_cast<float>(height_m.rows - 1));
    const int x0 = std::min(static_cast<int>(x), height_m.cols - 2);
    const int z0 = std::min(static_cast<int>(z), height_m.rows - 2);
    const float fx = x - static_cast<float>(x0), fz = z - static_cast<float>(z0);
    const auto h = [&](int r, int c) { return height_m.at<float>(r, c); };
    return (1.f - fz) * ((1.f - fx) * h(z0, x0) + fx * h(z0, x0 + 1)) +
           fz * ((1.f - fx) * h(z0 + 1, x0) + fx * h(z0 + 1, x0 + 1));
}

glm::vec3 HeightField::normalAt(glm::vec2 xz_m) const {
    const glm::vec2 d = spacing_m();
    const float dx = heightAt(xz_m + glm::vec2(d.x, 0.f)) - heightAt(xz_m - glm::vec2(d.x, 0.f));
    const float dz = heightAt(xz_m + glm::vec2(0.f, d.y)) - heightAt(xz_m - glm::vec2(0.f, d.y));
    return glm::normalize(glm::vec3(-dx / (2.f * d.x), 1.f, -dz / (2.f * d.y)));
}

HeightField makeHeightField(const TerrainDescription& t) {
    HeightField f;
    f.minXZ_m = t.minXZ_m;
    f.maxXZ_m = t.maxXZ_m;
    const cv::Size size(t.samples, t.samples);
    cv::Mat sum = cv::Mat::zeros(size, CV_32F);
    cv::RNG rng(t.seed);
    const float extent_m = std::max(t.maxXZ_m.x - t.minXZ_m.x, t.maxXZ_m.y - t.minXZ_m.y);
    float amplitude = 1.f;
    // Octaves down to four grid samples per lattice cell: finer ones would alias on the grid.
    for (float feature_m = t.featureSize_m;; feature_m *= 0.5f, amplitude *= 0.5f) {
        const int cells = std::max(1, static_cast<int>(std::ceil(extent_m / feature_m)));
        if (cells * 4 > t.samples && feature_m < t.featureSize_m) break;
        cv::Mat lattice(cells + 1, cells + 1, CV_32F);
        rng.fill(lattice, cv::RNG::UNIFORM, 0.f, 1.f);
        cv::Mat octave;
        cv::resize(lattice, octave, size, 0, 0, cv::INTER_CUBIC);
        sum += amplitude * octave;
        if (cells * 4 > t.samples) break;
    }
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(sum, &lo, &hi);
    const double span = hi - lo;
    sum.convertTo(f.height_m, CV_32F, span > 0.0 ? t.relief_m / span : 0.0,
                  span > 0.0 ? -lo * t.relief_m / span : 0.0);
    return f;
}

TriangleMesh terrainMesh(const HeightField& field) {
    TriangleMesh mesh;
    mesh.origin = "terrain";
    const int cols = field.height_m.cols, rows = field.height_m.rows;
    const glm::vec2 d = field.spacing_m();
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const glm::vec2 xz =
                field.minXZ_m + glm::vec2(static_cast<float>(c) * d.x, static_cast<float>(r) * d.y);
            mesh.positions_m.emplace_back(xz.x, field.height_m.at<float>(r, c), xz.y);
            mesh.normals.push_back(field.normalAt(xz));
        }
    for (int r = 0; r + 1 < rows; ++r)
        for (int c = 0; c + 1 < cols; ++c) {
            const auto i = static_cast<unsigned>(r * cols + c);
            const auto w = static_cast<unsigned>(cols);
            // Counter-clockwise seen from above (+Y).
            mesh.triangles.emplace_back(i, i + w, i + 1);
            mesh.triangles.emplace_back(i + 1, i + w, i + w + 1);
        }
    return mesh;
}

cv::Mat tileHeightRanges(const HeightField& field, float tileSize_m) {
    const glm::vec2 extent = field.maxXZ_m - field.minXZ_m;
    const int tilesX = std::max(1, static_cast<int>(std::ceil(extent.x / tileSize_m)));
    const int tilesZ = std::max(1, static_cast<int>(std::ceil(extent.y / tileSize_m)));
    cv::Mat ranges(tilesZ, tilesX, CV_32FC2);
    const glm::vec2 d = field.spacing_m();
    for (int tz = 0; tz < tilesZ; ++tz)
        for (int tx = 0; tx < tilesX; ++tx) {
            // Every grid sample under the tile and the one past each edge: bilinear heights lie
            // between them.
            const glm::vec2 lo = glm::vec2(tx, tz) * tileSize_m / d;
            const glm::vec2 hi = glm::vec2(tx + 1, tz + 1) * tileSize_m / d;
            const int c0 =
                std::clamp(static_cast<int>(std::floor(lo.x)), 0, field.height_m.cols - 1);
            const int c1 =
                std::clamp(static_cast<int>(std::ceil(hi.x)), 0, field.height_m.cols - 1);
            const int r0 =
                std::clamp(static_cast<int>(std::floor(lo.y)), 0, field.height_m.rows - 1);
            const int r1 =
                std::clamp(static_cast<int>(std::ceil(hi.y)), 0, field.height_m.rows - 1);
            double mn = 0.0, mx = 0.0;
            cv::minMaxLoc(field.height_m(cv::Range(r0, r1 + 1), cv::Range(c0, c1 + 1)), &mn, &mx);
            ranges.at<cv::Vec2f>(tz, tx) = {static_cast<float>(mn), static_cast<float>(mx)};
        }
    return ranges;
}

}  // namespace meadow::runtime
