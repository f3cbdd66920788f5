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
#include "numerics/agreement.h"
#include "numerics/envelope.h"
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
#include <optional>
#include <utility>

namespace vkray {

namespace {

namespace fs = std::filesystem;

struct Verdict {
    bool agreed = false;
    Precision precision = Precision::Robust;  // the mode rendered (auto's choice for an open scene)
    std::size_t setAside = 0, pixels = 0;
    std::string refusal;        // the reader's or the GPU's error, when either refused the scene
    std::string notComparable;  // what passes fp64's envelope too, for an open scene
    std::string figures;        // what the comparison found
    std::optional<std::pair<int, int>> firstUnexplained;  // the first pixel nothing explains
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
                                                         .precision = precision,
                                                         .traversal = o_.traversal}));
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

// One scene on both renderers at its own settings, judged by the margin
// rule (numerics/agreement.h): every differing pixel explained by the
// mode's error bound, or the scene disagrees.
// An open scene (RandomScene::open) is rendered in the mode `--precision
// auto` chooses, and not compared where it passes fp64's envelope too.
Verdict judge(const std::string& path, const RandomScene& r, Tracers& tracers, const Options& o) {
    Verdict v;
    v.precision = r.precision;
    try {
        const Scene scene = loadScene(path, {}, nullptr);
        RenderSettings settings{r.width, r.height, r.block, r.spp, r.sampleSeed};
        settings.aovs = true;
        const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
        const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
        if (r.open) {
            const PrecisionChoice choice = choosePrecision(scene, basis);
            v.precision = choice.precision;
            if (!choice.beyondEvery.empty()) {
                v.notComparable = describe(choice.beyondEvery.front(), Precision::Fp64);
                return v;
            }
        }
        const Frame gpu =
            tracers.forScene(scene, settings, v.precision).render(scene, basis, settings);
        reference::ReferenceOptions reference;
        reference.threads = o.threads;
        const Frame cpu = reference::render(scene, basis, settings, reference);
        AgreementOptions rule;
        rule.colorThreshold = kCheckFailThreshold;
        rule.allowedPercent = kCheckFailPercent;
        rule.threads = o.threads;
        const Agreement a = judgeAgreement(scene, basis, settings, v.precision, gpu, cpu, rule);
        v.agreed = a.passed;
        v.setAside = a.setAside;
        v.pixels = a.pixels;
        char text[200];
        std::snprintf(text, sizeof text,
                      "%dx%d: %zu of %zu pixels differ, %zu set aside, %zu unexplained (largest "
                      "colour difference %.3g)",
                      settings.width, settings.height, a.differing, a.pixels, a.setAside,
                      a.unexplained, a.largest);
        v.figures = text;
        if (!a.firstUnexplained.empty()) v.firstUnexplained = a.firstUnexplained.front();
    } catch (const gpu::BeyondTheLoopLimit& refused) {  // right or refused: refused, and said
        v.refusal = refused.what();
    } catch (const Error& refused) {  // the reader's (a generator's bug) or the GPU's own limits
        v.refusal = refused.what();
    }
    return v;
}

std::string commandFor(const std::string& path, const RandomScene& r) {
    return "vkray render " + path + " --size " + std::to_string(r.width) + "x" +
           std::to_string(r.height) + " --spp " + std::to_string(r.spp) + " --seed " +
           std::to_string(r.sampleSeed) + " --block " + std::to_string(r.block) + " --precision " +
           (r.open ? "auto" : precisionName(r.precision)) + " --check";
}

// `vkray pixel` on the first unexplained pixel, in the mode rendered: with
// several samples, --sample 0 .. spp - 1 shows each one's tree.
std::string pixelCommandFor(const std::string& path, const RandomScene& r, const Verdict& v) {
    std::string command = "vkray pixel " + path + " " + std::to_string(v.firstUnexplained->first) +
                          " " + std::to_string(v.firstUnexplained->second) + " --size " +
                          std::to_string(r.width) + "x" + std::to_string(r.height) + " --block " +
                          std::to_string(r.block) + " --precision " + precisionName(v.precision);
    if (r.spp > 1)
        command += " --spp " + std::to_string(r.spp) + " --seed " + std::to_string(r.sampleSeed) +
                   " --sample K  (K = 0 to " + std::to_string(r.spp - 1) + ")";
    return command;
}

}  // namespace

