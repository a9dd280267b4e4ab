// 3. Modeling accuracy: blade type x noise x distance (tables.h).
#include <cmath>
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/blade_error.h"
#include "accuracy_tradeoff/tables.h"
#include "common/report.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using modeling::BladeFit;
using modeling::CaptureOptions;

std::string modelingRow(const std::vector<BladeError>& e) {
    std::vector<float> v0, v1, v2, tipSq, heightAbs, heightSigned, width, off, knots, base, tip;
    for (const BladeError& b : e) {
        v0.push_back(b.v0_mm);
        v1.push_back(b.v1_mm);
        v2.push_back(b.v2_mm);
        tipSq.push_back(b.v2_mm * b.v2_mm);
        heightAbs.push_back(std::abs(b.heightError));
        heightSigned.push_back(b.heightError);
        width.push_back(b.widthMaeFraction);
        off.push_back(b.offCurve_mm);
        if (std::isfinite(b.knotPolyline_mm)) knots.push_back(b.knotPolyline_mm);
        base.push_back(b.baseS);
        tip.push_back(b.tipS);
    }
    std::ostringstream row;
    if (e.empty()) return ",,,,,,,,,,,";  // no fitted blade matched: nothing measured
    row << fixed(mean(v0), 2) << ',' << fixed(mean(v1), 2) << ',' << fixed(mean(v2), 2) << ','
        << fixed(std::sqrt(mean(tipSq)), 2) << ',' << fixed(kPercent * mean(heightAbs), 2) << ','
        << fixed(kPercent * mean(heightSigned), 2) << ',' << fixed(kPercent * mean(width), 2) << ','
        << fixed(median(off), 2) << ',' << fixed(mean(knots), 2) << ',' << fixed(median(base), 3)
        << ',' << fixed(median(tip), 3) << ',' << fixed(median(v2), 2);
    return row.str();
}

}  // namespace

void modelingAccuracy(const Plan& plan, const fs::path& out, Fig12Input& fig12) {
    std::cout << "modeling accuracy: " << plan.bladeTypes.size() << " presets x "
              << plan.noises.size() << " noise x " << plan.distances_m.size() << " distances x "
              << plan.modelingSeeds << " seeds (capture defaults: fuse "
              << CaptureOptions{}.groups.fusionFrames << " frames)\n";
    const CaptureOptions options{};
    const capture::Segmenter segmenter(options.segmenter);
    const std::string header =
        "v0_error_mm,v1_error_mm,v2_error_mm,tip_rms_mm,height_error_abs_pct,"
        "height_error_signed_pct,width_mae_pct_of_max,spine_off_curve_median_mm,"
        "knot_polyline_error_mm,base_s_median,tip_s_median,tip_error_median_mm";
    std::ostringstream csv, md;
    csv << "preset,noise_scale,distance_m,seeds,true_blades,fitted,fitted_matched,"
           "fitted_unmatched,fit_failures,"
        << header << '\n';
    md << "| preset | noise | fitted (matched) / true | v0 / v1 / v2 error (mm, mean) | tip RMS "
          "(median) (mm) | "
          "height error (mean abs, signed) | width MAE (% of max) | fitted spine off true "
          "curve (median, mm) | visible s (base-tip) |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& preset : plan.bladeTypes)
        for (float noise : plan.noises) {
            std::vector<BladeError> pooled;
            int pooledTrue = 0, pooledFitted = 0, pooledMatched = 0;
            for (float distance_m : plan.distances_m) {
                std::vector<BladeError> errors;
                int trueBlades = 0, fitted = 0, matched = 0, failures = 0;
                for (int seed = 1; seed <= plan.modelingSeeds; ++seed) {
                    const Scene scene = renderScene(preset, noise, static_cast<std::uint64_t>(seed),
                                                    distance_m, options.groups.fusionFrames);
                    const TuftCapture cap = captureTuft(segmenter, scene, options);
                    const TuftScore s = scoreCapture(scene, cap);
                    trueBlades += static_cast<int>(scene.tuft.blades.size());
                    fitted += s.fitted;
                    matched += s.fittedMatched;
                    failures += s.fitFailures;
                    errors.insert(errors.end(), s.errors.begin(), s.errors.end());
                    if (plan.verbose)
                        for (const BladeError& e : s.errors)
                            std::cout
                                << "    " << preset << ' ' << noiseName(noise) << ' ' << distance_m
                                << " m seed " << seed << ": v0/v1/v2 " << fixed(e.v0_mm, 1) << '/'
                                << fixed(e.v1_mm, 1) << '/' << fixed(e.v2_mm, 1) << " mm, height "
                                << fixed(kPercent * e.heightError, 1) << " %, s "
                                << fixed(e.baseS, 2) << "-" << fixed(e.tipS, 2) << ", off curve "
                                << fixed(e.offCurve_mm, 1) << " mm, knots "
                                << fixed(e.knotPolyline_mm, 1) << " mm\n";
                    if (noise == kNominalNoise)
                        for (const BladeFit* f : s.matchedFits)
                            appendFig12Skeleton(fig12, preset, *f);
                }
                csv << preset << ',' << noise << ',' << distance_m << ',' << plan.modelingSeeds
                    << ',' << trueBlades << ',' << fitted << ',' << matched << ','
                    << fitted - matched << ',' << failures << ',' << modelingRow(errors) << '\n';
                pooled.insert(pooled.end(), errors.begin(), errors.end());
                pooledTrue += trueBlades;
                pooledFitted += fitted;
                pooledMatched += matched;
            }
            std::istringstream row(modelingRow(pooled));
            std::vector<std::string> f;
            for (std::string cell; std::getline(row, cell, ',');)
                f.push_back(cell.empty() ? "–" : cell);
            f.resize(12, "–");
            md << "| " << preset << " | " << noiseName(noise) << " | " << pooledFitted << " ("
               << pooledMatched << ") / " << pooledTrue << " | " << f[0] << " / " << f[1] << " / "
               << f[2] << " | " << f[3] << " (" << f[11] << ") | " << f[4] << " %, " << f[5]
               << " % | " << f[6] << " % | " << f[7] << " | "
               << (pooled.empty() ? std::string("–") : f[9] + "-" + f[10]) << " |\n";
            std::cout << "  " << preset << ' ' << noiseName(noise) << ": " << pooledMatched << '/'
                      << pooledTrue << " fitted, v0/v1/v2 " << f[0] << '/' << f[1] << '/' << f[2]
                      << " mm, height " << f[4] << " %, width " << f[6] << " %\n";
        }
    writeText(out / "modeling_accuracy.csv", csv.str());
    writeText(out / "modeling_accuracy.md", md.str());
}

}  // namespace meadow::bench
