// vkray's benchmark harness: primary rays per second on the same
// scenes, rays and cores for
//   - the GPU tracer (lavapipe here) with the scene's specialised variant,
//   - the same with the all-features variant,
//   - the CPU reference (double precision, with shading),
//   - Embree 3 (closest hit only), one ray at a time and in 8-ray packets,
// side by side in one run, as a Markdown table; then lavapipe's FMA peak and
// the fraction of it the ray-sphere loop reaches. See BENCHMARKS.md.
//
//   LP_NUM_THREADS=2 build/vkray_bench [--size WxH] [--scenes a,b,...] ...
// (--help lists the options and scenes). Not a test: built with
// -DVKRAY_BENCHMARKS=ON; Embree only where CMake finds it.
#include "app/random_scene.h"
#include "bench/bench_options.h"
#include "bench/bench_scenes.h"
#include "bench/fma_peak.h"
#if VKRAY_HAVE_EMBREE
#include "bench/embree_tracer.h"
#endif
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "numerics/envelope.h"
#include "reference/reference_tracer.h"
#include "render/camera.h"
#include "scene/scene_geometry.h"
#include "util/error.h"
#include "util/files.h"
#include "util/stopwatch.h"

#include <malloc.h>
#include <stdlib.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

namespace {

using namespace vkray;

struct BenchScene {
    std::string name;
    std::string description;
    std::function<Scene()> make;
    bool sphereOnly = false;
    bool random = false;  // drawn by difftest's generator: traced primary and shaded
};

std::vector<BenchScene> knownScenes() {
    const std::string source = VKRAY_SOURCE_DIR;
    std::vector<BenchScene> scenes;
    for (int n : {1, 10, 16, 256, 1000, 10000, 100000}) {
        const std::string count = n >= 1000 ? std::to_string(n / 1000) + "k" : std::to_string(n);
        scenes.push_back({"spheres" + count, std::to_string(n) + " spheres",
                          [n] { return bench::randomSpheres(n); }, true});
    }
    // castle.dat is in the corpus of real SDL scenes, the folder VKRAY_SDL_CORPUS
    // names (parse() leaves castle out when it is unset).
    scenes.push_back({"castle", "castle.dat (corpus)", [] {
                          const char* corpus = std::getenv("VKRAY_SDL_CORPUS");
                          return bench::sdlScene(std::string(corpus ? corpus : "") + "/castle.dat");
                      }});
    scenes.push_back(
        {"mesh", "UV sphere, 1002528 triangles", [] { return bench::uvSphereMesh(708); }});
    scenes.push_back({"default", "scenes/default.sdl",
                      [source] { return bench::sdlScene(source + "/scenes/default.sdl"); }});
    return scenes;
}

const char* kDefaultScenes =
    "spheres1,spheres10,spheres16,spheres256,spheres1k,spheres10k,spheres100k,castle,mesh";

// The options, with the scenes resolved to what the harness traces.
struct Options : bench::BenchOptions {
    std::vector<BenchScene> scenes;
    std::uint32_t firstSeed = 0;  // of the random set, when --random drew one
};

// --random's scenes, written into a fresh folder (difftest's generator names
// a 3VN file to be beside the scene): seeds first .. first + n - 1, the same
// scenes `vkray difftest --seed FIRST --scenes N` draws.
std::vector<BenchScene> randomSet(std::uint32_t first, int n) {
    char folder[] = "/tmp/vkray_bench-XXXXXX";
    if (!::mkdtemp(folder)) throw Error("could not make a folder in /tmp for --random's scenes");
    std::vector<BenchScene> scenes;
    for (int i = 0; i < n; ++i) {
        const std::uint64_t seed = std::uint64_t(first) + std::uint64_t(i);
        const RandomScene r = randomScene(seed);
        const std::string path = std::string(folder) + "/seed-" + std::to_string(seed) + ".sdl";
        writeFileAtomically(path, r.sdl);
        for (const SideFile& file : r.files)
            writeFileAtomically(std::string(folder) + "/" + file.name, file.bytes);
        BenchScene scene{"seed-" + std::to_string(seed), "seed " + std::to_string(seed),
                         [path] { return loadScene(path, {}, nullptr); }};
        scene.random = true;
        scenes.push_back(scene);
    }
    return scenes;
}

// Prints the usage and exits 0 for --help; exits 1 with the error on bad usage.
Options parse(int argc, char** argv) {
    const std::vector<BenchScene> known = knownScenes();
    std::vector<std::string> names;
    for (const BenchScene& scene : known) names.push_back(scene.name);
    bench::BenchOptions defaults;
    std::istringstream list(kDefaultScenes);
    for (std::string name; std::getline(list, name, ',');) defaults.sceneNames.push_back(name);
    defaults.tile = gpu::GpuRenderOptions{}.tileSize;
    defaults.shaderDirectory = VKRAY_BINARY_DIR "/shaders";
    Options o;
    try {
        static_cast<bench::BenchOptions&>(o) = bench::parseBenchOptions(
            std::vector<std::string>(argv + 1, argv + argc), defaults, names);
    } catch (const Error& e) {
        std::fprintf(stderr, "vkray_bench: error: %s; try `vkray_bench --help`\n", e.what());
        std::exit(1);
    }
    if (!o.helpText.empty()) {
        std::fputs(o.helpText.c_str(), stdout);
        std::exit(0);
    }
    for (const std::string& name : o.sceneNames) {
        const char* corpus = std::getenv("VKRAY_SDL_CORPUS");
        if (name == "castle" && (corpus == nullptr || *corpus == '\0')) {
            std::fprintf(stderr,
                         "vkray_bench: castle skipped: VKRAY_SDL_CORPUS does not name the "
                         "corpus folder that holds castle.dat\n");
            continue;
        }
        o.scenes.push_back(*std::find_if(known.begin(), known.end(),
                                         [&](const BenchScene& s) { return s.name == name; }));
    }
    for (const std::string& file : o.sceneFiles)
        o.scenes.push_back({file, file, [file] { return bench::sdlScene(file); }});
    if (o.randomScenes > 0) {
        // A fresh seed unless one was given, so that no recorded run is of
        // scenes the kernel was tuned on; room left for the set's seeds.
        std::random_device fresh;
        o.firstSeed = o.seed ? *o.seed
                             : std::uint32_t(std::uint64_t(fresh()) %
                                             (0x100000000ull - std::uint64_t(o.randomScenes)));
        try {
            for (BenchScene& scene : randomSet(o.firstSeed, o.randomScenes))
                o.scenes.push_back(std::move(scene));
        } catch (const Error& e) {
            std::fprintf(stderr, "vkray_bench: error: %s\n", e.what());
            std::exit(1);
        }
    }
    return o;
}

std::string loadAverage() {
    std::ifstream file("/proc/loadavg");
    std::string one, five, fifteen;
    file >> one >> five >> fifteen;
    return one + " " + five + " " + fifteen;
}

std::string cpuModel() {
    std::ifstream info("/proc/cpuinfo");
    for (std::string line; std::getline(info, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

double agreement(const std::vector<int>& a, const std::vector<std::int32_t>& b) {
    size_t same = 0;
    for (size_t i = 0; i < a.size(); ++i) same += a[i] == b[i] ? 1 : 0;
    return 100.0 * double(same) / double(a.size());
}

std::string rate(std::optional<double> mrays) {
    if (!mrays) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", *mrays);
    return text;
}

std::string ratio(std::optional<double> a, std::optional<double> b) {
    if (!a || !b) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", *a / *b);
    return text;
}

// Wall-clock and CPU time (every thread of the process: lavapipe's workers,
// the reference's, Embree's) of one run. On a machine shared with other work
// the wall clock stretches while CPU time stays about the work done, so both
// are reported; on a quiet machine wall = CPU / threads when all cores work.
struct Timing {
    double wall = 1e30, cpu = 1e30;
    void keepBest(const Timing& t) {
        wall = std::min(wall, t.wall);
        cpu = std::min(cpu, t.cpu);
    }
};

template <typename F>
Timing timed(F&& work) {
    const Stopwatch wall;
    const double cpu = processCpuSeconds();
    work();
    return {wall.seconds(), processCpuSeconds() - cpu};
}

// The engines of the table, in its column order.
enum Engine {
    kGpu,
    kGpuEveryGroup,
    kAllFeatures,
    kCpuReference,
    kEmbree1,
    kEmbree8,
    kGpuRayQuery,  // the specialised variant with --traversal rayquery
    kGpuOwn,       // and with --traversal own (GPU is auto's choice)
    kEngines
};

struct Row {
    std::string name, description, variant;
    std::size_t objects = 0;
    bool sphereOnly = false, random = false, shaded = false;
    std::string refused;  // the GPU's refusal (beyond the loop-turn bound): nothing timed
    // The trace alone, and the scene's preparation before it (GPU: inputs,
    // BVHs, cover, uploads; CPU reference: the frame and its BVH; Embree:
    // its build), each the best of the runs.
    std::optional<Timing> time[kEngines], prepare[kEngines];
    std::string idsGpu = "-", idsEmbree = "-";
    std::string groupsTraced = "-";  // the specialised variant's workgroups dispatched, of all
    std::optional<Timing> smallGpu;  // the specialised variant on the all-features variant's image
    // The specialised variant's best device time (timestamp queries) and the
    // wall clock of that render: none where the queue has no timestamps.
    std::optional<double> gpuDevice, gpuDeviceWall;
    // The ray-query traversal: its acceleration structure's build (within
    // its preparation), and whether its ids equal the own walk's.
    std::optional<double> structureBuild;
    std::string idsRayQuery = "-";
    bool rayQueryChosen = false;  // auto took ray queries for the GPU column
};

// The rays of the big image and of the all-features variant's small one.
struct RayCounts {
    double full, small;
};

// Mrays/s from wall-clock time, or Mrays per CPU-second.
std::optional<double> mrays(const std::optional<Timing>& time, double rays, bool cpuTime) {
    if (!time) return std::nullopt;
    return rays / (cpuTime ? time->cpu : time->wall) * 1e-6;
}
std::optional<double> mrays(const Row& row, Engine e, RayCounts rays, bool cpuTime) {
    return mrays(row.time[e], e == kAllFeatures ? rays.small : rays.full, cpuTime);
}
// The same, over preparation and trace together.
std::optional<double> mraysWithPreparation(const Row& row, Engine e, RayCounts rays, bool cpuTime) {
    if (!row.time[e] || !row.prepare[e]) return std::nullopt;
    return mrays(
        Timing{row.time[e]->wall + row.prepare[e]->wall, row.time[e]->cpu + row.prepare[e]->cpu},
        rays.full, cpuTime);
}
// Specialised over all-features, both on the all-features variant's image.
std::optional<double> specialisedOverAll(const Row& row, RayCounts rays, bool cpuTime) {
    const auto gpu = mrays(row.smallGpu, rays.small, cpuTime);
    const auto all = mrays(row, kAllFeatures, rays, cpuTime);
    if (!gpu || !all) return std::nullopt;
    return *gpu / *all;
}
std::optional<double> over(std::optional<double> a, std::optional<double> b) {
    if (!a || !b) return std::nullopt;
    return *a / *b;
}
// The faster of Embree's two columns.
std::optional<double> embreeBest(const Row& row, RayCounts rays, bool cpuTime) {
    const auto e1 = mrays(row, kEmbree1, rays, cpuTime), e8 = mrays(row, kEmbree8, rays, cpuTime);
    if (!e1 || !e8) return std::nullopt;
    return std::max(*e1, *e8);
}

std::string seconds(const std::optional<Timing>& time) {
    if (!time) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", time->wall);
    return text;
}

void printTable(const std::vector<Row>& rows, RayCounts rays, bool cpuTime) {
    std::printf(
        "| scene | objects | variant | GPU | GPU, every workgroup | all-features | CPU ref "
        "| Embree 1 | Embree 8 | GPU, ray query | GPU/all | GPU/CPU | every workgroup/CPU | "
        "GPU/Embree | ray query/own walk "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
        "\n");
    for (const Row& r : rows) {
        if (!r.refused.empty()) {
            std::printf("| %s | %zu | refused: %s |\n", r.description.c_str(), r.objects,
                        r.refused.c_str());
            continue;
        }
        std::optional<double> m[kEngines];
        for (int e = 0; e < kEngines; ++e) m[e] = mrays(r, Engine(e), rays, cpuTime);
        std::printf(
            "| %s | %zu | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
            r.description.c_str(), r.objects, r.variant.c_str(), rate(m[kGpu]).c_str(),
            rate(m[kGpuEveryGroup]).c_str(), rate(m[kAllFeatures]).c_str(),
            rate(m[kCpuReference]).c_str(), rate(m[kEmbree1]).c_str(), rate(m[kEmbree8]).c_str(),
            rate(m[kGpuRayQuery]).c_str(), rate(specialisedOverAll(r, rays, cpuTime)).c_str(),
            ratio(m[kGpu], m[kCpuReference]).c_str(),
            ratio(m[kGpuEveryGroup], m[kCpuReference]).c_str(),
            rate(over(m[kGpu], embreeBest(r, rays, cpuTime))).c_str(),
            ratio(m[kGpuRayQuery], m[kGpuOwn]).c_str());
    }
}

// Each side's preparation, timed apart from its trace, and the GPU/CPU
// ratio over both together.
void printPreparation(const std::vector<Row>& rows, RayCounts rays) {
    std::printf(
        "| scene | GPU preparation s | CPU ref preparation s | Embree build s | ray query "
        "preparation s (its structure's build) | GPU/CPU, preparation + trace, per CPU-s | the "
        "same, wall |\n|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows) {
        if (!r.refused.empty()) continue;
        std::string rayQuery = seconds(r.prepare[kGpuRayQuery]);
        if (r.structureBuild) rayQuery += " (" + seconds(Timing{*r.structureBuild, 0}) + ")";
        std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", r.description.c_str(),
                    seconds(r.prepare[kGpu]).c_str(), seconds(r.prepare[kCpuReference]).c_str(),
                    seconds(r.prepare[kEmbree8]).c_str(), rayQuery.c_str(),
                    rate(over(mraysWithPreparation(r, kGpu, rays, true),
                              mraysWithPreparation(r, kCpuReference, rays, true)))
                        .c_str(),
                    rate(over(mraysWithPreparation(r, kGpu, rays, false),
                              mraysWithPreparation(r, kCpuReference, rays, false)))
                        .c_str());
    }
}

// Min, median and max of a ratio over the random set's rows of one kind.
struct Spread {
    double min = 0, median = 0, max = 0;
    size_t count = 0;
};

Spread spreadOf(std::vector<double> values) {
    if (values.empty()) return {};
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    const double median = n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
    return {values.front(), median, values.back(), n};
}

void printSpread(const char* what, const Spread& s) {
    if (s.count == 0)
        std::printf("| %s | - | - | - | 0 |\n", what);
    else
        std::printf("| %s | %.2f | %.2f | %.2f | %zu |\n", what, s.min, s.median, s.max, s.count);
}

// One aim over the random set: a floor every scene must clear and one its
// median must.
void printRandomAim(const char* what, const Spread& s, double floor, double median) {
    if (s.count == 0) return;
    std::printf("- %s >= %.1fx on every scene, >= %.1fx at the median: %.2fx, %.2fx: %s\n", what,
                floor, median, s.min, s.median,
                s.min >= floor && s.median >= median ? "met" : "NOT met");
}

void printRandomSummary(const std::vector<Row>& rows, RayCounts rays, const Options& o) {
    std::printf(
        "\nThe random set: %d scenes of `vkray difftest`'s generator, seeds %u to %llu "
        "(`vkray difftest --seed %u --scenes %d` draws them), %dx%d, each traced with "
        "primary rays only and shaded:\n\n",
        o.randomScenes, o.firstSeed,
        static_cast<unsigned long long>(o.firstSeed) + unsigned(o.randomScenes) - 1, o.firstSeed,
        o.randomScenes, o.width, o.height);
    std::printf("| ratio | min | median | max | scenes |\n|---|---|---|---|---|\n");
    int refused = 0;
    Spread spreads[2][12];
    for (bool shaded : {false, true}) {
        std::vector<double> figures[12];
        for (const Row& r : rows) {
            if (!r.random || r.shaded != shaded) continue;
            if (!r.refused.empty()) {
                refused += shaded ? 0 : 1;
                continue;
            }
            const auto add = [&](int i, std::optional<double> v) {
                if (v) figures[i].push_back(*v);
            };
            for (bool cpuTime : {true, false}) {
                const int k = cpuTime ? 0 : 1;
                add(k, over(mrays(r, kGpu, rays, cpuTime), mrays(r, kCpuReference, rays, cpuTime)));
                add(2 + k, over(mrays(r, kGpuEveryGroup, rays, cpuTime),
                                mrays(r, kCpuReference, rays, cpuTime)));
                add(4 + k, over(mraysWithPreparation(r, kGpu, rays, cpuTime),
                                mraysWithPreparation(r, kCpuReference, rays, cpuTime)));
                add(6 + k, over(mrays(r, kGpu, rays, cpuTime), embreeBest(r, rays, cpuTime)));
                add(8 + k,
                    over(mrays(r, kGpuRayQuery, rays, cpuTime), mrays(r, kGpuOwn, rays, cpuTime)));
                add(10 + k, over(mrays(r, kGpu, rays, cpuTime), mrays(r, kGpuOwn, rays, cpuTime)));
            }
        }
        const std::string kind = shaded ? "shaded" : "primary";
        const char* what[12] = {"GPU/CPU ref, per CPU-second",
                                "GPU/CPU ref, wall clock",
                                "GPU every workgroup (no cover)/CPU ref, per CPU-second",
                                "GPU every workgroup (no cover)/CPU ref, wall clock",
                                "GPU/CPU ref, preparation + trace, per CPU-second",
                                "GPU/CPU ref, preparation + trace, wall clock",
                                "GPU/Embree (the faster of 1 and 8), per CPU-second",
                                "GPU/Embree (the faster of 1 and 8), wall clock",
                                "GPU ray query/GPU own walk, per CPU-second",
                                "GPU ray query/GPU own walk, wall clock",
                                "GPU as shipped (auto's walk)/GPU own walk, per CPU-second",
                                "GPU as shipped (auto's walk)/GPU own walk, wall clock"};
        for (int i = 0; i < 12; ++i) {
            if (shaded && (i == 6 || i == 7)) continue;  // Embree traces primary rays only
            spreads[shaded][i] = spreadOf(figures[i]);
            printSpread((kind + ": " + what[i]).c_str(), spreads[shaded][i]);
        }
    }
    const auto chosen = std::count_if(rows.begin(), rows.end(), [](const Row& r) {
        return r.random && !r.shaded && r.rayQueryChosen;
    });
    if (spreads[0][8].count > 0)
        std::printf(
            "\nauto took ray queries for %td of the %d scenes (`vkray features` says why)\n",
            chosen, o.randomScenes);
    if (refused > 0)
        std::printf("\n%d scene(s) refused by the GPU (beyond the loop-turn bound): not counted\n",
                    refused);
    std::printf("\nAims over the random set:\n");
    printRandomAim("primary GPU/CPU ref, per CPU-second,", spreads[0][0], 2, 3);
    printRandomAim("primary GPU/CPU ref, wall clock,", spreads[0][1], 2, 3);
    printRandomAim("shaded GPU/CPU ref, per CPU-second,", spreads[1][0], 2, 3);
    printRandomAim("shaded GPU/CPU ref, wall clock,", spreads[1][1], 2, 3);
    printRandomAim("primary GPU/Embree, per CPU-second,", spreads[0][6], 0.7, 1.0);
    printRandomAim("primary GPU/Embree, wall clock,", spreads[0][7], 0.7, 1.0);
}

// The aims, from one table's figures.
void printAims(const std::vector<Row>& rows, RayCounts rays, bool cpuTime) {
    const char* unit = cpuTime ? "per CPU-second" : "wall clock";
    double minSphere = 1e30, maxSphere = 0, minAll = 1e30, bestEmbree = 0, worstEmbree = 1e30;
    std::optional<double> at10, at100k;
    for (const Row& r : rows) {
        const auto gpu = mrays(r, kGpu, rays, cpuTime);
        if (!gpu || r.random) continue;
        if (const auto overAll = specialisedOverAll(r, rays, cpuTime)) {
            minAll = std::min(minAll, *overAll);
            if (r.sphereOnly) {
                minSphere = std::min(minSphere, *overAll);
                maxSphere = std::max(maxSphere, *overAll);
            }
        }
        if (const auto embree = embreeBest(r, rays, cpuTime)) {
            bestEmbree = std::max(bestEmbree, *gpu / *embree);
            worstEmbree = std::min(worstEmbree, *gpu / *embree);
        }
        if (r.name == "spheres10") at10 = gpu;
        if (r.name == "spheres100k") at100k = gpu;
    }
    if (maxSphere > 0)
        std::printf(
            "- specialised >= 1.5x all-features on sphere-only scenes (%s): %.2fx .. %.2fx: %s\n",
            unit, minSphere, maxSphere, minSphere >= 1.5 ? "met" : "NOT met");
    if (minAll < 1e30)
        std::printf("- specialised never slower than all-features (%s): lowest %.2fx: %s\n", unit,
                    minAll,
                    minAll >= 1      ? "met"
                    : minAll >= 0.95 ? "even within noise"
                                     : "NOT met");
    if (bestEmbree > 0)
        std::printf("- lavapipe >= 0.7x Embree (%s): GPU/Embree %.2fx .. %.2fx: %s\n", unit,
                    worstEmbree, bestEmbree,
                    worstEmbree >= 0.7  ? "met"
                    : bestEmbree >= 0.7 ? "met on some scenes"
                                        : "NOT met");
    if (at10 && at100k)
        std::printf("- cost per ray at 100000 spheres / at 10 (GPU, %s): %.2fx\n", unit,
                    *at10 / *at100k);
}

// The ray-sphere test's arithmetic (toObjectSpace in trace.comp,
// shapes/sphere.glsl), counted in FMA slots: one multiply, add or fused
// multiply-add is one slot (mul + add pairs fused wherever they can be, so
// this is the least the hardware must issue); a division or square root
// counts 1, though it costs several. Every ray in the missed-spheres frames
// misses, so the test ends at `disc < 0`:
//   origin into generic space, 3 x dot(row, (o, 1)) = 3 x 3 fma      9
//   direction, 3 x dot3 = 3 x 3                                       9
//   a = d.d 3, b = o.d 3, b / a 1, fPerp = o - (b/a) d 3,
//   fPerp.fPerp 3, 1 - that 1, a * that 1                            15
// = 33 slots (57 flops unfused). llvmpipe runs a shader 8 lanes at a time
// with masks; if it does not branch around the rest of the test for a group
// whose lanes all missed, it also issues q with its sqrt 3, c 3, t0 and t1 2,
// both normals 6, the tie tolerance 2: 49 slots. Both fractions are printed.
// Loads, compares, selects and the loop are not counted.
constexpr double kSlotsPerMissedSphere = 33, kSlotsPerWholeSphereTest = 49;

// One tuning configuration of the specialised GPU variant.
struct Experiment {
    const char* name;
    gpu::GpuRenderOptions options;
};

// The tuning table: each configuration against the shipped one (8x8
// workgroups, the device's tile side, tiles left to right), the runs interleaved
// round-robin so that other load on the machine falls on all of them alike.
// The scene as the benchmark traces it. Primary rays only (default): no
// lights, so no shadow feelers, and no reflected or refracted rays; every
// engine then traces exactly the same rays (Embree finds closest hits only).
// What every engine writes of a w x h frame: each pixel's colour and object
// id, as `vkray render` does without --aov (the ids prove the same hits).
RenderSettings imageOf(int width, int height) {
    RenderSettings settings{width, height, 1};
    settings.aovs = false;
    return settings;
}

Scene sceneToTrace(const BenchScene& bench, bool shaded) {
    Scene scene = bench.make();
    if (!shaded) {
        scene.lights.clear();
        scene.maxRecursionDepth = 0;
    }
    return scene;
}

// The GPU tracers of the run: the specialised variant as `vkray render`
// ships it, the same with every workgroup traced (no primary cover: the
// cull neither peer gets), and the all-features variant.
struct Tracers {
    gpu::GpuTracer specialised, everyGroup, allFeatures;
    std::optional<gpu::GpuTracer> rayQuery, own;  // where the device has ray queries
};

// One scene, primary or shaded, on every engine.
Row measure(const BenchScene& bs, bool shaded, Tracers& tracers, const Options& o, RayCounts rays) {
    const Scene scene = sceneToTrace(bs, shaded);
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    const RenderSettings settings = imageOf(o.width, o.height);
    const CameraBasis basis = makeCameraBasis(camera, o.width, o.height);
    Row row;
    row.name = bs.name;
    row.description = bs.description + (bs.random ? (shaded ? ", shaded" : ", primary") : "");
    row.objects = scene.objects.size();
    row.sphereOnly = bs.sphereOnly;
    row.random = bs.random;
    row.shaded = shaded;
    // The mode `vkray render` takes for this scene and camera (--precision auto).
    const Precision precision = choosePrecision(scene, basis).precision;
    for (gpu::GpuTracer* t : {&tracers.specialised, &tracers.everyGroup, &tracers.allFeatures})
        t->setPrecision(precision);
    if (tracers.rayQuery) tracers.rayQuery->setPrecision(precision);
    if (tracers.own) tracers.own->setPrecision(precision);

    // llvmpipe JIT-compiles a pipeline at its first dispatch: a small
    // warm-up render takes that out of the timed ones.
    const auto warmUp = [&](gpu::GpuTracer& tracer) {
        tracer.render(scene, makeCameraBasis(camera, 64, 36), imageOf(64, 36));
    };
    // One timed render; `keep`: the specialised variant's full-size render,
    // whose image, share of workgroups and device time the tables show.
    const auto gpuRun = [&](gpu::GpuTracer& tracer, const RenderSettings& size, Engine engine,
                            Timing& best, Frame* keep) {
        gpu::GpuRenderStats stats;
        Frame frame =
            tracer.render(scene, makeCameraBasis(camera, size.width, size.height), size, &stats);
        best.keepBest({stats.renderSeconds, stats.renderCpuSeconds});
        if (engine == kGpuRayQuery) {
            Timing prepare = row.prepare[kGpuRayQuery].value_or(Timing{});
            prepare.keepBest({stats.setupSeconds, stats.setupCpuSeconds});
            row.prepare[kGpuRayQuery] = prepare;
            row.structureBuild =
                std::min(row.structureBuild.value_or(1e30), stats.structureSeconds);
            if (keep && keep->pixelCount() == 0) *keep = std::move(frame);
            return;
        }
        if (engine != kGpu) return;
        row.rayQueryChosen = stats.variant.find("+ray-query") != std::string::npos;
        row.variant = stats.variant + (precision == Precision::Robust
                                           ? std::string()
                                           : std::string(", ") + precisionName(precision));
        if (!keep) return;
        Timing prepare = row.prepare[kGpu].value_or(Timing{});
        prepare.keepBest({stats.setupSeconds, stats.setupCpuSeconds});
        row.prepare[kGpu] = prepare;
        char share[64];
        std::snprintf(share, sizeof share, "%.1f %% (%zu of %zu)",
                      100.0 * double(stats.groupsTraced) / double(stats.groups), stats.groupsTraced,
                      stats.groups);
        row.groupsTraced = share;
        if (stats.deviceSeconds && (!row.gpuDevice || *stats.deviceSeconds < *row.gpuDevice)) {
            row.gpuDevice = stats.deviceSeconds;
            row.gpuDeviceWall = stats.renderSeconds;
        }
        if (keep->pixelCount() == 0) *keep = std::move(frame);
    };
    // The specialised variants and the CPU reference take turns, each run of
    // one beside a run of the others, so that a slow spell of the machine (a
    // shared VM's) falls on all and their ratios hold.
    Frame gpuFrame, cpuFrame, rayQueryFrame;
    Timing gpuBest, everyGroupBest, rayQueryBest, ownBest, cpuBest, cpuPrepare;
    try {
        warmUp(tracers.specialised);
        warmUp(tracers.everyGroup);
        if (tracers.rayQuery) warmUp(*tracers.rayQuery), warmUp(*tracers.own);
        for (int r = 0; r < o.repeat; ++r) {
            gpuRun(tracers.specialised, settings, kGpu, gpuBest, &gpuFrame);
            gpuRun(tracers.everyGroup, settings, kGpuEveryGroup, everyGroupBest, nullptr);
            if (tracers.rayQuery) {
                gpuRun(*tracers.rayQuery, settings, kGpuRayQuery, rayQueryBest, &rayQueryFrame);
                gpuRun(*tracers.own, settings, kGpuOwn, ownBest, nullptr);
            }
            if (!o.cpu) continue;
            reference::ReferenceStats stats;
            reference::ReferenceOptions options{o.threads};
            options.stats = &stats;
            cpuFrame = reference::render(scene, basis, settings, options);
            cpuBest.keepBest({stats.trace.wall, stats.trace.cpu});
            cpuPrepare.keepBest({stats.prepare.wall, stats.prepare.cpu});
        }
    } catch (const gpu::BeyondTheLoopLimit& refused) {  // right or refused: refused, and said
        row.refused = refused.what();
        return row;
    }
    row.time[kGpu] = gpuBest;
    row.time[kGpuEveryGroup] = everyGroupBest;
    if (tracers.rayQuery) {
        row.time[kGpuRayQuery] = rayQueryBest;
        row.time[kGpuOwn] = ownBest;
        row.idsRayQuery = rayQueryFrame.id == gpuFrame.id ? "same" : "DIFFER";
    }
    // The all-features variant is tens of times slower on lavapipe
    // (BENCHMARKS.md): --all-size times it on a smaller image of the same
    // view, beside the specialised variant on that image. Not on the random
    // set, whose figures are the shipped variant's.
    if (o.all && !bs.random) {
        const RenderSettings small = imageOf(o.allWidth, o.allHeight);
        const bool sameSize = small.width == o.width && small.height == o.height;
        Timing allBest, smallBest;
        warmUp(tracers.allFeatures);
        for (int r = 0; r < o.repeat; ++r) {
            gpuRun(tracers.allFeatures, small, kAllFeatures, allBest, nullptr);
            if (!sameSize) gpuRun(tracers.specialised, small, kGpu, smallBest, nullptr);
        }
        row.time[kAllFeatures] = allBest;
        row.smallGpu = sameSize ? row.time[kGpu] : smallBest;
    }
    char text[96];
    if (o.cpu) {
        row.time[kCpuReference] = cpuBest;
        row.prepare[kCpuReference] = cpuPrepare;
        std::snprintf(
            text, sizeof text, "%.2f %%",
            agreement(std::vector<int>(gpuFrame.id.begin(), gpuFrame.id.end()), cpuFrame.id));
        row.idsGpu = text;
    }
#if VKRAY_HAVE_EMBREE
    // Embree finds closest hits of primary rays: it has no column in a
    // shaded run, whose feelers and secondary rays it does not trace.
    if (o.embree && !shaded) {
        std::optional<bench::EmbreeTracer> embree;
        const Timing build = timed([&] { embree.emplace(scene, o.threads); });
        row.prepare[kEmbree1] = row.prepare[kEmbree8] = build;
        for (bool packets : {false, true}) {
            Timing best;
            std::vector<int> ids;
            for (int r = 0; r < o.repeat; ++r)
                best.keepBest(timed(
                    [&] { ids = embree->trace(basis, o.width, o.height, o.threads, packets); }));
            row.time[packets ? kEmbree8 : kEmbree1] = best;
            if (packets && o.cpu) {
                std::snprintf(text, sizeof text, "%.2f %%", agreement(ids, cpuFrame.id));
                row.idsEmbree = text;
            }
        }
    }
#endif
    (void)rays;
    return row;
}

void runExperiments(const Options& o, gpu::Context& context) {
    const gpu::GpuRenderOptions base{.shaderDirectory = o.shaderDirectory, .tileSize = o.tile};
    const auto with = [&](auto change) {
        gpu::GpuRenderOptions options = base;
        change(options);
        return options;
    };
    std::vector<Experiment> experiments;
    if (!o.againstDirectory.empty()) {
        // An A/B test of a shader change: both folders' runs alternate.
        experiments = {
            {"--shader-dir", base},
            {"--against", with([&](auto& p) { p.shaderDirectory = o.againstDirectory; })}};
    } else {
        experiments = {
            {"8x8 workgroups, the device's tiles (shipped)", base},
            {"16x4 workgroups", with([](auto& p) { p.workgroupX = 16, p.workgroupY = 4; })},
            {"32x2 workgroups", with([](auto& p) { p.workgroupX = 32, p.workgroupY = 2; })},
            {"4x16 workgroups", with([](auto& p) { p.workgroupX = 4, p.workgroupY = 16; })},
            {"64 px tiles", with([](auto& p) { p.tileSize = 64; })},
            {"1024 px tiles", with([](auto& p) { p.tileSize = 1024; })},
            {"serpentine tile order", with([](auto& p) { p.serpentineTiles = true; })},
            {"sphere early-out (behind the ray)", with([](auto& p) {
                 p.userDefines = {{"VKRAY_SPHERE_EARLY_OUT", "1"}};
             })},
            {"8 lanes in a row (not 4x2)", with([](auto& p) {
                 p.userDefines = {{"VKRAY_ROW_LANES", "1"}};
             })},
            {"every workgroup traced (no primary cover)",
             with([](auto& p) { p.primaryCover = false; })},
        };
    }
    std::printf(
        "\nTuning (specialised variant, %dx%d, best of %d interleaved runs), Mrays per "
        "CPU-second and its ratio to the shipped configuration:\n\n",
        o.width, o.height, o.repeat + 1);
    std::printf("| scene |");
    for (const Experiment& e : experiments) std::printf(" %s |", e.name);
    std::printf("\n|---|");
    for (size_t i = 0; i < experiments.size(); ++i) std::printf("---|");
    std::printf("\n");
    for (const BenchScene& bs : o.scenes) {
        const Scene scene = sceneToTrace(bs, o.shaded);
        const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
        const CameraBasis basis = makeCameraBasis(camera, o.width, o.height);
        const RenderSettings settings = imageOf(o.width, o.height);
        std::vector<std::unique_ptr<gpu::GpuTracer>> tracers;
        std::vector<Frame> reference;
        for (const Experiment& e : experiments) {
            tracers.push_back(std::make_unique<gpu::GpuTracer>(context, e.options));
            // The first render JIT-compiles; keep its image to check each
            // configuration draws the same picture.
            reference.push_back(tracers.back()->render(scene, basis, settings));
        }
        std::vector<Timing> best(experiments.size());
        for (int r = 0; r < o.repeat + 1; ++r)
            for (size_t i = 0; i < experiments.size(); ++i) {
                gpu::GpuRenderStats stats;
                tracers[i]->render(scene, basis, settings, &stats);
                best[i].keepBest({stats.renderSeconds, stats.renderCpuSeconds});
            }
        const double rays = double(o.width) * o.height;
        std::printf("| %s |", bs.description.c_str());
        for (size_t i = 0; i < experiments.size(); ++i) {
            const bool same =
                reference[i].color == reference[0].color && reference[i].id == reference[0].id;
            std::printf(" %.2f (%.2fx)%s |", rays / best[i].cpu * 1e-6, best[0].cpu / best[i].cpu,
                        same ? "" : " image differs!");
        }
        std::printf("\n");
        std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    // Freed frames (tens of MB) stay in the heap, their pages mapped, so
    // that every later frame of the run is allocated the same way (the CPU
    // reference's is timed as its preparation): glibc would otherwise map some
    // afresh (page faults) and reuse others, by what the process did before.
    // (32 MiB: glibc's largest mapping threshold; a 1920x1080 frame's
    // largest array is 25 MB.)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    // lavapipe's thread count is pinned (as the tests do) unless the caller set it.
    if (!std::getenv("LP_NUM_THREADS"))
        ::setenv("LP_NUM_THREADS", std::to_string(o.threads).c_str(), 1);
    const Stopwatch run;
    try {
        gpu::Context context;
        const gpu::DeviceInfo& device = context.device();
        const std::string& shaders = o.shaderDirectory;

        char date[64];
        const std::time_t now = std::time(nullptr);
        std::strftime(date, sizeof date, "%Y-%m-%d %H:%M %Z", std::localtime(&now));
        std::printf("vkray_bench, %s\n", date);
        std::printf("machine: %s, %u CPUs (nproc); load average %s\n", cpuModel().c_str(),
                    std::thread::hardware_concurrency(), loadAverage().c_str());
        std::printf("device: %s (%s, driver %s %s), LP_NUM_THREADS=%s\n", device.name.c_str(),
                    device.type.c_str(), device.driverName.c_str(), device.driverInfo.c_str(),
                    std::getenv("LP_NUM_THREADS"));
#if VKRAY_HAVE_EMBREE
        std::printf("Embree %s\n", bench::EmbreeTracer::version().c_str());
#else
        std::printf("Embree: not built (CMake did not find Embree 3; apt install libembree-dev)\n");
#endif
        std::printf(
            "%dx%d, one ray a pixel, best of %d runs (the GPU's and the CPU reference's in "
            "turn); CPU reference and Embree on %d threads; GPU tiles %d px, shaders %s; each "
            "scene in the precision `vkray render` chooses for it (--precision auto)\n",
            o.width, o.height, o.repeat, o.threads,
            o.tile > 0 ? o.tile : gpu::defaultTileSide(device), shaders.c_str());
        std::printf(
            "%s; every engine's trace timed apart from its preparation (the preparation table "
            "below): GPU, the dispatch loop with read-back, as shipped (the primary cover "
            "leaves out workgroups whose rays meet nothing) and with every workgroup traced; "
            "CPU reference, its rays; both shade each hit and write its colour and object id "
            "(`vkray render` without --aov); Embree: closest hits of primary rays only "
            "(rtcIntersect1, rtcIntersect8 on 4x2 pixels), so no Embree figure in a shaded "
            "row\n",
            o.shaded ? "the fixed scenes shaded (--shaded): lights, shadow feelers and "
                       "secondary rays as the scenes say"
                     : "the fixed scenes with primary rays only: lights and secondary rays "
                       "removed");
        if (o.randomScenes > 0)
            std::printf(
                "random set (--random %d): seeds %u on, a fresh seed unless --seed gave one; "
                "each scene traced with primary rays only and shaded\n",
                o.randomScenes, o.firstSeed);
        if (o.allWidth != o.width || o.allHeight != o.height)
            std::printf(
                "all-features variant (--all-size): on a %dx%d image of the same view; GPU/all "
                "compares it with the specialised variant on that image\n",
                o.allWidth, o.allHeight);
        std::fflush(stdout);

        if (o.experiments) runExperiments(o, context);
        if (o.onlyExperiments) {
            std::printf("\ntotal %.0f s; load average %s\n", run.seconds(), loadAverage().c_str());
            return 0;
        }
        std::vector<Row> rows;
        const RayCounts rays{double(o.width) * o.height, double(o.allWidth) * o.allHeight};
        Tracers tracers{
            gpu::GpuTracer(context, {.shaderDirectory = shaders, .tileSize = o.tile}),
            gpu::GpuTracer(context,
                           {.shaderDirectory = shaders, .tileSize = o.tile, .primaryCover = false}),
            gpu::GpuTracer(context,
                           {.shaderDirectory = shaders, .allFeatures = true, .tileSize = o.tile}),
            std::nullopt};
        if (o.rayQuery && context.device().rayQuery) {
            tracers.rayQuery.emplace(context,
                                     gpu::GpuRenderOptions{.shaderDirectory = shaders,
                                                           .tileSize = o.tile,
                                                           .traversal = gpu::Traversal::RayQuery});
            tracers.own.emplace(context, gpu::GpuRenderOptions{.shaderDirectory = shaders,
                                                               .tileSize = o.tile,
                                                               .traversal = gpu::Traversal::Own});
        }
        for (const BenchScene& bs : o.scenes) {
            for (bool shaded : bs.random ? std::vector<bool>{false, true} : std::vector{o.shaded}) {
                rows.push_back(measure(bs, shaded, tracers, o, rays));
                std::fprintf(stderr, "  %-12s %s done at %.0f s\n", bs.name.c_str(),
                             shaded ? "shaded" : "primary", run.seconds());
            }
        }

        std::printf("\nMrays/s, wall clock (best of %d):\n\n", o.repeat);
        printTable(rows, rays, false);
        std::printf(
            "\nMrays per CPU-second (all threads' CPU time; robust to other load on the "
            "machine):\n\n");
        printTable(rows, rays, true);
        std::printf(
            "\nEach side's preparation before its trace, timed apart (best of %d; the tables "
            "above are of the trace alone): GPU, the scene's device inputs, BVHs, world-space "
            "triangles, primary cover and uploads (not the shader's compile); CPU reference, "
            "its frame and object BVH; Embree, its build:\n\n",
            o.repeat);
        printPreparation(rows, rays);
        std::printf("\nSame rays, same hits: object ids equal to the CPU reference's:\n\n");
        std::printf(
            "| scene | GPU ids | Embree ids | ray query's ids, against the GPU's | GPU workgroups "
            "traced (the rest meet nothing) |\n|---|---|---|---|---|\n");
        for (const Row& r : rows)
            std::printf("| %s | %s | %s | %s | %s |\n", r.description.c_str(), r.idsGpu.c_str(),
                        r.idsEmbree.c_str(), r.idsRayQuery.c_str(), r.groupsTraced.c_str());
        std::printf(
            "\nThe specialised variant's time on the device (timestamp queries around each "
            "dispatch; best of %d), against the wall clock of that render (the rest: submits, "
            "waits, read-back):\n\n",
            o.repeat);
        std::printf(
            "| scene | device s | wall s | device/wall | Mrays/s by device time |\n"
            "|---|---|---|---|---|\n");
        for (const Row& r : rows) {
            if (!r.gpuDevice) {
                std::printf("| %s | not measured (no timestamps) | - | - | - |\n",
                            r.description.c_str());
                continue;
            }
            std::printf("| %s | %.4f | %.4f | %.0f %% | %.2f |\n", r.description.c_str(),
                        *r.gpuDevice, *r.gpuDeviceWall, 100 * *r.gpuDevice / *r.gpuDeviceWall,
                        *r.gpuDevice > 0 ? rays.full / *r.gpuDevice * 1e-6 : 0.0);
        }
        if (o.randomScenes > 0) printRandomSummary(rows, rays, o);
        if (std::any_of(rows.begin(), rows.end(), [](const Row& r) { return !r.random; })) {
            std::printf("\nAims (GPU/Embree against the faster Embree column):\n");
            printAims(rows, rays, false);
            printAims(rows, rays, true);
        }
        std::fflush(stdout);

        if (o.fma) {
            std::printf(
                "\nFMA peak (bench/shaders/fma_peak.comp on %s), per CPU-second and wall clock:\n",
                device.name.c_str());
            bench::FmaPeak peak;
            for (int chains : {4, 8, 16}) {
                const bench::FmaPeak p =
                    bench::measureFmaPeak(context, VKRAY_SOURCE_DIR "/bench/shaders", chains);
                std::printf(
                    "- %2d vec4 chains per invocation: %.1f GFLOP per CPU-second, %.1f GFLOP/s "
                    "wall\n",
                    chains, p.flops / p.cpuSeconds * 1e-9, p.flops / p.seconds * 1e-9);
                if (p.flops / p.cpuSeconds > peak.flops / std::max(peak.cpuSeconds, 1e-30))
                    peak = p;
            }
            const double peakPerCpuSecond = peak.flops / peak.cpuSeconds;
            // The ray-sphere loop alone: rays that miss 8 spheres, less rays
            // that miss 1 (every ray tests every sphere: no BVH under 9).
            // Every workgroup is traced, though no ray meets a sphere.
            gpu::GpuTracer everyRay(
                context, {.shaderDirectory = shaders, .tileSize = o.tile, .primaryCover = false});
            Timing time[2];
            for (int r = 0; r < 4; ++r)  // the first of each JIT-compiles: best of the rest
                for (int k = 0; k < 2; ++k) {
                    const Scene scene = bench::missedSpheres(k == 0 ? 1 : 8);
                    const CameraBasis basis = makeCameraBasis(*scene.camera, o.width, o.height);
                    const RenderSettings settings = imageOf(o.width, o.height);
                    gpu::GpuRenderStats st;
                    everyRay.render(scene, basis, settings, &st);
                    if (r > 0) time[k].keepBest({st.renderSeconds, st.renderCpuSeconds});
                }
            const double tests = 7 * rays.full;
            const double cpuPerTest = (time[1].cpu - time[0].cpu) / tests;
            const double peakFmaPerCpuSecond = peakPerCpuSecond / 2;  // 2 flops per FMA
            const double slotsPerCpuSecond = kSlotsPerMissedSphere / cpuPerTest;
            std::printf(
                "- ray-sphere loop: frames missing 1 and 8 spheres took %.3f and %.3f CPU-s "
                "(%.3f and %.3f s wall): %.2f CPU-ns per ray-sphere test (%.0f Mtests per "
                "CPU-second)\n",
                time[0].cpu, time[1].cpu, time[0].wall, time[1].wall, cpuPerTest * 1e9,
                1e-6 / cpuPerTest);
            std::printf(
                "- FMA peak %.2f G FMA per CPU-second; the loop issues %.2f G FMA slots per "
                "CPU-second counting the %.0f a miss needs = %.1f %% of the peak "
                "(%.1f %% counting all %.0f of the whole test)\n",
                peakFmaPerCpuSecond * 1e-9, slotsPerCpuSecond * 1e-9, kSlotsPerMissedSphere,
                100 * slotsPerCpuSecond / peakFmaPerCpuSecond,
                100 * kSlotsPerWholeSphereTest / cpuPerTest / peakFmaPerCpuSecond,
                kSlotsPerWholeSphereTest);
        }
        std::printf("\ntotal %.0f s; load average %s\n", run.seconds(), loadAverage().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkray_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
