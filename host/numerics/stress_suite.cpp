#include "numerics/stress_suite.h"

#include "dist/bytes.h"
#include "gpu/gpu_tracer.h"
#include "image/pictures.h"
#include "numerics/secondary_check.h"
#include "numerics/stress_pictures.h"
#include "reference/scene_intersector.h"
#include "scene/scene_geometry.h"
#include "util/error.h"
#include "util/parallel_for.h"

#include <glm/geometric.hpp>

#include <fnmatch.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ostream>

namespace vkray::numerics {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string trimmed(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

}  // namespace

// The CPU reference in double: the reference's own intersector on the
// primary ray built in double, t kept in double (a Frame's depth is float).
std::vector<StressSample> referenceSamples(const Scene& scene, const CameraBasis& camera,
                                           const RenderSettings& settings, int threads) {
    const reference::SceneIntersector intersector(scene);
    std::vector<StressSample> samples(size_t(settings.width) * size_t(settings.height));
    parallelFor(
        std::size_t(settings.height),
        [&](std::size_t row) {
            const int y = int(row);
            for (int x = 0; x < settings.width; ++x) {
                const double sx = 2 * (x + 0.5) / settings.width - 1;
                const double sy = 1 - 2 * (y + 0.5) / settings.height;
                const glm::dvec3 d =
                    glm::normalize(-camera.n + sx * camera.tanHalfFov * camera.aspect * camera.u +
                                   sy * camera.tanHalfFov * camera.v);
                const auto hit = intersector.closestHit({camera.eye, d}, 0.0);
                StressSample& s = samples[size_t(y) * size_t(settings.width) + size_t(x)];
                s.inDouble = true;
                if (!hit) continue;
                s.t = hit->t;
                s.normal = hit->normal;
                s.object = hit->object;
            }
        },
        threads);
    return samples;
}

StressCase readStressCase(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot read the stress case");
    StressCase c;
    c.path = path;
    c.name = fs::path(path).stem().string();
    std::string line, *current = nullptr;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        const std::string text = trimmed(line);
        if (text.empty()) continue;
        if (text[0] != '!') break;  // the header ends at the first non-comment line
        const std::string body = trimmed(text.substr(1));
        const size_t colon = body.find(':');
        const std::string key = colon == std::string::npos ? "" : body.substr(0, colon);
        const std::string value = colon == std::string::npos ? "" : trimmed(body.substr(colon + 1));
        if (key == "stress")
            current = &c.title;
        else if (key == "stiff")
            current = &c.stiff;
        else if (key == "correct")
            current = &c.correct;
        else if (key == "naive") {
            current = nullptr;
            if (value != "fails" && value != "passes")
                throw Error(path + ":" + std::to_string(lineNumber) +
                            ": 'naive:' takes fails or passes, found '" + value + "'");
            c.naiveFails = value == "fails";
            continue;
        } else if (current && !body.empty()) {  // continuation of the last key
            *current += " " + body;
            continue;
        } else {
            current = nullptr;
            continue;
        }
        *current = value;
    }
    if (c.title.empty() || c.stiff.empty() || c.correct.empty())
        throw Error(path +
                    ": a stress case starts with '! stress:', '! stiff:' and '! correct:' "
                    "comment lines (see scenes/stress/README.md)");
    return c;
}

bool caseNameMatches(const std::string& name, const std::string& pattern) {
    if (pattern.empty()) return true;
    if (pattern.find_first_of("*?[") != std::string::npos)
        return ::fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
    return name.find(pattern) != std::string::npos;
}

std::vector<StressCase> findStressCases(const std::string& directory, const std::string& pattern) {
    if (!fs::is_directory(directory))
        throw Error("stress cases: '" + directory + "' is not a folder (pass --cases-dir DIR)");
    std::vector<std::string> paths;
    for (const auto& entry : fs::directory_iterator(directory)) {
        const fs::path p = entry.path();
        if (p.extension() != ".sdl") continue;
        if (!caseNameMatches(p.stem().string(), pattern)) continue;
        paths.push_back(p.string());
    }
    std::sort(paths.begin(), paths.end());
    if (paths.empty())
        throw Error(
            "stress cases: no scene in '" + directory + "'" +
            (pattern.empty() || pattern == "*" ? std::string() : " matches '" + pattern + "'"));
    std::vector<StressCase> cases;
    for (const std::string& path : paths) cases.push_back(readStressCase(path));
    return cases;
}

Arithmetic arithmeticOf(const std::string& mode) {
    return mode == kCpuDoubleMode ? kDoubleAsWritten : mode == "fp64" ? kDouble : kFloat;
}

