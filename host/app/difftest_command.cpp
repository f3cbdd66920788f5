#include "app/difftest_command.h"

#include "app/commands.h"
#include "app/random_scene.h"
#include "app/watch.h"
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "gpu/shader_variant.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "reference/reference_tracer.h"
#include "scene/camera.h"
#include "scene/error.h"
#include "scene/scene_geometry.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <list>
#include <map>
#include <memory>

namespace vkray {

namespace {

namespace fs = std::filesystem;

struct Verdict {
    bool agreed = false;
    std::string refusal;  // the GPU's error, when it refused the scene
    std::string figures;  // what the comparison found
};

// The run's GPU tracers, one per shader variant and mode, the 64 used last
// kept: lavapipe compiles a variant's machine code (seconds for a large one)
// once per tracer, and a run of scenes with their own variants meets many
// a variant again (1000 scenes: 424 variants, 630 compiles with 64 kept,
// against 987 with one). With --variant all, one per mode.
class Tracers {
public:
    Tracers(gpu::Context& context, const Options& o) : context_(context), o_(o) {}

    gpu::GpuTracer& forScene(const Scene& scene, const RenderSettings& settings, Precision precision) {
        const gpu::ShaderFeatures f = gpu::featuresOf(scene, settings, o_.allFeatures);
        std::string key = precisionName(precision);
        for (bool kind : f.kinds) key += kind ? '1' : '0';
        for (bool shading : f.shading) key += shading ? '1' : '0';
        key += f.objectBvh ? '1' : '0';
        const auto found = std::find_if(used_.begin(), used_.end(), [&](const auto& t) { return t.first == key; });
        if (found != used_.end()) {
            used_.splice(used_.begin(), used_, found);
        } else {
            used_.emplace_front(key, std::make_unique<gpu::GpuTracer>(
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
    std::list<std::pair<std::string, std::unique_ptr<gpu::GpuTracer>>> used_;  // the last used first
};

// One scene on both renderers, compared as `render --check` compares them.
Verdict judge(const std::string& path, const RandomScene& r, Tracers& tracers, const Options& o) {
    const Scene scene = loadScene(path, {}, nullptr);
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    const RenderSettings settings{r.width, r.height, r.block, r.spp, r.sampleSeed};
    const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
    Verdict v;
    Frame gpu;
    try {
        gpu = tracers.forScene(scene, settings, r.precision).render(scene, basis, settings);
    } catch (const gpu::BeyondTheLoopLimit& refused) {  // right or refused: refused, and said
        v.refusal = refused.what();
        return v;
    }
    reference::ReferenceOptions reference;
    reference.threads = o.threads;
    const Frame cpu = reference::render(scene, basis, settings, reference);
    CompareResult result = compareImages(colorImage(gpu), colorImage(cpu),
                                         {kCheckFailThreshold, kCheckFailPercent});
    compareIds(idImage(gpu), idImage(cpu), result);
    // `render --check`'s bound, counted in rays instead of pixels: float
    // places a ray's hits to within a band along every edge (docs/numerics.md,
    // "Envelope"), and each ray, each of a pixel's samples included, is a
    // chance to fall in it. So 0.1 % of the rays (never less than one) may
    // differ; one that does differs on the block x block pixels it fills.
    // The ids are sample 0's: one ray a pixel (a block).
    const double block = double(r.block) * double(r.block);
    const double rays = double(result.pixelCount) / block;
    const double allowedColours = block * std::max(1.0, kCheckFailPercent / 100 * rays * double(r.spp));
    const double allowedIds = block * std::max(1.0, kCheckFailPercent / 100 * rays);
    v.agreed = double(result.pixelsOverThreshold) <= allowedColours &&
               double(result.idMismatches.value_or(0)) <= allowedIds;
    char text[160];
    std::snprintf(text, sizeof text, "%.3g %% of pixels over %.2g (largest %.3g), %.3g %% of ids differ",
                  result.percentOverThreshold, kCheckFailThreshold, result.maxAbsError,
                  result.idMismatchPercent);
    v.figures = text;
    return v;
}

std::string commandFor(const std::string& path, const RandomScene& r) {
    return "vkray render " + path + " --size " + std::to_string(r.width) + "x" +
           std::to_string(r.height) + " --spp " + std::to_string(r.spp) + " --seed " +
           std::to_string(r.sampleSeed) + " --block " + std::to_string(r.block) +
           " --precision " + precisionName(r.precision) + " --check";
}

}  // namespace

int runDifftest(const Options& o, std::ostream& out, std::ostream& err) {
    const fs::path dir = o.outDirectory.empty() ? fs::path("difftest") : fs::path(o.outDirectory);
    fs::create_directories(dir);
    gpu::Context context(gpu::ContextOptions{o.device, false, 0});
    Tracers tracers(context, o);
    const auto start = std::chrono::steady_clock::now();
    std::map<Precision, int> agreed, drawn;
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
            out << "refused  seed " << seed << ": " << v.refusal << "\n  scene: " << path << "\n";
            continue;
        }
        ++disagreed;
        out << "DISAGREE seed " << seed << " (" << precisionName(r.precision) << "): " << v.figures
            << "\n  " << commandFor(path, r) << "\n";
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out << "difftest: " << o.difftestScenes << " scenes (seeds " << std::uint64_t(o.seed) << " to "
        << std::uint64_t(o.seed) + std::uint64_t(std::max(o.difftestScenes, 1) - 1) << ") in "
        << int(seconds + 0.5) << " s:";
    for (const auto& [mode, n] : drawn)
        out << " " << precisionName(mode) << " " << agreed[mode] << " of " << n << " agreed;";
    out << " " << refused << " refused by the GPU with an error\n";
    out << "difftest: " << o.difftestScenes - disagreed << " passed, " << disagreed << " failed\n";
    (void)err;
    return disagreed > 0 ? 2 : 0;
}

}  // namespace vkray
