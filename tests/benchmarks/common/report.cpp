// Statistics, timing and output shared by the table-writing benches (report.h).
#include "common/report.h"

#include <time.h>

#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "meadow/core/atomic_file.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;

double threadCpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

}  // namespace

std::string fixed(double value, int decimals) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << value;
    return s.str();
}

std::string noiseName(float noise) { return fixed(noise, 0) + "x"; }

Timing timeMedian(int repetitions, const std::function<void()>& work) {
    std::vector<double> wall, cpu;
    for (int r = 0; r < repetitions; ++r) {
        const double c0 = threadCpu_ms();
        const auto t0 = std::chrono::steady_clock::now();
        work();
        const auto t1 = std::chrono::steady_clock::now();
        cpu.push_back(threadCpu_ms() - c0);
        wall.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    return {median(wall), median(cpu)};
}

std::string& madeLine() {
    static std::string made;
    return made;
}

void setMadeLine(const std::string& made) { madeLine() = made; }

void writeText(const fs::path& path, const std::string& text) {
    if (path.extension() == ".md" && !madeLine().empty())
        writeFileAtomically(path, text + "\nMade by `./meadow.sh measure`: " + madeLine() + ".\n");
    else
        writeFileAtomically(path, text);
    std::cout << "  wrote " << path.string() << '\n';
}

void chart(const fs::path& csv, const fs::path& png, const std::string& title, const std::string& x,
           const std::string& y, const std::string& series, const std::string& xLabel,
           const std::string& yLabel, const std::string& scale) {
    const fs::path script = fs::path(MEADOW_SOURCE_DIR) / "tools" / "chart.sh";
    const auto quote = [](const std::string& s) {  // one shell word, quotes in it escaped
        std::string q = "'";
        for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return q + "'";
    };
    const std::string command = quote(script.string()) + ' ' + quote(csv.string()) + ' ' +
                                quote(png.string()) + ' ' + quote(title) + ' ' + x + ' ' + y + ' ' +
                                series + ' ' + quote(xLabel) + ' ' + quote(yLabel) + ' ' + scale;
    if (std::system(command.c_str()) != 0)
        std::cerr << "  chart.sh failed for " << png.string() << " (is gnuplot installed?)\n";
    else
        std::cout << "  wrote " << png.string() << '\n';
}

std::string flagCounts(const std::map<std::string, int>& counts, int emptyFrames) {
    std::string text;
    for (const auto& [name, n] : counts)
        text += (text.empty() ? "" : ", ") + name + " x" + std::to_string(n);
    if (emptyFrames > 0)
        text +=
            (text.empty() ? "" : ", ") + std::string("no blades x") + std::to_string(emptyFrames);
    return text.empty() ? "-" : text;
}

std::string sortedRows(std::vector<TradeoffRow> rows) {
    std::vector<std::string> knobOrder;
    for (const TradeoffRow& r : rows)
        if (std::find(knobOrder.begin(), knobOrder.end(), r.knob) == knobOrder.end())
            knobOrder.push_back(r.knob);
    const auto rank = [&](const std::string& knob) {
        return std::find(knobOrder.begin(), knobOrder.end(), knob) - knobOrder.begin();
    };
    std::stable_sort(rows.begin(), rows.end(), [&](const TradeoffRow& a, const TradeoffRow& b) {
        return rank(a.knob) != rank(b.knob) ? rank(a.knob) < rank(b.knob) : a.time_ms < b.time_ms;
    });
    std::string text;
    for (const TradeoffRow& r : rows) text += r.line;
    return text;
}

}  // namespace meadow::bench
