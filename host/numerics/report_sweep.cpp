#include "numerics/report_sweep.h"

#include "dist/bytes.h"
#include "dist/job_hand_out.h"
#include "gpu/gpu_tracer.h"
#include "image/aov_images.h"
#include "image/metrics.h"
#include "reference/reference_tracer.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <ostream>
#include <thread>

namespace vkray::numerics {

namespace {

std::string sizeText(const RenderSettings& s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

std::string labelOf(const SweepPoint& p) {
    std::string label;
    for (const std::string& v : p.values) label += (label.empty() ? "" : " ") + v;
    return label;
}

// Every combination, the first knob varying slowest.
void combine(const std::vector<Knob>& knobs, size_t k, ReportConfig config,
             std::vector<std::string> values, std::vector<SweepPoint>& out) {
    if (k == knobs.size()) {
        SweepPoint p;
        p.values = values;
        p.config = config;
        out.push_back(p);
        return;
    }
    for (const std::string& v : knobs[k].values) {
        ReportConfig next = config;
        knobs[k].apply(next, v);
        std::vector<std::string> nextValues = values;
        nextValues.push_back(knobs[k].name + " " + v);
        combine(knobs, k + 1, next, nextValues, out);
    }
}

}  // namespace

std::vector<Knob> reportKnobs() {
    return {
        {"precision",
         {"naive", "robust", "fp64"},
         [](ReportConfig& c, const std::string& v) {
             c.precision = parsePrecision("precision", v);
         }},
        {"spp",
         {"1", "4"},
         [](ReportConfig& c, const std::string& v) { c.settings.spp = std::stoi(v); }},
        {"block",
         {"1", "2", "4"},
         [](ReportConfig& c, const std::string& v) { c.settings.block = std::stoi(v); }},
        {"size",
         {"full", "half"},
         [](ReportConfig& c, const std::string& v) {
             if (v == "half") {
                 c.settings.width = std::max(1, c.settings.width / 2);
                 c.settings.height = std::max(1, c.settings.height / 2);
             }
         }},
    };
}

namespace {

// A reference frame as it travels between MPI ranks: its time, colours and ids.
std::string encodeReference(double seconds, const Frame& frame) {
    dist::ByteWriter writer;
    writer << seconds << frame.width << frame.height;
    for (std::size_t i = 0; i < frame.pixelCount(); ++i)
        writer << frame.color[i].x << frame.color[i].y << frame.color[i].z << frame.id[i];
    return writer.bytes();
}

std::pair<double, Frame> decodeReference(const std::string& bytes) {
    dist::ByteReader reader(bytes);
    double seconds = 0;
    int width = 0, height = 0;
    reader >> seconds >> width >> height;
    if (std::uint64_t(width) * std::uint64_t(height) > bytes.size())
        throw Error("MPI: a reference frame came back garbled");
    Frame frame(width, height);
    for (std::size_t i = 0; i < frame.pixelCount(); ++i)
        reader >> frame.color[i].x >> frame.color[i].y >> frame.color[i].z >> frame.id[i];
    return {seconds, std::move(frame)};
}

// A point's measurements (its configuration is known to every rank).
template <typename Point, typename Visit>
void forEachMeasurement(Point& p, Visit&& visit) {
    visit(p.ran);
    visit(p.note);
    for (auto* value : {&p.seconds, &p.rmse, &p.maxError, &p.idMismatchPercent}) visit(*value);
    visit(p.imagePng);
    visit(p.errorPng);
}

// The thumbnails of an image, and of its error against the reference when given.
void makeThumbnails(const Image& image, const Image* reference, SweepPoint& p) {
    const int factor = shrinkFactorFor(image, kThumbnailWidth);
    p.imagePng = pngBytes(shrink(image, factor, Shrink::Average));
    if (reference)
        p.errorPng = pngBytes(
            heatMap(shrink(errorImage(image, *reference), factor, Shrink::Largest), kErrorScale));
}

}  // namespace

std::vector<SweepPoint> runSweep(const Scene& scene, const Camera& camera, gpu::Context& context,
                                 const SweepOptions& options, std::ostream* log) {
    ReportConfig base;
    base.settings = {options.width, options.height, 1};
    std::vector<SweepPoint> points;
    combine(reportKnobs(), 0, base, {}, points);
    if (options.precision)
        std::erase_if(
            points, [&](const SweepPoint& p) { return p.config.precision != *options.precision; });
    const int threads = options.threads > 0
                            ? options.threads
                            : int(std::max(1u, std::thread::hardware_concurrency()));
    // Under mpirun the work is handed out across the ranks (dist/job_hand_out.h)
    // in two rounds: the references, which every rank then holds, and the points.
    const dist::World& world = dist::World::current();

    // The reference of each size (itself a point: error 0).
    std::vector<std::pair<int, int>> sizes;
    for (const SweepPoint& p : points) {
        const std::pair<int, int> size{p.config.settings.width, p.config.settings.height};
        if (std::find(sizes.begin(), sizes.end(), size) == sizes.end()) sizes.push_back(size);
    }
    std::vector<std::string> rendered =
        dist::runJobsAcrossRanks(world, sizes.size(), [&](std::size_t job) {
            const RenderSettings full{sizes[job].first, sizes[job].second, 1, kReferenceSpp};
            const Stopwatch stopwatch;
            const Frame frame = reference::render(
                scene, makeCameraBasis(camera, full.width, full.height), full, {threads});
            const double seconds = stopwatch.seconds();
            if (log) *log << "reference " << sizeText(full) << ": cpu double " << seconds << " s\n";
            return encodeReference(seconds, frame);
        });
    rendered.resize(sizes.size());
    std::map<std::pair<int, int>, std::pair<double, Frame>> references;
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        dist::shareFromRankZero(world, rendered[i]);
        references.emplace(sizes[i], decodeReference(rendered[i]));
    }

