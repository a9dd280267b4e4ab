// The real-plant benchmark: the six Label3DMaize shoots (../shared/data/real/maize-label3d) on a
// phenotyping bench, 12 turntable views each, through every simulated sensor, rendered into a
// test set in the build folder (meadow synth --plant's files, not committed); today's capture
// run on each view alone; its library scored against the truth (synth/library_score.h) beside
// the plain leaf counter (synth/leaf_counter.h); the synthetic tuft presets scored the same way.
// Writes plant_benchmark.md and .csv, and plant_turntable.csv (the .md's turntable section), into
// --out. Run by tools/measure.sh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/report.h"
#include "meadow/capture/depth_source.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/modeling/error.h"
#include "meadow/synth/leaf_counter.h"
#include "meadow/synth/library_score.h"
#include "meadow/synth/plant_synthesize.h"
#include "meadow/synth/synthesize.h"
#include "plant/stem_truth.h"
#include "plant/truth_partition.h"
#include "plant/turntable_library.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kPlants{"v-3-1", "v-3-2", "v-6-1", "v-6-2", "v-9-1", "v-12-1"};
const std::vector<std::string> kTuftPresets{"quadratic-leaf", "shrub-leaf", "bamboo-leaf",
                                            "sharp-tip", "slim-grass"};

// Per frame: all of capture; finding the plant (depth band, plane removal, plant finding);
// cutting it into blades (partition).
struct FrameTimes {
    std::vector<double> capture_ms, finding_ms, partition_ms;
    void add(const FrameTimes& o) {
        append(capture_ms, o.capture_ms);
        append(finding_ms, o.finding_ms);
        append(partition_ms, o.partition_ms);
    }
};

struct Row {
    std::string set, sensor, what, finding;
    int views = 0, leaves = 0, matched = 0;
    int anyViewLeaves = 0, anyViewMatched = 0;  // per plant, summed: synth::AnyViewScore
    std::vector<float> bestLengthError;
    std::array<double, 7> falseBlades{};  // summed over views, by FalseBladeOn
    std::vector<float> lengthError, widthError, baseMissed, tipMissed;
    std::vector<float> upsideDown;  // 1 or 0 per matched leaf spanned far enough to tell
    std::vector<float> stemError;   // |measured - true| / true stem height, one per plant
    double countError = 0.0, baselineCountError = 0.0;  // summed over views
    FrameTimes times;
    [[nodiscard]] double recall() const { return leaves ? double(matched) / leaves : 0.0; }
    [[nodiscard]] double anyViewRecall() const {
        return anyViewLeaves ? double(anyViewMatched) / anyViewLeaves : 0.0;
    }
    void add(const Row& o) {
        views += o.views, leaves += o.leaves, matched += o.matched;
        anyViewLeaves += o.anyViewLeaves, anyViewMatched += o.anyViewMatched;
        for (std::size_t k = 0; k < falseBlades.size(); ++k) falseBlades[k] += o.falseBlades[k];
        for (auto list : {&Row::lengthError, &Row::widthError, &Row::baseMissed, &Row::tipMissed,
                          &Row::upsideDown, &Row::stemError, &Row::bestLengthError})
            append(this->*list, o.*list);
        countError += o.countError, baselineCountError += o.baselineCountError;
        times.add(o.times);
    }
};

// Capture as `meadow capture` runs it, each frame alone (the plant turns between views), one
// archetype per blade and frame. An empty library when nothing could be modelled.
// A way of capturing: how the plant is found and how it is cut into blades.
struct Method {
    capture::PlantFinding finding;
    capture::PartitionMethod partition;
    [[nodiscard]] std::string name() const {
        return std::string(capture::kPlantFindingNames.name(finding)) + " + " +
               std::string(capture::kPartitionMethodNames.name(partition));
    }
};