int runDifftest(const Options& o, std::ostream& out, std::ostream& err) {
    const fs::path dir = o.outDirectory.empty() ? fs::path("difftest") : fs::path(o.outDirectory);
    fs::create_directories(dir);
    gpu::Context context(gpu::ContextOptions{o.device, false, 0});
    Tracers tracers(context, o);
    const Stopwatch stopwatch;
    std::map<std::string, int> agreed, drawn;  // by the mode's name, auto's as "auto (fp64)"
    int disagreed = 0, refused = 0, notComparable = 0;
    std::size_t setAside = 0, pixels = 0;
    const Precision* only = o.precisionGiven ? &o.precision : nullptr;
    for (int i = 0; i < o.difftestScenes; ++i) {
        if (stopRequested()) throw Interrupted();
        const std::uint64_t seed = std::uint64_t(o.seed) + std::uint64_t(i);
        const RandomScene r = randomScene(seed, only);
        const std::string path = (dir / ("seed-" + std::to_string(seed) + ".sdl")).string();
        writeFileAtomically(path, r.sdl);
        for (const SideFile& file : r.files)
            writeFileAtomically((dir / file.name).string(), file.bytes);
        const Verdict v = judge(path, r, tracers, o);
        const std::string mode = r.open ? std::string("auto (") + precisionName(v.precision) + ")"
                                        : std::string(precisionName(v.precision));
        if (!v.notComparable.empty()) {  // counted apart, neither agreed nor not
            ++notComparable;
            out << "not comparable seed " << seed << ": " << v.notComparable
                << ", past every mode's envelope\n  scene: " << path << std::endl;
            continue;
        }
        ++drawn[mode];
        setAside += v.setAside;
        pixels += v.pixels;
        if (v.agreed) {
            ++agreed[mode];
            fs::remove(path);
            for (const SideFile& file : r.files)
                if (file.name.starts_with("seed-")) fs::remove(dir / file.name);
            continue;
        }
        if (!v.refusal.empty()) {
            ++refused;
            out << "refused  seed " << seed << ": " << v.refusal << "\n  scene: " << path
                << std::endl;
            continue;
        }
        ++disagreed;
        out << "DISAGREE seed " << seed << " (" << mode << "): " << v.figures << "\n  "
            << commandFor(path, r) << "\n";
        if (v.firstUnexplained) out << "  " << pixelCommandFor(path, r, v) << "\n";
        out << std::flush;
    }
    const double seconds = stopwatch.seconds();
    out << "difftest: " << o.difftestScenes << " scenes (seeds " << std::uint64_t(o.seed) << " to "
        << std::uint64_t(o.seed) + std::uint64_t(std::max(o.difftestScenes, 1) - 1) << ") in "
        << int(seconds + 0.5) << " s:";
    for (const auto& [mode, n] : drawn)
        out << " " << mode << " " << agreed[mode] << " of " << n << " agreed;";
    out << " " << notComparable << " not comparable; " << refused << " refused with an error\n";
    char share[120];
    std::snprintf(share, sizeof share, "%.4g %%",
                  pixels ? 100.0 * double(setAside) / double(pixels) : 0.0);
    out << "difftest: " << setAside << " of " << pixels << " pixels set aside (" << share
        << "): within a decision's margin of the mode's error bound\n";
    out << "difftest: " << o.difftestScenes - disagreed - refused - notComparable << " passed, "
        << disagreed << " failed\n";
    (void)err;
    return disagreed > 0 ? 2 : 0;
}

}  // namespace vkray
