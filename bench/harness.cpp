// vkray's benchmark harness (issue #7): primary rays per second on the same
// scenes, rays and cores for
//   - the GPU tracer (lavapipe here) with the scene's specialised variant,
//   - the same with the all-features variant,
//   - the CPU reference (double precision, with shading),
//   - Embree 3 (closest hit only), one ray at a time and in 8-ray packets,
// side by side in one run, as a Markdown table; then lavapipe's FMA peak and
// the fraction of it the ray-sphere loop reaches. See BENCHMARKS.md.
//
//   build/vkray_bench [--scenes a,b,...] [--size WxH] [--repeat N] [--threads N]
//                     [--tile N] [--shader-dir DIR] [--all-size WxH] [--no-all]
//                     [--scene FILE.sdl] [--no-cpu] [--no-embree] [--no-fma]
#include "bench/bench_scenes.h"
#include "bench/fma_peak.h"
#if VKRAY_HAVE_EMBREE
#include "bench/embree_tracer.h"
#endif
#include "gpu/context.h"
#include "gpu/gpu_scene.h"
#include "gpu/gpu_tracer.h"
#include "reference/reference_tracer.h"
#include "scene/camera.h"
#include "scene/error.h"
#include "scene/scene_geometry.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <time.h>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <thread>

namespace {

using namespace vkray;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct BenchScene {
    std::string name;
    std::string description;
    std::function<Scene()> make;
    bool sphereOnly = false;
};

std::vector<BenchScene> knownScenes() {
    const std::string source = VKRAY_SOURCE_DIR;
    std::vector<BenchScene> scenes;
    for (int n : {1, 10, 16, 256, 10000, 100000}) {
        const std::string count = n >= 1000 ? std::to_string(n / 1000) + "k" : std::to_string(n);
        scenes.push_back({"spheres" + count, std::to_string(n) + " spheres",
                          [n] { return bench::randomSpheres(n); }, true});
    }
    scenes.push_back({"castle", "castle.dat (corpus)",
                      [source] { return bench::sdlScene(source + "/../shared/sdl-corpus/castle.dat"); }});
    scenes.push_back({"mesh", "UV sphere, 1002528 triangles", [] { return bench::uvSphereMesh(708); }});
    scenes.push_back({"default", "scenes/default.sdl",
                      [source] { return bench::sdlScene(source + "/scenes/default.sdl"); }});
    return scenes;
}

const char* kDefaultScenes = "spheres1,spheres10,spheres16,spheres256,spheres10k,spheres100k,castle,mesh";

struct Options {
    std::vector<BenchScene> scenes;
    int width = 1920, height = 1080;
    int repeat = 2;
    int threads = 2;
    int tile = gpu::GpuRenderOptions{}.tileSize;
    std::string shaderDirectory = VKRAY_BINARY_DIR "/shaders";
    int allWidth = 320, allHeight = 180;  // the all-features variant's image
    bool all = true, cpu = true, embree = true, fma = true;
};

[[noreturn]] void usage(const std::string& message) {
    std::fprintf(stderr,
                 "vkray_bench: %s\nusage: vkray_bench [--scenes a,b,...] [--scene FILE.sdl] "
                 "[--size WxH] [--repeat N] [--threads N] [--tile N] [--shader-dir DIR] [--all-size WxH] [--no-all] [--no-cpu] [--no-embree] [--no-fma]\n"
                 "scenes: %s, default (default list: %s)\n",
                 message.c_str(), kDefaultScenes, kDefaultScenes);
    std::exit(1);
}

Options parse(int argc, char** argv) {
    Options o;
    std::string names = kDefaultScenes;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(arg + " expects a value");
            return argv[++i];
        };
        if (arg == "--scenes") names = value();
        else if (arg == "--scene") files.push_back(value());
        else if (arg == "--size") {
            if (std::sscanf(value().c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 1 ||
                o.height < 1 || o.width > 16384 || o.height > 16384)
                usage("--size expects WxH, each side 1 .. 16384");
        } else if (arg == "--repeat") o.repeat = std::clamp(std::atoi(value().c_str()), 1, 100);
        else if (arg == "--threads") o.threads = std::clamp(std::atoi(value().c_str()), 1, 1024);
        else if (arg == "--shader-dir") o.shaderDirectory = value();
        else if (arg == "--tile") o.tile = std::clamp(std::atoi(value().c_str()), 8, 16384);
        else if (arg == "--all-size") {
            if (std::sscanf(value().c_str(), "%dx%d", &o.allWidth, &o.allHeight) != 2 ||
                o.allWidth < 1 || o.allHeight < 1 || o.allWidth > 16384 || o.allHeight > 16384)
                usage("--all-size expects WxH, each side 1 .. 16384");
        } else if (arg == "--no-all") o.all = false;
        else if (arg == "--no-cpu") o.cpu = false;
        else if (arg == "--no-embree") o.embree = false;
        else if (arg == "--no-fma") o.fma = false;
        else usage("unknown option " + arg);
    }
    if (!files.empty() && names == kDefaultScenes) names.clear();
    std::istringstream list(names);
    const std::vector<BenchScene> known = knownScenes();
    for (std::string name; std::getline(list, name, ',');) {
        if (name.empty()) continue;
        auto it = std::find_if(known.begin(), known.end(), [&](const auto& s) { return s.name == name; });
        if (it == known.end()) usage("unknown scene '" + name + "'");
        o.scenes.push_back(*it);
    }
    for (const std::string& file : files)
        o.scenes.push_back({file, file, [file] { return bench::sdlScene(file); }});
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

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

template <typename F>
Timing timed(F&& work) {
    const auto wall = Clock::now();
    const double cpu = processCpuSeconds();
    work();
    return {secondsSince(wall), processCpuSeconds() - cpu};
}

// The engines of the table, in its column order.
enum Engine { kGpu, kAllFeatures, kCpuReference, kEmbree1, kEmbree8, kEngines };

struct Row {
    std::string name, description, variant;
    std::size_t objects = 0;
    bool sphereOnly = false;
    std::optional<Timing> time[kEngines];
    std::string idsGpu = "-", idsEmbree = "-", builds;
    std::optional<Timing> smallGpu;  // the specialised variant on the all-features variant's image
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
// Specialised over all-features, both on the small image.
std::optional<double> specialisedOverAll(const Row& row, RayCounts rays, bool cpuTime) {
    const auto gpu = mrays(row.smallGpu, rays.small, cpuTime);
    const auto all = mrays(row, kAllFeatures, rays, cpuTime);
    if (!gpu || !all) return std::nullopt;
    return *gpu / *all;
}

void printTable(const std::vector<Row>& rows, RayCounts rays, bool cpuTime) {
    std::printf("| scene | objects | variant | GPU | all-features (small image) | CPU ref | Embree 1 | Embree 8 "
                "| GPU/all (small image) | GPU/CPU | GPU/Embree |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows) {
        std::optional<double> m[kEngines];
        for (int e = 0; e < kEngines; ++e) m[e] = mrays(r, Engine(e), rays, cpuTime);
        const std::optional<double> embree =
            m[kEmbree1] && m[kEmbree8] ? std::optional(std::max(*m[kEmbree1], *m[kEmbree8])) : std::nullopt;
        std::printf("| %s | %zu | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.description.c_str(),
                    r.objects, r.variant.c_str(), rate(m[kGpu]).c_str(), rate(m[kAllFeatures]).c_str(),
                    rate(m[kCpuReference]).c_str(), rate(m[kEmbree1]).c_str(), rate(m[kEmbree8]).c_str(),
                    rate(specialisedOverAll(r, rays, cpuTime)).c_str(), ratio(m[kGpu], m[kCpuReference]).c_str(),
                    ratio(m[kGpu], embree).c_str());
    }
}

// The aims of issue #7, from one table's figures.
void printAims(const std::vector<Row>& rows, RayCounts rays, bool cpuTime) {
    const char* unit = cpuTime ? "per CPU-second" : "wall clock";
    double minSphere = 1e30, maxSphere = 0, minAll = 1e30, bestEmbree = 0, worstEmbree = 1e30;
    std::optional<double> at10, at100k;
    for (const Row& r : rows) {
        const auto gpu = mrays(r, kGpu, rays, cpuTime);
        if (!gpu) continue;
        if (const auto overAll = specialisedOverAll(r, rays, cpuTime)) {
            minAll = std::min(minAll, *overAll);
            if (r.sphereOnly) {
                minSphere = std::min(minSphere, *overAll);
                maxSphere = std::max(maxSphere, *overAll);
            }
        }
        const auto e1 = mrays(r, kEmbree1, rays, cpuTime), e8 = mrays(r, kEmbree8, rays, cpuTime);
        if (e1 && e8) {
            bestEmbree = std::max(bestEmbree, *gpu / std::max(*e1, *e8));
            worstEmbree = std::min(worstEmbree, *gpu / std::max(*e1, *e8));
        }
        if (r.name == "spheres10") at10 = gpu;
        if (r.name == "spheres100k") at100k = gpu;
    }
    if (maxSphere > 0)
        std::printf("- specialised >= 1.5x all-features on sphere-only scenes (%s): %.2fx .. %.2fx: %s\n",
                    unit, minSphere, maxSphere, minSphere >= 1.5 ? "met" : "NOT met");
    if (minAll < 1e30)
        std::printf("- specialised never slower than all-features (%s): lowest %.2fx: %s\n", unit,
                    minAll, minAll >= 1 ? "met" : minAll >= 0.95 ? "even within noise" : "NOT met");
    if (bestEmbree > 0)
        std::printf("- lavapipe >= 0.7x Embree (%s): GPU/Embree %.2fx .. %.2fx: %s\n", unit,
                    worstEmbree, bestEmbree,
                    worstEmbree >= 0.7 ? "met" : bestEmbree >= 0.7 ? "met on some scenes" : "NOT met");
    if (at10 && at100k)
        std::printf("- cost per ray at 100000 spheres / at 10 (GPU, %s): %.2fx\n", unit, *at10 / *at100k);
}

// The ray-sphere test's arithmetic (trace.comp, shapes/sphere.glsl). llvmpipe
// runs every instruction of the path for each group of 8 rays, masked (no
// branch skips code), so a missed sphere costs the whole path: the ray into
// generic space (origin: 3 dot products with w = 1, 3 mul + 3 add each;
// direction: 3 dot3, 3 + 2 each) 33; a = d.d 5, b = o.d 5, b / a 1,
// fPerp = o - (b/a) d 6, fPerp.fPerp 5, 1 - that 1, a * that 1 (24); q with
// its sqrt 4; c = o.o - 1 6; t0 = c/q, t1 = q/a 2; both normals o + t d 12;
// the tie-tolerance products of testObject 2: 83 flops, a multiply or an add
// (fused or not), a division or a square root counting 1. Loads, compares,
// selects and the loop are not counted.
constexpr double kFlopsPerSphereTest = 83;

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    // lavapipe's thread count is pinned (as the tests do) unless the caller set it.
    if (!std::getenv("LP_NUM_THREADS")) ::setenv("LP_NUM_THREADS", std::to_string(o.threads).c_str(), 1);
    const auto runStart = Clock::now();
    try {
        gpu::Context context;
        const gpu::DeviceInfo& device = context.device();
        const std::string& shaders = o.shaderDirectory;
        gpu::GpuTracer specialised(context, {.shaderDirectory = shaders, .tileSize = o.tile});
        gpu::GpuTracer allFeatures(context, {.shaderDirectory = shaders, .allFeatures = true, .tileSize = o.tile});

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
        std::printf("%dx%d primary rays, best of %d runs; CPU reference and Embree on %d threads; "
                    "GPU tiles %d px, shaders %s\n",
                    o.width, o.height, o.repeat, o.threads, o.tile, shaders.c_str());
        std::printf("GPU: the dispatch loop with read-back, shaded; CPU reference: the whole render, "
                    "shaded; Embree: closest hit only (rtcIntersect1, rtcIntersect8 on 4x2 pixels)\n");
        std::printf("all-features variant: best of 2, on a %dx%d image of the same view; GPU/all compares "
                    "it with the specialised variant on that image\n", o.allWidth, o.allHeight);
        std::fflush(stdout);

        std::vector<Row> rows;
        const RayCounts rays{double(o.width) * o.height, double(o.allWidth) * o.allHeight};
        for (const BenchScene& bs : o.scenes) {
            const Scene scene = bs.make();
            const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
            const RenderSettings settings{o.width, o.height, 1};
            const CameraBasis basis = makeCameraBasis(camera, o.width, o.height);
            Row row;
            row.name = bs.name;
            row.description = bs.description;
            row.objects = scene.objects.size();
            row.sphereOnly = bs.sphereOnly;

            // GPU. llvmpipe JIT-compiles a pipeline at its first dispatch: a
            // small warm-up render takes that out of the timed ones. CPU time
            // is the whole render's less that of packing the scene (host work
            // that the wall-clock figure, the dispatch loop, leaves out too).
            const auto gpuTiming = [&](gpu::GpuTracer& tracer, bool all, const RenderSettings& size,
                                       int repeat, Frame* keep) {
                const CameraBasis sized = makeCameraBasis(camera, size.width, size.height);
                tracer.render(scene, makeCameraBasis(camera, 64, 36), {64, 36, 1});
                const gpu::ShaderFeatures features = gpu::featuresOf(scene, all);
                const double packCpu = timed([&] { gpu::packScene(scene, features); }).cpu;
                Timing best;
                for (int r = 0; r < repeat; ++r) {
                    gpu::GpuRenderStats stats;
                    Frame frame;
                    const Timing t = timed([&] { frame = tracer.render(scene, sized, size, &stats); });
                    best.keepBest({stats.renderSeconds, std::max(t.cpu - packCpu, 1e-9)});
                    if (std::getenv("VKRAY_BENCH_DEBUG"))
                        std::fprintf(stderr, "  %s %dx%d run %d: dispatch %.3f s, render %.3f s wall %.3f s CPU, setup %.3f s, pack %.3f CPU-s\n",
                                     all ? "all" : "specialised", size.width, size.height, r, stats.renderSeconds, t.wall, t.cpu, stats.setupSeconds, packCpu);
                    row.variant = all ? row.variant : stats.variant;
                    if (keep && r == 0) *keep = std::move(frame);
                }
                return best;
            };
            Frame gpuFrame;
            row.time[kGpu] = gpuTiming(specialised, false, settings, o.repeat, &gpuFrame);
            // The all-features variant is tens of times slower on lavapipe (it
            // runs every shape's code for every object, see BENCHMARKS.md), so
            // it is timed on a smaller image of the same view (best of 2), beside the
            // specialised variant on that same image for the ratio.
            if (o.all) {
                const RenderSettings small{o.allWidth, o.allHeight, 1};
                row.time[kAllFeatures] = gpuTiming(allFeatures, true, small, 2, nullptr);
                row.smallGpu = gpuTiming(specialised, false, small, 2, nullptr);
            }

            const Timing bvh = timed([&] { buildObjectBvh(scene); });
            char text[96];
            std::snprintf(text, sizeof text, "object BVH %.3f s", bvh.wall);
            row.builds = text;
            Frame cpuFrame;
            if (o.cpu) {
                Timing best;
                for (int r = 0; r < o.repeat; ++r)
                    best.keepBest(timed([&] { cpuFrame = reference::render(scene, basis, settings, {o.threads}); }));
                row.time[kCpuReference] = best;
                std::snprintf(text, sizeof text, "%.2f %%",
                              agreement(std::vector<int>(gpuFrame.id.begin(), gpuFrame.id.end()), cpuFrame.id));
                row.idsGpu = text;
            }
#if VKRAY_HAVE_EMBREE
            if (o.embree) {
                std::optional<bench::EmbreeTracer> embree;
                const Timing build = timed([&] { embree.emplace(scene, o.threads); });
                std::snprintf(text, sizeof text, ", Embree %.3f s (%s)", build.wall, embree->contents().c_str());
                row.builds += text;
                for (bool packets : {false, true}) {
                    Timing best;
                    std::vector<int> ids;
                    for (int r = 0; r < o.repeat; ++r)
                        best.keepBest(timed([&] { ids = embree->trace(basis, o.width, o.height, o.threads, packets); }));
                    row.time[packets ? kEmbree8 : kEmbree1] = best;
                    if (packets && o.cpu) {
                        std::snprintf(text, sizeof text, "%.2f %%", agreement(ids, cpuFrame.id));
                        row.idsEmbree = text;
                    }
                }
            }
#endif
            std::fprintf(stderr, "  %-12s done at %.0f s\n", bs.name.c_str(), secondsSince(runStart));
            rows.push_back(row);
        }

        std::printf("\nMrays/s, wall clock (best of %d):\n\n", o.repeat);
        printTable(rows, rays, false);
        std::printf("\nMrays per CPU-second (all threads' CPU time; robust to other load on the "
                    "machine):\n\n");
        printTable(rows, rays, true);
        std::printf("\nSame rays, same hits: object ids equal to the CPU reference's, and build times:\n\n");
        std::printf("| scene | GPU ids | Embree ids | builds |\n|---|---|---|---|\n");
        for (const Row& r : rows)
            std::printf("| %s | %s | %s | %s |\n", r.description.c_str(), r.idsGpu.c_str(),
                        r.idsEmbree.c_str(), r.builds.c_str());
        std::printf("\nAims of issue #7 (GPU/Embree against the faster Embree column):\n");
        printAims(rows, rays, false);
        printAims(rows, rays, true);
        std::fflush(stdout);

        if (o.fma) {
            std::printf("\nFMA peak (bench/shaders/fma_peak.comp on %s), per CPU-second and wall clock:\n",
                        device.name.c_str());
            bench::FmaPeak peak;
            for (int chains : {4, 8, 16}) {
                const bench::FmaPeak p =
                    bench::measureFmaPeak(context, VKRAY_SOURCE_DIR "/bench/shaders", chains);
                std::printf("- %2d vec4 chains per invocation: %.1f GFLOP per CPU-second, %.1f GFLOP/s wall\n",
                            chains, p.flops / p.cpuSeconds * 1e-9, p.flops / p.seconds * 1e-9);
                if (p.flops / p.cpuSeconds > peak.flops / std::max(peak.cpuSeconds, 1e-30)) peak = p;
            }
            const double peakPerCpuSecond = peak.flops / peak.cpuSeconds;
            // The ray-sphere loop alone: rays that miss 8 spheres, less rays
            // that miss 1 (every ray tests every sphere: no BVH under 9).
            Timing time[2];
            for (int r = 0; r < 4; ++r)  // the first of each JIT-compiles: best of the rest
                for (int k = 0; k < 2; ++k) {
                    const Scene scene = bench::missedSpheres(k == 0 ? 1 : 8);
                    const CameraBasis basis = makeCameraBasis(*scene.camera, o.width, o.height);
                    const RenderSettings settings{o.width, o.height, 1};
                    gpu::GpuRenderStats st;
                    const Timing t = timed([&] { specialised.render(scene, basis, settings, &st); });
                    if (r > 0) time[k].keepBest({st.renderSeconds, t.cpu});
                }
            const double tests = 7 * rays.full;
            const double cpuPerTest = (time[1].cpu - time[0].cpu) / tests;
            const double flopsPerCpuSecond = kFlopsPerSphereTest / cpuPerTest;
            std::printf("- ray-sphere loop: frames missing 1 and 8 spheres took %.3f and %.3f CPU-s "
                        "(%.3f and %.3f s wall): %.1f CPU-ns per ray-sphere test (%.0f Mtests per "
                        "CPU-second), x %.0f flops = %.2f GFLOP per CPU-second = %.1f %% of the FMA peak "
                        "(%.1f GFLOP per CPU-second)\n",
                        time[0].cpu, time[1].cpu, time[0].wall, time[1].wall, cpuPerTest * 1e9,
                        1e-6 / cpuPerTest, kFlopsPerSphereTest, flopsPerCpuSecond * 1e-9,
                        100 * flopsPerCpuSecond / peakPerCpuSecond, peakPerCpuSecond * 1e-9);
        }
        std::printf("\ntotal %.0f s; load average %s\n", secondsSince(runStart), loadAverage().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkray_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