// Fills `times`, one value a frame (each frame's share of the run's time).
modeling::ArchetypeLibrary captureEachFrame(const fs::path& recording, int frames,
                                            FrameTimes& times, bool perFrame,
                                            const Method& method) {
    auto source = capture::openDepthSource(recording.string());
    modeling::CaptureOptions options;
    options.segmenter.plantFinding = method.finding;
    options.segmenter.partition = method.partition;
    if (perFrame) {
        options.groups.fusionFrames = 1;
        options.groups.checkMotion = false;
        options.tracks.enabled = false;
    }
    const auto start = std::chrono::steady_clock::now();
    modeling::CaptureResult result;
    try {
        result = modeling::captureArchetypes(*source, recording.string(), options);
    } catch (const modeling::ModelingError&) {
    }
    const double total =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const auto stage = [&](const char* name) {
        const auto it = result.summary.stage_ms.find(name);
        return it == result.summary.stage_ms.end() ? 0.0 : it->second;
    };
    const double finding = stage("depth band") + stage("plane removal") + stage("plant finding");
    for (int i = 0; i < frames; ++i) {
        times.capture_ms.push_back(total / frames);
        if (result.summary.segmentations > 0) {
            times.finding_ms.push_back(finding / frames);
            times.partition_ms.push_back(stage("partition") / frames);
        }
    }
    // Scored as a user gets it, written and read back: a value the library's reader refuses (and
    // `meadow render` with it) stops the bench here, naming the view.
    if (result.library.archetypes.empty()) return result.library;
    const fs::path file = fs::temp_directory_path() /
                          ("meadow-plant-bench-" + recording.parent_path().filename().string() +
                           "-" + recording.filename().string() + ".json");
    modeling::saveArchetypeLibrary(result.library, file);
    modeling::ArchetypeLibrary readBack = modeling::loadArchetypeLibrary(file);
    fs::remove(file);
    return readBack;
}

// Capture as `meadow capture --turntable` runs it: each frame alone, the views registered and each
// leaf's archetypes joined. An empty library when nothing could be modelled.
modeling::CaptureResult captureTurntable(const fs::path& recording, const Method& method,
                                         const modeling::CaptureOptions& defaults) {
    auto source = capture::openDepthSource(recording.string());
    modeling::CaptureOptions options = defaults;
    options.segmenter.plantFinding = method.finding;
    options.segmenter.partition = method.partition;
    options.groups.turning = true;
    try {
        return modeling::captureArchetypes(*source, recording.string(), options);
    } catch (const modeling::ModelingError&) {
        return {};
    }
}

// The rows of the truth's own leaves, each modelled as capture models a blade: carried to where
// its true centre line starts, and as far down as the sensor read it.
struct TruthRow {
    const char* name;
    TruthBase base;
};
constexpr TruthRow kTruthRows[] = {{"truth leaves (bound)", TruthBase::WhereItStarts},
                                   {"truth leaves as seen (bound)", TruthBase::LowestSeen}};

// The baseline's depth band: the plant's distance from the camera +- kBaselineBand_m, as a user
// would set it.
constexpr float kBaselineBand_m = 0.3f;

Row score(const modeling::ArchetypeLibrary& library, const synth::ScoringTruth& truth,
          const fs::path& recording, float plantDistance_m) {
    const synth::LibraryScore s = synth::scoreLibrary(library, truth);
    Row row;
    row.views = static_cast<int>(s.views.size());
    const synth::AnyViewScore any = s.anyView();
    row.anyViewLeaves = any.leaves, row.anyViewMatched = any.matched;
    row.bestLengthError = any.bestLengthError;
    for (std::size_t v = 0; v < s.views.size(); ++v) {
        const synth::ViewScore& vs = s.views[v];
        row.leaves += vs.leaves, row.matched += vs.matched;
        for (std::size_t k = 0; k < row.falseBlades.size(); ++k)
            row.falseBlades[k] += vs.falseBlades[k];
        append(row.lengthError, vs.lengthError);
        append(row.widthError, vs.widthError);
        append(row.baseMissed, vs.baseMissed);
        append(row.tipMissed, vs.tipMissed);
        append(row.upsideDown, vs.upsideDown);
        row.countError += std::abs(vs.archetypes - vs.leaves);
        char name[32];
        std::snprintf(name, sizeof name, "%06d.png", vs.frame);
        const cv::Mat depth =
            cv::imread((recording / "depth" / name).string(), cv::IMREAD_UNCHANGED);
        row.baselineCountError +=
            std::abs(synth::countLeavesPlainly(depth, plantDistance_m - kBaselineBand_m,
                                               plantDistance_m + kBaselineBand_m) -
                     vs.leaves);
    }
    return row;
}