    std::map<Precision, std::unique_ptr<gpu::GpuTracer>> tracers;
    const std::vector<std::string> measured =
        dist::runJobsAcrossRanks(world, points.size(), [&](std::size_t job) {
            SweepPoint p = points[job];
            const RenderSettings& s = p.config.settings;
            const Frame& reference = references.at({s.width, s.height}).second;
            if (p.config.precision == Precision::Fp64 && !context.device().shaderFloat64) {
                p.note = "the device has no shaderFloat64";
            } else {
                auto& tracer = tracers[p.config.precision];
                if (!tracer)
                    tracer = std::make_unique<gpu::GpuTracer>(
                        context, gpu::GpuRenderOptions{.shaderDirectory = options.shaderDirectory,
                                                       .precision = p.config.precision});
                const CameraBasis basis = makeCameraBasis(camera, s.width, s.height);
                Frame frame;
                p.seconds = std::numeric_limits<double>::infinity();
                for (int run = 0; run < 3; ++run) {  // the fastest of three
                    gpu::GpuRenderStats stats;
                    frame = tracer->render(scene, basis, s, &stats);
                    p.seconds = std::min(p.seconds, stats.renderSeconds);
                }
                const Image colour = colorImage(frame), referenceColour = colorImage(reference);
                CompareResult result = compareImages(colour, referenceColour, {});
                compareIds(idImage(frame), idImage(reference), result);
                makeThumbnails(colour, &referenceColour, p);
                p.ran = true;
                p.rmse = result.rmse;
                p.maxError = result.maxAbsError;
                p.idMismatchPercent = result.idMismatchPercent;
                if (log) *log << labelOf(p) << ": " << p.seconds << " s, RMSE " << p.rmse << "\n";
            }
            dist::ByteWriter writer;
            forEachMeasurement(p, [&](const auto& field) { writer << field; });
            return writer.bytes();
        });
    if (world.rank() != 0) return {};  // rank 0 reports
    for (std::size_t i = 0; i < points.size(); ++i) {
        dist::ByteReader reader(measured[i]);
        forEachMeasurement(points[i], [&](auto& field) { reader >> field; });
    }
    for (const auto& [size, reference] : references) {
        SweepPoint p;
        p.values = {"cpu double", "spp " + std::to_string(kReferenceSpp), "block 1",
                    "size " + std::to_string(size.first) + "x" + std::to_string(size.second)};
        p.config.settings = {size.first, size.second, 1, kReferenceSpp};
        p.ran = true;
        p.seconds = reference.first;
        p.note = "the reference";
        makeThumbnails(colorImage(reference.second), nullptr, p);
        points.push_back(p);
    }
    return points;
}

Report sweepReport(const std::string& scenePath, const std::vector<SweepPoint>& points,
                   const std::string& device) {
    Report report;
    report.title = "vkray report " + scenePath;
    report.paragraphs = {
        "Error against run time over precision mode, samples per pixel, block size and image "
        "size, on " +
            device +
            ". Each GPU configuration is rendered three times and the fastest render counts. Its "
            "error is the colour difference (clamped to [0, 1]) from the CPU reference in double "
            "at " +
            std::to_string(kReferenceSpp) +
            " samples per pixel, block 1 and the same "
            "size: RMSE over all pixels and channels, and the largest difference.",
        "In the plots, lower left is better; the dashed line joins the configurations that no "
        "other beats in both time and error (the Pareto front); a label that would cover "
        "another is left out (every point names itself on hover). Hollow red points have object "
        "ids differing from the reference on more than 1 % of pixels (ids are those of each "
        "pixel's first sample, which sits elsewhere in the reference's finer grid of samples: "
        "a fraction of a percent of edge pixels differ in any configuration)."};
    report.table.columns = {"configuration", "size",         "time s", "RMSE",
                            "max error",     "ids differ %", "note"};
    std::map<std::string, std::pair<Plot, Plot>> plots;  // by size
    std::map<std::string, Gallery> galleries;            // by size
    for (const SweepPoint& p : points) {
        const std::string size = sizeText(p.config.settings);
        std::vector<std::string> label(p.values.begin(), p.values.end() - 1);  // without the size
        std::string text;
        for (const std::string& v : label) text += (text.empty() ? "" : " ") + v;
        using V = ReportValue;
        report.table.rows.push_back({V::str(text), V::str(size), p.ran ? V::num(p.seconds) : V{},
                                     p.ran ? V::num(p.rmse) : V{}, p.ran ? V::num(p.maxError) : V{},
                                     p.ran ? V::num(p.idMismatchPercent) : V{}, V::str(p.note)});
        FigureGroup group{text, p.note, {}};
        if (p.ran && !p.errorPng.empty()) {
            char note[128];
            std::snprintf(note, sizeof note, "RMSE %.3g, max error %.3g, %.3g s", p.rmse,
                          p.maxError, p.seconds);
            group.note = note;
        }
        if (!p.imagePng.empty()) group.figures.push_back({"image", p.imagePng, std::nullopt, ""});
        if (!p.errorPng.empty())
            group.figures.push_back({"error against the reference", p.errorPng, kErrorScale,
                                     "colour error (log scale)"});
        galleries[size].groups.push_back(std::move(group));
        if (!p.ran) continue;
        auto& [rmsePlot, maxPlot] = plots[size];
        rmsePlot.title = "RMSE against time, " + size;
        maxPlot.title = "max error against time, " + size;
        rmsePlot.xLabel = maxPlot.xLabel = "render time (s)";
        rmsePlot.yLabel = "colour RMSE";
        maxPlot.yLabel = "max colour error";
        rmsePlot.flaggedMeaning = maxPlot.flaggedMeaning = "ids differ on more than 1 % of pixels";
        const bool flagged = p.idMismatchPercent > 1.0;
        std::string shortLabel;  // "robust b2"
        for (std::string v : label) {
            for (const char* knob : {"precision ", "spp ", "block "}) {
                const std::string k = knob;
                if (v.rfind(k, 0) == 0)
                    v = (k == "block " ? "b" : k == "spp " ? "s" : "") + v.substr(k.size());
            }
            shortLabel += (shortLabel.empty() ? "" : " ") + v;
        }
        // A colour per precision mode ("cpu double" for the reference).
        const std::string series =
            label.front().rfind("precision ", 0) == 0 ? label.front().substr(10) : label.front();
        rmsePlot.points.push_back({shortLabel, p.seconds, p.rmse, flagged, series});
        maxPlot.points.push_back({shortLabel, p.seconds, p.maxError, flagged, series});
    }
    for (auto& [size, pair] : plots) {
        report.plots.push_back(pair.first);
        report.plots.push_back(pair.second);
    }
    for (auto& [size, gallery] : galleries) {
        gallery.title = "Pictures, " + size;
        gallery.paragraphs = {
            "Each configuration's image, shrunk to at most " + std::to_string(kThumbnailWidth) +
            " pixels wide (each pixel the mean of those it covers), beside its error against the "
            "reference of its size as a heat map: each thumbnail pixel shows the largest colour "
            "error (clamped colours, largest channel) of the pixels it covers, on a log scale from "
            "1e-4 (and below, exact agreement included: black) to 1 (pale yellow)."};
        report.galleries.push_back(std::move(gallery));
    }
    return report;
}

}  // namespace vkray::numerics
