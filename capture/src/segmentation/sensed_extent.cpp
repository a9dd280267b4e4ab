// Where the sensor saw anything. A structured-light camera reads nothing in a band along some
// image borders (the Kinect-class recording in ../shared/data: the first 33-45 columns, varying
// with depth, 37 rows at the top, 2 at the bottom, 10 or more columns at the right). A blade
// that reaches such a band may go on inside it, as it may past the image border.
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {
// A band wider than this share of the frame is not the sensor's: a row of ground seen at a
// grazing angle reads nothing for hundreds of pixels, up to the tuft standing on it.
constexpr float kMaxBandFraction = 0.1f;
}  // namespace

SensedExtent SensedExtent::whole(cv::Size frame) {
    SensedExtent e;
    e.firstX.assign(static_cast<size_t>(frame.height), 0);
    e.lastX.assign(static_cast<size_t>(frame.height), frame.width - 1);
    e.firstY.assign(static_cast<size_t>(frame.width), 0);
    e.lastY.assign(static_cast<size_t>(frame.width), frame.height - 1);
    return e;
}

SensedExtent SensedExtent::of(const cv::Mat1w& depth_mm) {
    SensedExtent e = whole(depth_mm.size());
    const int maxColumns = static_cast<int>(kMaxBandFraction * static_cast<float>(depth_mm.cols));
    const int maxRows = static_cast<int>(kMaxBandFraction * static_cast<float>(depth_mm.rows));
    for (int y = 0; y < depth_mm.rows; ++y) {
        const auto* row = depth_mm[y];
        int first = 0, last = depth_mm.cols - 1;
        while (first <= maxColumns && row[first] == 0) ++first;
        while (last >= depth_mm.cols - 1 - maxColumns && row[last] == 0) --last;
        if (first <= maxColumns) e.firstX[static_cast<size_t>(y)] = first;
        if (last >= depth_mm.cols - 1 - maxColumns) e.lastX[static_cast<size_t>(y)] = last;
    }
    // Columns from the top and from the bottom, a row at a time (rows are contiguous).
    std::vector<char> open(static_cast<size_t>(depth_mm.cols), 1);
    for (int y = 0; y <= maxRows; ++y) {
        const auto* row = depth_mm[y];
        for (int x = 0; x < depth_mm.cols; ++x)
            if (open[static_cast<size_t>(x)] && row[x] != 0) {
                open[static_cast<size_t>(x)] = 0;
                e.firstY[static_cast<size_t>(x)] = y;
            }
    }
    open.assign(open.size(), 1);
    for (int y = depth_mm.rows - 1; y >= depth_mm.rows - 1 - maxRows; --y) {
        const auto* row = depth_mm[y];
        for (int x = 0; x < depth_mm.cols; ++x)
            if (open[static_cast<size_t>(x)] && row[x] != 0) {
                open[static_cast<size_t>(x)] = 0;
                e.lastY[static_cast<size_t>(x)] = y;
            }
    }
    return e;
}

bool SensedExtent::atEdge(cv::Point p) const {
    if (p.y < 0 || p.x < 0 || p.y >= static_cast<int>(firstX.size()) ||
        p.x >= static_cast<int>(firstY.size()))
        return true;
    const auto y = static_cast<size_t>(p.y), x = static_cast<size_t>(p.x);
    // Within a pixel: edge smoothing moves a contour by up to one.
    return p.x <= firstX[y] + 1 || p.x >= lastX[y] - 1 || p.y <= firstY[x] + 1 ||
           p.y >= lastY[x] - 1;
}

bool SensedExtent::atBottom(cv::Point p) const {
    if (p.x < 0 || p.x >= static_cast<int>(lastY.size())) return true;
    return p.y >= lastY[static_cast<size_t>(p.x)] - 1;
}

}  // namespace meadow::capture::segmentation
