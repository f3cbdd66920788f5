// `vkray report SCENE`: one scene rendered over every combination of the
// knobs that trade error for run time, each point measured against a
// high-quality CPU reference (double precision, kReferenceSpp samples per
// pixel, block 1) of the same size.
#pragma once

#include "gpu/precision.h"
#include "image/pictures.h"
#include "numerics/report_writer.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace vkray::gpu {
class Context;
}

namespace vkray::numerics {

// One configuration of the GPU renderer.
struct ReportConfig {
    Precision precision = Precision::Robust;
    RenderSettings settings;
};

// A knob: its values as written in labels, and how each sets a configuration.
// Adding one is one line in reportKnobs(), e.g. samples per pixel:
//   {"spp", {"1", "4", "16"}, [](ReportConfig& c, const std::string& v) { c.settings.spp =
//   std::stoi(v); }},
struct Knob {
    std::string name;
    std::vector<std::string> values;
    std::function<void(ReportConfig&, const std::string&)> apply;
};

// precision (naive, robust, fp64), spp (1, 4), block (1, 2, 4), size (full =
// width x height, half).
std::vector<Knob> reportKnobs();

// The reference's samples per pixel (the same jittered grid the GPU uses).
inline constexpr int kReferenceSpp = 16;

struct SweepPoint {
    std::vector<std::string> values;  // one per knob, in reportKnobs() order
    ReportConfig config;
    bool ran = false;
    std::string note;               // why it did not run
    double seconds = 0;             // render time
    double rmse = 0, maxError = 0;  // colour, clamped to [0, 1], against the reference
    double idMismatchPercent = 0;
    // Thumbnails (PNG, at most kThumbnailWidth wide): the image, and its error
    // against the reference as a heat map on kErrorScale (none for a reference).
    std::string imagePng, errorPng;
};

inline constexpr int kThumbnailWidth = 160;
// The colour error's heat scale: below 1e-4 (and 0) the cold end, 1 the hot.
inline constexpr HeatScale kErrorScale{1e-4, 1};

struct SweepOptions {
    int width = 640, height = 480;
    std::string shaderDirectory;
    int threads = 0;                     // CPU reference threads
    std::optional<Precision> precision;  // only this mode (default: every value of the knob)
};

// Every combination of the knobs' values, then the CPU reference itself
// (error 0) once per size. `log` (may be null) gets a line per point.
std::vector<SweepPoint> runSweep(const Scene& scene, const Camera& camera, gpu::Context& context,
                                 const SweepOptions& options, std::ostream* log);

// The table and plots (RMSE and max error against time, one pair per size).
Report sweepReport(const std::string& scenePath, const std::vector<SweepPoint>& points,
                   const std::string& device);

}  // namespace vkray::numerics
