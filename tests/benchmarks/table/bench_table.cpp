// Google Benchmark's JSON output -> a Markdown table and a CSV: one row per benchmark with its
// label, real and CPU time per iteration, and every counter it reports (benchmarks of one program
// may report different counters; a missing one is a blank cell).
//   meadow_bench_table RAW.json TITLE MADE TABLE.md TABLE.csv
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "meadow/core/atomic_file.h"
#include "meadow/core/json_reader.h"

namespace {

using nlohmann::json;

// Fields Google Benchmark writes for every run; everything else is a counter.
bool isStandardField(const std::string& key) {
    static const std::vector<std::string> standard{"name",
                                                   "family_index",
                                                   "per_family_instance_index",
                                                   "run_name",
                                                   "run_type",
                                                   "repetitions",
                                                   "repetition_index",
                                                   "threads",
                                                   "iterations",
                                                   "real_time",
                                                   "cpu_time",
                                                   "time_unit",
                                                   "label",
                                                   "error_occurred",
                                                   "error_message",
                                                   "aggregate_name",
                                                   "aggregate_unit",
                                                   "big_o",
                                                   "rms"};
    for (const std::string& s : standard)
        if (key == s) return true;
    return false;
}

std::string number(double value) {
    std::ostringstream s;
    s << std::setprecision(4) << value;
    return s.str();
}

std::string cell(const json& run, const std::string& key) {
    const auto it = run.find(key);
    if (it == run.end()) return "";
    if (it->is_number()) return number(it->get<double>());
    if (it->is_string()) return it->get<std::string>();
    return it->dump();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 6) {
        std::cerr << "usage: meadow_bench_table RAW.json TITLE MADE TABLE.md TABLE.csv\n";
        return 2;
    }
    try {
        const json doc = meadow::parseJsonObject(meadow::readTextFile(argv[1]));
        const json& runs = doc.at("benchmarks");
        std::vector<std::string> counters;
        for (const json& run : runs)
            for (const auto& [key, value] : run.items())
                if (!isStandardField(key) && value.is_number() &&
                    std::find(counters.begin(), counters.end(), key) == counters.end())
                    counters.push_back(key);
        std::ostringstream md, csv;
        md << argv[2] << "\n\n| benchmark | label | real time | CPU time |";
        csv << "benchmark,label,real_time,cpu_time,time_unit";
        for (const std::string& c : counters) {
            md << ' ' << c << " |";
            csv << ',' << c;
        }
        md << "\n|---|---|---|---|";
        for (std::size_t i = 0; i < counters.size(); ++i) md << "---|";
        md << '\n';
        csv << '\n';
        for (const json& run : runs) {
            const std::string unit = cell(run, "time_unit");
            md << "| " << cell(run, "name") << " | " << cell(run, "label") << " | "
               << cell(run, "real_time") << ' ' << unit << " | " << cell(run, "cpu_time") << ' '
               << unit << " |";
            csv << cell(run, "name") << ',' << cell(run, "label") << ',' << cell(run, "real_time")
                << ',' << cell(run, "cpu_time") << ',' << unit;
            for (const std::string& c : counters) {
                md << ' ' << cell(run, c) << " |";
                csv << ',' << cell(run, c);
            }
            md << '\n';
            csv << '\n';
        }
        md << "\nMade by `./meadow.sh measure`: " << argv[3] << ".\n";
        meadow::writeFileAtomically(argv[4], md.str());
        meadow::writeFileAtomically(argv[5], csv.str());
    } catch (const std::exception& e) {
        std::cerr << "meadow_bench_table: " << argv[1] << ": " << e.what() << '\n';
        return 2;
    }
    return 0;
}