std::string cells(const Row& r) {
    const FrameTimes& t = r.times;
    const double views = std::max(r.views, 1);
    std::ostringstream out;
    out << r.views << " | " << r.leaves << " | " << fixed(r.recall(), 2) << " | "
        << fixed(r.anyViewRecall(), 2) << " | "
        << (r.bestLengthError.empty() ? "-" : fixed(100.0 * median(r.bestLengthError), 0) + " %")
        << " | ";
    double falseTotal = 0.0;
    for (double f : r.falseBlades) falseTotal += f;
    out << fixed(falseTotal / views, 2) << " | ";
    std::string by;
    for (std::size_t k = 0; k < r.falseBlades.size(); ++k)
        if (r.falseBlades[k] > 0)
            by += (by.empty() ? "" : ", ") +
                  std::string(synth::kFalseBladeOnNames.name(static_cast<synth::FalseBladeOn>(k))) +
                  " " + fixed(r.falseBlades[k] / views, 2);
    out << (by.empty() ? "-" : by) << " | "
        << (r.lengthError.empty() ? "-" : fixed(100.0 * median(r.lengthError), 0) + " %") << " | "
        << (r.baseMissed.empty() ? "-"
                                 : fixed(100.0 * median(r.baseMissed), 0) + " % / " +
                                       fixed(100.0 * median(r.tipMissed), 0) + " %")
        << " | " << (r.upsideDown.empty() ? "-" : fixed(100.0 * mean(r.upsideDown), 0) + " %")
        << " | " << (r.widthError.empty() ? "-" : fixed(100.0 * median(r.widthError), 0) + " %")
        << " | " << (r.stemError.empty() ? "-" : fixed(100.0 * median(r.stemError), 0) + " %")
        << " | " << fixed(r.countError / views, 1) << " | "
        << fixed(r.baselineCountError / views, 1) << " | "
        << (t.capture_ms.empty() ? "-" : fixed(median(t.capture_ms), 0)) << " | "
        << (t.finding_ms.empty() ? "-" : fixed(median(t.finding_ms), 0)) << " | "
        << (t.partition_ms.empty() ? "-" : fixed(median(t.partition_ms), 1));
    return out.str();
}

std::string csvRow(const Row& r) {
    const FrameTimes& t = r.times;
    const double views = std::max(r.views, 1);
    std::ostringstream out;
    out << r.set << ',' << r.sensor << ',' << r.finding << ',' << r.what << ',' << r.views << ','
        << r.leaves << ',' << fixed(r.recall(), 3) << ',' << fixed(r.anyViewRecall(), 3) << ','
        << orBlank(r.bestLengthError, median(r.bestLengthError), 3);
    for (double f : r.falseBlades) out << ',' << fixed(f / views, 3);
    out << ',' << orBlank(r.lengthError, median(r.lengthError), 3) << ','
        << orBlank(r.baseMissed, median(r.baseMissed), 3) << ','
        << orBlank(r.tipMissed, median(r.tipMissed), 3) << ','
        << orBlank(r.upsideDown, mean(r.upsideDown), 3) << ','
        << orBlank(r.widthError, median(r.widthError), 3) << ','
        << orBlank(r.stemError, median(r.stemError), 3) << ',' << fixed(r.countError / views, 2)
        << ',' << fixed(r.baselineCountError / views, 2) << ','
        << orBlank(t.capture_ms, median(t.capture_ms), 1) << ','
        << orBlank(t.finding_ms, median(t.finding_ms), 1) << ','
        << orBlank(t.partition_ms, median(t.partition_ms), 2);
    return out.str();
}