bool withinBounds(const ModeMetrics& m) {
    return m.ran && m.flips == 0 && m.wrongId == 0 && m.acne == 0 && m.shadowFlips == 0 &&
           m.exitErrors == 0 && m.shippedDiffer == 0 && m.tRatioMax <= kTAllowanceMultiple &&
           m.normalRatioMax <= kNormalAllowanceMultiple;
}

PixelVerdict classifyPixel(const OraclePixel& o, const StressSample& s, Arithmetic a) {
    if (o.setAside[a]) return PixelVerdict::SetAside;
    if ((o.hit.id >= 0) != (s.object >= 0)) return PixelVerdict::Flip;
    if (o.hit.id < 0) return PixelVerdict::BothMiss;
    return o.hit.id != s.object ? PixelVerdict::WrongId : PixelVerdict::Compared;
}

ModeMetrics compareWithOracle(const std::vector<OraclePixel>& oracle,
                              const std::vector<StressSample>& samples, Arithmetic a) {
    if (oracle.size() != samples.size()) throw Error("internal: oracle and samples differ in size");
    ModeMetrics m;
    m.ran = true;
    m.pixels = oracle.size();
    const double u = kUnitRoundoff[a], uWorld = a == kDoubleAsWritten ? kUnitRoundoff[a] : 0;
    double tSquares = 0, nSquares = 0;
    for (size_t i = 0; i < oracle.size(); ++i) {
        const OraclePixel& o = oracle[i];
        const StressSample& s = samples[i];
        m.besideEdges += o.besideEdge;
        switch (classifyPixel(o, s, a)) {
        case PixelVerdict::SetAside: ++m.setAside; continue;
        case PixelVerdict::Flip: ++m.flips; continue;
        case PixelVerdict::WrongId: ++m.wrongId; continue;
        case PixelVerdict::BothMiss: continue;
        case PixelVerdict::Compared: break;
        }
        ++m.compared;
        const double tErr = std::isfinite(s.t) ? double(abs(Quad(s.t) - o.hit.t) / o.hit.t)
                                               : std::numeric_limits<double>::infinity();
        const double angle = angleBetween(s.normal, toDvec3(o.hit.normal));
        const double nErr = std::isnan(angle) ? M_PI : angle;
        const Conditioning& c = o.conditioning;
        // Against an infinite allowance (a grazing hit) the ratio is 0: no error is beyond it.
        const auto ratio = [](double err, double allowance) {
            return std::isinf(allowance) ? 0.0 : err / allowance;
        };
        m.tErrMax = std::max(m.tErrMax, tErr);
        m.normalErrMax = std::max(m.normalErrMax, nErr);
        m.tConditionMax = std::max(m.tConditionMax, c.t);
        m.tWorldMax = std::max(m.tWorldMax, c.tWorld);
        m.normalConditionMax = std::max(m.normalConditionMax, c.normal);
        m.normalWorldMax = std::max(m.normalWorldMax, c.normalWorld);
        m.tRatioMax = std::max(m.tRatioMax, ratio(tErr, u * c.t + uWorld * c.tWorld));
        m.normalRatioMax =
            std::max(m.normalRatioMax, ratio(nErr, u * c.normal + uWorld * c.normalWorld));
        m.oracleBound = std::max(m.oracleBound, double(o.hit.tBound / o.hit.t));
        tSquares += tErr * tErr;
        nSquares += nErr * nErr;
    }
    if (m.compared > 0) {
        m.tErrRms = std::sqrt(tSquares / double(m.compared));
        m.normalErrRms = std::sqrt(nSquares / double(m.compared));
    }
    return m;
}

namespace {

// Every field of a row, in one order for both directions.
template <typename Row, typename Visit>
void forEachField(Row& m, Visit&& visit) {
    for (auto* text : {&m.caseName, &m.mode, &m.note}) visit(*text);
    visit(m.ran);
    for (auto* count :
         {&m.pixels, &m.setAside, &m.besideEdges, &m.compared, &m.flips, &m.wrongId, &m.feelers,
          &m.acne, &m.shadowFlips, &m.shadowEdges, &m.refracted, &m.exitErrors})
        visit(*count);
    for (auto* value : {&m.seconds, &m.tErrMax, &m.tErrRms, &m.tConditionMax, &m.tWorldMax,
                        &m.tRatioMax, &m.normalErrMax, &m.normalErrRms, &m.normalConditionMax,
                        &m.normalWorldMax, &m.normalRatioMax, &m.oracleBound})
        visit(*value);
}

}  // namespace

std::string encodeRows(const std::vector<ModeMetrics>& rows) {
    dist::ByteWriter writer;
    writer << std::uint64_t(rows.size());
    for (const ModeMetrics& m : rows) forEachField(m, [&](const auto& field) { writer << field; });
    return writer.bytes();
}

