#pragma once
// Statistics, timing and output shared by the benches that write tables: medians and means, fixed
// decimals, the thread's CPU time, files written atomically, and charts drawn by tools/chart.sh.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace meadow::bench {

template <class T>
double median(std::vector<T> v) {
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    if (v.size() % 2 == 1) return static_cast<double>(*mid);
    const T upper = *mid;
    const T lower = *std::max_element(v.begin(), mid);
    return 0.5 * (static_cast<double>(lower) + static_cast<double>(upper));
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
    to.insert(to.end(), from.begin(), from.end());
}

template <class T>
double mean(const std::vector<T>& v) {
    if (v.empty()) return 0.0;
    double sum = 0.0;
    for (const T& x : v) sum += static_cast<double>(x);
    return sum / static_cast<double>(v.size());
}

std::string fixed(double value, int decimals);

// A CSV cell: blank when nothing was measured (gnuplot then draws no point).
template <class T>
std::string orBlank(const std::vector<T>& values, double value, int decimals) {
    return values.empty() ? std::string() : fixed(value, decimals);
}

std::string noiseName(float noise);

// Times `work` `repetitions` times: median wall (steady_clock) and thread CPU time in ms.
struct Timing {
    double wall_ms = 0.0, cpu_ms = 0.0;
};
Timing timeMedian(int repetitions, const std::function<void()>& work);

// Writes `text` atomically; a Markdown file ends with the provenance line, when one is set.
void writeText(const std::filesystem::path& path, const std::string& text);
// "commit 1a2b3c4 on 2026-12-03, 2 cores ...": which code made the tables, when, on what.
void setMadeLine(const std::string& made);

// A PNG of `y` against `x`, one line per value of column `series`, from `csv` (tools/chart.sh).
void chart(const std::filesystem::path& csv, const std::filesystem::path& png,
           const std::string& title, const std::string& x, const std::string& y,
           const std::string& series, const std::string& xLabel, const std::string& yLabel,
           const std::string& scale = "");

// "overlapping x2, too-thin x1, no blades x3" (frames with an empty result), or "-".
std::string flagCounts(const std::map<std::string, int>& counts, int emptyFrames);

// Trade-off CSV rows: chart.sh joins a series' points in file order, so within each knob the
// rows are written by increasing time (the knob's values are in the CSV's value column).
struct TradeoffRow {
    std::string knob;
    double time_ms = 0.0;
    std::string line;
};
std::string sortedRows(std::vector<TradeoffRow> rows);

}  // namespace meadow::bench
