#include "plant_points_io.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "meadow/core/library_messages.h"
#include "meadow/synth/error.h"

namespace meadow::synth::plant {
namespace {

bool skipped(const std::string& line) {
    const auto first = line.find_first_not_of(" \t\r");
    return first == std::string::npos || line[first] == '#';
}

bool finite(const glm::vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

std::ifstream openText(const std::filesystem::path& file, const char* what) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw SynthError(file.string() + ": no such " + what + " file; check the path");
    std::ifstream in(file);
    if (!in) throw SynthError(file.string() + ": cannot open the " + what + " file");
    return in;
}

}  // namespace

LabelledPoints readPointText(const std::filesystem::path& file) {
    std::ifstream in = openText(file, "point");
    LabelledPoints out;
    std::string line;
    for (long number = 1; std::getline(in, line); ++number) {
        if (skipped(line)) continue;
        std::istringstream fields(line);
        glm::vec3 p;
        double label = 0.0;
        std::string extra;
        if (!(fields >> p.x >> p.y >> p.z >> label) || (fields >> extra) || !finite(p) ||
            label < 0.0 || label != std::floor(label) || label > 1e6)
            throw SynthError(file.string() + ": line " + std::to_string(number) +
                             " is not \"x y z label\" (finite numbers, an integer label >= 0): '" +
                             line.substr(0, 60) + "'");
        out.points.push_back(p);
        out.labels.push_back(static_cast<int>(label));
    }
    if (out.points.empty()) throw SynthError(file.string() + ": holds no points");
    return out;
}

LabelledPoints readPointPly(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw SynthError(file.string() + ": no such point file; check the path");
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    pcl::PCLPointCloud2 cloud;
    int status = -1;
    std::string said;
    {
        CapturedStderr messages;  // PCL reports a broken header on stderr, in several lines
        pcl::PLYReader reader;
        status = reader.read(file.string(), cloud);
        said = messages.text();
    }
    if (status < 0 || cloud.width * cloud.height == 0)
        throw SynthError(file.string() + ": not a readable PLY point cloud" +
                         (said.empty() ? std::string() : " (" + said + ")"));
    const auto has = [&](const char* name) {
        return std::any_of(cloud.fields.begin(), cloud.fields.end(),
                           [&](const pcl::PCLPointField& f) { return f.name == name; });
    };
    if (!has("x") || !has("y") || !has("z"))
        throw SynthError(file.string() + ": the PLY has no x, y, z properties");
    LabelledPoints out;
    if (has("label")) {
        pcl::PointCloud<pcl::PointXYZL> points;
        pcl::fromPCLPointCloud2(cloud, points);
        for (const auto& p : points) {
            out.points.emplace_back(p.x, p.y, p.z);
            out.labels.push_back(static_cast<int>(p.label));
        }
    } else {
        pcl::PointCloud<pcl::PointXYZ> points;
        pcl::fromPCLPointCloud2(cloud, points);
        for (const auto& p : points) out.points.emplace_back(p.x, p.y, p.z);
    }
    for (std::size_t i = 0; i < out.points.size(); ++i)
        if (!finite(out.points[i]))
            throw SynthError(file.string() + ": point " + std::to_string(i) +
                             " has a coordinate that is not a finite number");
    return out;
}

LabelledPoints readLabelledPoints(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".ply" ? readPointPly(file) : readPointText(file);
}

SkeletonGraph readSkeletonGraph(const std::filesystem::path& file) {
    std::ifstream in = openText(file, "skeleton graph");
    SkeletonGraph g;
    std::string line;
    for (long number = 1; std::getline(in, line); ++number) {
        if (skipped(line)) continue;
        std::istringstream fields(line);
        std::string kind, extra;
        fields >> kind;
        const auto fail = [&](const std::string& why) {
            throw SynthError(file.string() + ": line " + std::to_string(number) + " " + why +
                             ": '" + line.substr(0, 60) + "'");
        };
        if (kind == "v") {
            glm::vec3 p;
            double organ = -1.0;  // written "1" or "1." by different tools
            if (!(fields >> p.x >> p.y >> p.z >> organ) || (fields >> extra) || !finite(p) ||
                organ < 0.0 || organ != std::floor(organ) || organ > 1e6)
                fail("is not \"v x y z organ\" (an organ id >= 0, 0 the stem)");
            g.nodes.push_back(p);
            g.organ.push_back(static_cast<int>(organ));
        } else if (kind == "e") {
            long a = -1, b = -1;
            if (!(fields >> a >> b) || (fields >> extra)) fail("is not \"e i j\"");
            g.edges.emplace_back(static_cast<int>(a), static_cast<int>(b));
        } else {
            fail("starts with neither v nor e");
        }
    }
    for (const auto& [a, b] : g.edges)
        if (a < 0 || b < 0 || a >= static_cast<long>(g.nodes.size()) ||
            b >= static_cast<long>(g.nodes.size()))
            throw SynthError(file.string() + ": an edge names node " +
                             std::to_string(std::max(a, b)) + " of " +
                             std::to_string(g.nodes.size()));
    if (g.nodes.empty() || g.edges.empty())
        throw SynthError(file.string() + ": holds no skeleton (no v or no e lines)");
    if (std::find(g.organ.begin(), g.organ.end(), 0) == g.organ.end())
        throw SynthError(file.string() + ": no node of organ 0 (the stem)");
    return g;
}

}  // namespace meadow::synth::plant