int run(int argc, char** argv) {
    fs::path out = "docs/measurements", data = fs::path(MEADOW_SOURCE_DIR) / "../shared/data/real",
             set = fs::path(MEADOW_SOURCE_DIR) / "build/plant-bench";
    bool quick = false, reuse = false, defaultOnly = false;
    std::string onlySensor, onlyPlant;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick")
            quick = true;
        else if (arg == "--reuse-set")
            reuse = true;
        else if (arg == "--default-only")
            defaultOnly = true;
        else if (arg == "--sensor" && i + 1 < argc)
            onlySensor = argv[++i];
        else if (arg == "--plant" && i + 1 < argc)
            onlyPlant = argv[++i];
        else if (arg == "--out" && i + 1 < argc)
            out = argv[++i];
        else if (arg == "--data" && i + 1 < argc)
            data = argv[++i];
        else if (arg == "--set" && i + 1 < argc)
            set = argv[++i];
        else if (arg == "--made" && i + 1 < argc)
            setMadeLine(argv[++i]);
        else {
            std::cerr
                << "usage: " << argv[0]
                << " [--out DIR] [--data DIR] [--set DIR] [--reuse-set] [--quick] [--made TEXT]\n"
                   "       [--sensor NAME] [--plant NAME] [--default-only]\n"
                   "  --data DIR  the shared real data (default ../shared/data/real)\n"
                   "  --set DIR   where the rendered test set goes (default build/plant-bench)\n"
                   "  --reuse-set keep the views already rendered there (same plant, sensor, "
                   "views)\n"
                   "  --quick     two plants, four views, one sensor: a smoke run\n"
                   "  --sensor NAME   that sensor's views only (kinect-v1, kinect-v2, "
                   "realsense-d435)\n"
                   "  --plant NAME    that plant's views only (v-3-1, ..., v-12-1)\n"
                   "  --default-only  only the way --subject potted-plant sets: no other way, no "
                   "bound\n";
            return 2;
        }
    }
    std::cout << std::unitbuf;
    cv::setNumThreads(0);
    fs::create_directories(out);
    std::vector<std::string> plants = quick ? std::vector<std::string>{"v-3-1", "v-9-1"} : kPlants;
    if (!onlyPlant.empty()) {
        if (std::find(plants.begin(), plants.end(), onlyPlant) == plants.end()) {
            std::cerr << "plant bench: no plant named " << onlyPlant << "\n";
            return 2;
        }
        plants = {onlyPlant};
    }
    std::vector<std::string> sensors =
        quick ? std::vector<std::string>{"kinect-v1"} : synth::plantSensorNames();
    if (!onlySensor.empty()) {
        if (std::find(sensors.begin(), sensors.end(), onlySensor) == sensors.end()) {
            std::cerr << "plant bench: no sensor named " << onlySensor << "\n";
            return 2;
        }
        sensors = {onlySensor};
    }
    const int views = quick ? 4 : 12;
    std::vector<Row> rows;
    const fs::path scans = data / "maize-label3d";
    const bool haveScans = fs::exists(scans);
    if (!haveScans) std::cout << "plant bench: " << scans << " absent; real plants skipped\n";
    std::vector<Method> findings{
        {capture::PlantFinding::DepthMode, capture::PartitionMethod::Contour},
        {capture::PlantFinding::Clusters, capture::PartitionMethod::Contour},
        {capture::PlantFinding::Clusters, capture::PartitionMethod::StemGraph}};
    if (defaultOnly) {  // the way --subject potted-plant sets, whatever the order above
        capture::SegmenterParams potted;
        potted.setSubject(capture::Subject::PottedPlant);
        std::erase_if(findings, [&](const Method& m) {
            return m.finding != potted.plantFinding || m.partition != potted.partition;
        });
    }
    const auto findingName = [](const Method& m) { return m.name(); };
    // The last two kinds of row per sensor: the truth's own leaves, modelled (the partition's
    // bounds).
    const std::size_t kinds = findings.size() + (defaultOnly ? 0 : std::size(kTruthRows));
    const auto truthRow = [&](std::size_t f) { return kTruthRows[f - findings.size()]; };
    const auto kindName = [&](std::size_t f) {
        return f < findings.size() ? findingName(findings[f]) : std::string(truthRow(f).name);
    };
    std::vector<TurntableRow> turntableRows;
    const Method turntableMethod{capture::PlantFinding::Clusters,
                                 capture::PartitionMethod::StemGraph};
    for (const std::string& sensor : haveScans ? sensors : std::vector<std::string>{}) {
        TurntableRow turntableTotal;
        turntableTotal.sensor = sensor, turntableTotal.plant = "all";
        std::vector<Row> totals(kinds);
        std::vector<std::vector<Row>> perPlant(kinds);
        for (const std::string& plant : plants) {
            synth::PlantSynthOptions o;
            o.plant = scans / (plant + "-l-r.txt");
            o.views.views = views;
            o.sensor = sensor;
            o.out = set / sensor / plant;
            // A set rendered for another run (a --quick one's four views) is rendered again.
            const fs::path truthFile = o.out / "truth" / "plant.json";
            if (!(reuse && fs::exists(truthFile) &&
                  synth::readPlantTruth(truthFile).views.size() == static_cast<std::size_t>(views)))
                synth::synthesizePlant(o);
            const synth::PlantTruth truth = synth::readPlantTruth(truthFile);
            const synth::ScoringTruth scoring = synth::scoringTruthOf(truth, o.out / "truth");
            for (std::size_t f = 0; f < kinds; ++f) {
                FrameTimes times;
                const modeling::ArchetypeLibrary library =
                    f < findings.size() ? captureEachFrame(o.out, views, times, true, findings[f])
                                        : modelTruthLeaves(o.out, scoring, {}, truthRow(f).base);
                Row row = score(library, scoring, o.out, truth.options.distance_m);
                row.times = times;
                if (library.stem)
                    row.stemError.push_back(
                        std::abs(library.stem->height_m - truthStemHeight_m(truth)) /
                        truthStemHeight_m(truth));
                row.set = "maize", row.sensor = sensor, row.what = plant;
                row.finding = kindName(f);
                std::cout << sensor << ' ' << row.finding << ' ' << plant << ": " << cells(row)
                          << '\n';
                totals[f].add(row);
                perPlant[f].push_back(row);
                if (f < findings.size() && findings[f].name() == turntableMethod.name()) {
                    const modeling::CaptureOptions defaults;
                    const auto start = std::chrono::steady_clock::now();
                    const modeling::CaptureResult turntable =
                        captureTurntable(o.out, findings[f], defaults);
                    const double total_ms = std::chrono::duration<double, std::milli>(
                                                std::chrono::steady_clock::now() - start)
                                                .count();
                    TurntableRow t = scoreTurntable(library, turntable, truth, scoring, o.out,
                                                    defaults.registration);
                    t.eachView_ms = times.capture_ms;
                    t.turntable_ms.assign(static_cast<std::size_t>(views), total_ms / views);
                    t.sensor = sensor, t.plant = plant;
                    std::cout << sensor << " turntable " << plant << ": " << t.registered << " of "
                              << t.pairs << " registered (" << t.registrable << " registrable), "
                              << t.eachView.archetypes << " -> " << t.joined.archetypes
                              << " archetypes, held " << t.eachView.held << " -> " << t.joined.held
                              << " of " << t.leaves << '\n';
                    turntableTotal.add(t);
                    turntableRows.push_back(std::move(t));
                }
            }
        }
        if (turntableTotal.pairs > 0) turntableRows.push_back(turntableTotal);
        for (std::size_t f = 0; f < kinds; ++f) {
            rows.insert(rows.end(), perPlant[f].begin(), perPlant[f].end());
            totals[f].set = "maize", totals[f].sensor = sensor, totals[f].what = "all";
            totals[f].finding = kindName(f);
            rows.push_back(totals[f]);
        }
    }
    // The simulated tufts, scored the same way (3 fused frames, capture's defaults).
    for (const Method& finding : findings) {
        Row tufts;
        for (const std::string& preset :
             quick ? std::vector<std::string>{"quadratic-leaf"} : kTuftPresets) {
            synth::SynthOptions o;
            o.preset = preset;
            o.frames = 3;
            o.out = set / "tufts" / preset;
            if (&finding == &findings.front()) synth::synthesize(o);
            FrameTimes times;
            const modeling::ArchetypeLibrary library =
                captureEachFrame(o.out, 3, times, false, finding);
            synth::ScoringTruth truth = synth::readScoringTruth(o.out / "truth" / "blades.json");
            truth.views.resize(1);  // the library's archetypes stem from the group's first frame
            Row row = score(library, truth, o.out,
                            synth::readSynthTruth(o.out / "truth" / "blades.json").distance_m);
            row.times = times;
            row.set = "tufts", row.sensor = "kinect-v1", row.what = preset;
            row.finding = findingName(finding);
            std::cout << "tuft " << row.finding << ' ' << preset << ": " << cells(row) << '\n';
            tufts.add(row);
            rows.push_back(row);
        }
        tufts.set = "tufts", tufts.sensor = "kinect-v1", tufts.what = "all";
        tufts.finding = findingName(finding);
        rows.push_back(tufts);
    }

    std::ostringstream md;
    md << "# Real plants: capture against the truth, beside a plain leaf counter\n\n"
          "Six real maize shoots (Label3DMaize, `../shared/data/real/maize-label3d`) in a pot on a "
          "floor before a wall with clutter, "
       << views
       << " turntable views each, rendered through each simulated sensor (`meadow synth --plant`); "
          "`meadow capture` run on each view alone (`--fuse 1 --per-group --assume-still`), "
          "with each way of finding the plant (`--find-plant`) and cutting it (`--partition`); the "
          "library scored against the truth (docs/formats.md, \"Plant truth\"). A leaf counts "
          "when it shows at least 300 pixels; an archetype matches it when its spine stays "
          "within max(10 mm, 5 % of the leaf's length) of the leaf's centre line over 80 % of "
          "the shorter of the two. Recall, any view: what one library over all the views holds, "
          "the share of the plant's leaves (each counted where it shows 300 pixels in some view) "
          "matched in at least one view; its length error is each such leaf's best match's "
          "(a leaf that overlaps others in one view may stand clear in another). False blades are "
          "archetypes that match no leaf, named by what "
          "their spine lies on. Count error: |archetypes - leaves| per view; the baseline counts "
          "end points of a thinned depth band (synth/leaf_counter.h). Stem height error "
          "(stem-graph "
          "rows): |measured - true| / true for each plant, the height the library reports (its "
          "views' median, from the stem's foot to the highest node) against the truth's (from "
          "the foot to the farthest leaf base). The rows \""
       << kTruthRows[0].name
       << "\" bound what any partition could reach on these views: each leaf cut as the truth "
          "cuts it (its own pixels the sensor read, its base and tip where its true centre "
          "line starts and ends) and modelled as capture models a blade, carried down to where "
          "its true centre line starts as a tuft's blade is carried to the tuft's base; what "
          "they miss, the sensor did not show well enough or the model cannot hold. The rows \""
       << kTruthRows[1].name
       << "\" model the same leaves only as far down as the sensor read them, as capture models "
          "a leaf cut from a stem: the length a partition reaches without guessing where a "
          "hidden base is. Missed at base / tip: for each matched leaf, the share of its true "
          "centre line below the archetype's lower end and beyond its upper end (each end's "
          "nearest point on the line); a true centre line starts at the foot of the leaf's "
          "sheath, below where its blade leaves the stem (docs/formats.md, \"Scanned plants\"). "
          "Upside down: of the matched leaves whose archetype's ends lie at least a fifth of the "
          "leaf apart along it, the share whose archetype runs from the "
          "leaf's tip side toward its base (a meadow plants it by its tip). The tuft rows score "
          "the "
          "synthetic presets' first fused group the same way. Times, on one core, median over "
          "the frames: all of capture from depth to archetypes; finding the plant (depth band, "
          "plane removal, plant finding); the partition.\n\n"
          "| Set | Sensor | Capture | Plant | Views | Leaves | Recall | Recall, any view | "
          "Length error, best view (median) | False / view | "
          "False on | Length error (median) | Missed at base / tip (median) | Upside down | Width "
          "error (median) "
          "| Stem height error (median) | "
          "Count error | Baseline count error | Capture ms / frame | Finding ms / frame | "
          "Partition ms / frame |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows)
        md << "| " << r.set << " | " << r.sensor << " | " << r.finding << " | "
           << (r.what == "all" ? "**all**" : r.what) << " | " << cells(r) << " |\n";
    if (!turntableRows.empty()) md << turntableSection(turntableRows);
    writeText(out / "plant_benchmark.md", md.str());
    std::ostringstream csv;
    csv << "set,sensor,capture,plant,views,leaves,recall,recall_any_view,length_error_best_view";
    for (std::size_t k = 0; k < 7; ++k)
        csv << ",false_on_" << synth::kFalseBladeOnNames.name(static_cast<synth::FalseBladeOn>(k));
    csv << ",length_error_median,base_missed_median,tip_missed_median,upside_down_share,width_"
           "error_median,stem_"
           "height_error_median,count_error,baseline_"
           "count_error,capture_ms,finding_ms,partition_ms\n";
    for (const Row& r : rows) csv << csvRow(r) << '\n';
    writeText(out / "plant_benchmark.csv", csv.str());
    if (!turntableRows.empty()) writeText(out / "plant_turntable.csv", turntableCsv(turntableRows));
    return 0;
}

}  // namespace
}  // namespace meadow::bench

int main(int argc, char** argv) {
    setenv("OMP_NUM_THREADS", "1", 1);
    try {
        return meadow::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "plant_bench: " << e.what() << '\n';
        return 1;
    }
}