std::vector<ModeMetrics> decodeRows(const std::string& bytes) {
    dist::ByteReader reader(bytes);
    std::uint64_t count = 0;
    reader >> count;
    if (count > bytes.size()) throw Error("MPI: a case's rows came back garbled");
    std::vector<ModeMetrics> rows(count);
    for (ModeMetrics& m : rows) forEachField(m, [&](auto& field) { reader >> field; });
    return rows;
}

namespace {

// The pixels where two frames of the same rays differ (ShippedDiffer's
// figures, ModeMetrics).
std::size_t pixelsApart(const Frame& a, const Frame& b) {
    std::size_t apart = 0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) {
        const glm::vec3 colour = glm::abs(a.color[i] - b.color[i]);
        const glm::vec3 normal = glm::abs(a.normal[i] - b.normal[i]);
        const bool depthsApart = std::isfinite(a.depth[i]) != std::isfinite(b.depth[i]) ||
                                 (std::isfinite(a.depth[i]) &&
                                  std::abs(a.depth[i] - b.depth[i]) > 1e-5f * std::abs(b.depth[i]));
        apart += a.id[i] != b.id[i] || depthsApart ||
                 std::max({colour.x, colour.y, colour.z}) > 1e-4f ||
                 std::max({normal.x, normal.y, normal.z}) > 1e-4f;
    }
    return apart;
}

}  // namespace

std::vector<ModeMetrics> runStressCase(const StressCase& stressCase, gpu::Context* context,
                                       const StressOptions& options, std::ostream* log,
                                       StressPicture* picture) {
    const Scene scene = loadScene(stressCase.path, {}, nullptr);
    requireOracleScene(scene);
    if (!scene.camera) throw Error(stressCase.path + ": a stress case must set its camera");
    const RenderSettings settings{options.width, options.height, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, options.width, options.height);

    const auto oracleStart = Clock::now();
    const std::vector<OraclePixel> oracle = renderOracle(scene, camera, settings, options.threads);
    if (log) *log << stressCase.name << ": oracle " << secondsSince(oracleStart) << " s\n";
    if (picture) {
        picture->caseName = stressCase.name;
        picture->oraclePng = oraclePng(scene, oracle, settings.width, settings.height);
        picture->shrunkBy = shrinkFactorFor(Image{settings.width, 1, 1, {}}, kStressPictureWidth);
    }

    std::vector<ModeMetrics> rows;
    const auto finish = [&](ModeMetrics m, const std::string& mode, double seconds) {
        m.caseName = stressCase.name;
        m.mode = mode;
        m.seconds = seconds;
        if (log) *log << stressCase.name << ": " << mode << " " << seconds << " s\n";
        rows.push_back(std::move(m));
    };
    for (Precision precision : options.gpuModes) {
        ModeMetrics m;
        if (!context || (precision == Precision::Fp64 && !context->device().shaderFloat64)) {
            m.note = !context ? "no Vulkan device" : "the device has no shaderFloat64";
            finish(m, precisionName(precision), 0);
            continue;
        }
        gpu::GpuTracer tracer(*context,
                              {.shaderDirectory = options.shaderDirectory, .precision = precision});
        // The time: the fastest of three plain renders (the first also warms
        // caches); the numbers: the stress-output variant's, the same rays.
        double best = std::numeric_limits<double>::infinity();
        Frame shipped;
        for (int run = 0; run < 3; ++run) {
            gpu::GpuRenderStats stats;
            shipped = tracer.render(scene, camera, settings, &stats);
            best = std::min(best, stats.renderSeconds);
        }
        std::vector<StressSample> samples;
        const Frame frame = tracer.renderStressOutput(scene, camera, settings, samples);
        const std::size_t shippedDiffer = pixelsApart(shipped, frame);
        const Arithmetic a = arithmeticOf(precisionName(precision));
        m = compareWithOracle(oracle, samples, a);
        const SecondaryStats secondary = checkSecondaryRays(
            scene, camera, oracle, samples, a, originFootprintOf(precision), options.threads);
        m.feelers = secondary.feelerPixels;
        m.acne = secondary.acne;
        m.shadowFlips = secondary.shadowFlips;
        m.shadowEdges = secondary.shadowEdges;
        m.refracted = secondary.refracted;
        m.exitErrors = secondary.exitErrors;
        m.shippedDiffer = shippedDiffer;
        if (picture)
            picture->modes.push_back(markedPicture(precisionName(precision), frame, oracle, samples,
                                                   a, secondary.failedPixels));
        finish(m, precisionName(precision), best);
    }
    if (options.cpuDouble) {
        const auto start = Clock::now();
        const std::vector<StressSample> samples =
            referenceSamples(scene, camera, settings, options.threads);
        const double seconds = secondsSince(start);
        finish(compareWithOracle(oracle, samples, arithmeticOf(kCpuDoubleMode)), kCpuDoubleMode,
               seconds);
    }
    return rows;
}

}  // namespace vkray::numerics
