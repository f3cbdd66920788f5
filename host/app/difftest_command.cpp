#include "app/difftest_command.h"

#include "app/commands.h"
#include "app/random_scene.h"
#include "app/watch.h"
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "gpu/shader_variant.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "reference/reference_tracer.h"
#include "render/camera.h"
#include "scene/scene_geometry.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <filesystem>
#include <list>
#include <map>
#include <memory>

namespace vkray {

namespace {

namespace fs = std::filesystem;

struct Verdict {
    bool agreed = false;
    bool onlyAtCheckSize = false;  // over the bound at its size, within render --check's at 160x120
    std::string refusal;           // the GPU's error, when it refused the scene
    std::string figures;           // what the comparison found
};

// The run's GPU tracers, one per shader variant and mode, the 64 used last
// kept: lavapipe compiles a variant's machine code (seconds for a large one)
// once per tracer, and a run of scenes with their own variants meets many
// a variant again (1000 scenes: 424 variants, 630 compiles with 64 kept,
// against 987 with one). With --variant all, one per mode.
class Tracers {
public:
    Tracers(gpu::Context& context, const Options& o) : context_(context), o_(o) {}

    gpu::GpuTracer& forScene(const Scene& scene, const RenderSettings& settings,
                             Precision precision) {
        const gpu::ShaderFeatures f = gpu::featuresOf(scene, settings, o_.allFeatures);
        std::string key = precisionName(precision);
        for (bool kind : f.kinds) key += kind ? '1' : '0';
        for (bool shading : f.shading) key += shading ? '1' : '0';
        key += f.objectBvh ? '1' : '0';
        const auto found =
            std::find_if(used_.begin(), used_.end(), [&](const auto& t) { return t.first == key; });
        if (found != used_.end()) {
            used_.splice(used_.begin(), used_, found);
        } else {
            used_.emplace_front(
                key, std::make_unique<gpu::GpuTracer>(
                         context_, gpu::GpuRenderOptions{.shaderDirectory = shaderDirectoryFor(o_),
                                                         .allFeatures = o_.allFeatures,
                                                         .precision = precision}));
            if (used_.size() > kKept) used_.pop_back();
        }
        return *used_.front().second;
    }

private:
    static constexpr std::size_t kKept = 64;
    gpu::Context& context_;
    const Options& o_;
    std::list<std::pair<std::string, std::unique_ptr<gpu::GpuTracer>>>
        used_;  // the last used first
};

struct Comparison {
    bool agreed = false;
    std::string figures;
};

// The scene rendered on both with `settings`, compared as `render --check`
// compares them. `inRays`: the bound counted in rays instead of pixels.
// Throws gpu::BeyondTheLoopLimit when the GPU refuses the scene.
Comparison compareRenders(const Scene& scene, const RenderSettings& settings, Precision precision,
                          bool inRays, Tracers& tracers, const Options& o) {
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
    const Frame gpu = tracers.forScene(scene, settings, precision).render(scene, basis, settings);
    reference::ReferenceOptions reference;
    reference.threads = o.threads;
    const Frame cpu = reference::render(scene, basis, settings, reference);
    CompareResult result =
        compareImages(colorImage(gpu), colorImage(cpu), {kCheckFailThreshold, kCheckFailPercent});
    compareIds(idImage(gpu), idImage(cpu), result);
    // Counted in rays: float places a ray's hits to within a band along
    // every edge (docs/numerics.md, "Envelope"), and each ray, each of a
    // pixel's samples included, is a chance to fall in it. So 0.1 % of the
    // rays (never less than one) may differ; one that does differs on the
    // block x block pixels it fills. The ids are sample 0's: one ray a pixel
    // (a block). In pixels: render --check's own bound.
    const double block = inRays ? double(settings.block) * double(settings.block) : 1.0;
    const double rays = double(result.pixelCount) / block;
    const double share = kCheckFailPercent / 100;
    const double spp = inRays ? double(settings.spp) : 1.0;
    const double allowedColours = inRays ? block * std::max(1.0, share * rays * spp) : share * rays;
    const double allowedIds = inRays ? block * std::max(1.0, share * rays) : share * rays;
    char text[200];
    std::snprintf(text, sizeof text,
                  "%dx%d: %.3g %% of pixels over %.2g (largest %.3g), %.3g %% of ids differ",
                  settings.width, settings.height, result.percentOverThreshold, kCheckFailThreshold,
                  result.maxAbsError, result.idMismatchPercent);
    return {double(result.pixelsOverThreshold) <= allowedColours &&
                double(result.idMismatches.value_or(0)) <= allowedIds,
            text};
}

// One scene on both renderers at its own settings, the bound counted in
// rays. The images are small, and near the envelope's edge its share of
// rays in float's band (up to 0.1 %, measured at 160x120) gives a few
// hundred rays a fair chance of two: a scene over the bound is looked at
// again as the envelope was measured, `render --check` at 160x120 and one
// sample a pixel, and within that bound there it is reported apart, not as
// a disagreement.
Verdict judge(const std::string& path, const RandomScene& r, Tracers& tracers, const Options& o) {
    const Scene scene = loadScene(path, {}, nullptr);
    Verdict v;
    try {
        const Comparison own =
            compareRenders(scene, {r.width, r.height, r.block, r.spp, r.sampleSeed}, r.precision,
                           true, tracers, o);
        v.agreed = own.agreed;
        v.figures = own.figures;
        if (v.agreed) return v;
        const Comparison check =
            compareRenders(scene, {160, 120, 1, 1, r.sampleSeed}, r.precision, false, tracers, o);
        v.onlyAtCheckSize = check.agreed;
        v.figures += "; " + check.figures;
    } catch (const gpu::BeyondTheLoopLimit& refused) {  // right or refused: refused, and said
        v.refusal = refused.what();
    }
    return v;
}

std::string commandFor(const std::string& path, const RandomScene& r) {
    return "vkray render " + path + " --size " + std::to_string(r.width) + "x" +
           std::to_string(r.height) + " --spp " + std::to_string(r.spp) + " --seed " +
           std::to_string(r.sampleSeed) + " --block " + std::to_string(r.block) + " --precision " +
           precisionName(r.precision) + " --check";
}

}  // namespace

int runDifftest(const Options& o, std::ostream& out, std::ostream& err) {
    const fs::path dir = o.outDirectory.empty() ? fs::path("difftest") : fs::path(o.outDirectory);
    fs::create_directories(dir);
    gpu::Context context(gpu::ContextOptions{o.device, false, 0});
    Tracers tracers(context, o);
    const Stopwatch stopwatch;
    std::map<Precision, int> agreed, drawn, onlyAtCheckSize;
    int disagreed = 0, refused = 0;
    const Precision* only = o.precisionGiven ? &o.precision : nullptr;
    for (int i = 0; i < o.difftestScenes; ++i) {
        if (stopRequested()) throw Interrupted();
        const std::uint64_t seed = std::uint64_t(o.seed) + std::uint64_t(i);
        const RandomScene r = randomScene(seed, only);
        const std::string path = (dir / ("seed-" + std::to_string(seed) + ".sdl")).string();
        writeFileAtomically(path, r.sdl);
        if (!r.meshFile.empty()) writeFileAtomically((dir / r.meshFile).string(), r.meshText);
        ++drawn[r.precision];
        const Verdict v = judge(path, r, tracers, o);
        if (v.agreed) {
            ++agreed[r.precision];
            fs::remove(path);
            continue;
        }
        if (!v.refusal.empty()) {
            ++refused;
            out << "refused  seed " << seed << ": " << v.refusal << "\n  scene: " << path
                << std::endl;
            continue;
        }
        if (v.onlyAtCheckSize) {
            ++onlyAtCheckSize[r.precision];
            out << "at 160x120 only: seed " << seed << " (" << precisionName(r.precision)
                << "): " << v.figures << "\n  " << commandFor(path, r) << std::endl;
            continue;
        }
        ++disagreed;
        out << "DISAGREE seed " << seed << " (" << precisionName(r.precision) << "): " << v.figures
            << "\n  " << commandFor(path, r) << std::endl;
    }
    const double seconds = stopwatch.seconds();
    out << "difftest: " << o.difftestScenes << " scenes (seeds " << std::uint64_t(o.seed) << " to "
        << std::uint64_t(o.seed) + std::uint64_t(std::max(o.difftestScenes, 1) - 1) << ") in "
        << int(seconds + 0.5) << " s:";
    for (const auto& [mode, n] : drawn) {
        out << " " << precisionName(mode) << " " << agreed[mode] << " of " << n << " agreed";
        if (onlyAtCheckSize[mode] > 0)
            out << " (and " << onlyAtCheckSize[mode] << " at 160x120 only)";
        out << ";";
    }
    out << " " << refused << " refused by the GPU with an error\n";
    out << "difftest: " << o.difftestScenes - disagreed - refused << " passed, " << disagreed
        << " failed\n";
    (void)err;
    return disagreed > 0 ? 2 : 0;
}

}  // namespace vkray
