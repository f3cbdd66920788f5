// Primary-ray throughput of the GPU tracer (lavapipe here) against the CPU
// reference on the same scene, image and cores, side by side in one run.
//   LP_NUM_THREADS=2 build/vkray_bench [--scene FILE] [--size WxH]
// Google Benchmark flags (e.g. --benchmark_repetitions=3) pass through.
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "reference/reference_tracer.h"
#include "scene/camera.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <thread>
#include <unistd.h>

namespace {

using namespace vkray;

struct Setup {
    Scene scene;
    RenderSettings settings{1920, 1080, 1};
    CameraBasis camera;
    std::string shaderDir;
    int threads = 2;
};

Setup& setup() {
    static Setup s;
    return s;
}

double primaryRays() {
    const RenderSettings& s = setup().settings;
    return double(s.width) * double(s.height);
}

void gpuRender(benchmark::State& state) {
    static gpu::Context context;
    gpu::GpuTracer tracer(context, {.shaderDirectory = setup().shaderDir, .allFeatures = state.range(0) != 0});
    state.SetLabel(context.device().name + (state.range(0) ? ", all-features variant" : ""));
    for (auto _ : state) {
        benchmark::DoNotOptimize(tracer.render(setup().scene, setup().camera, setup().settings));
    }
    state.counters["Mrays/s"] =
        benchmark::Counter(primaryRays() * 1e-6 * double(state.iterations()), benchmark::Counter::kIsRate);
}

void cpuRender(benchmark::State& state) {
    state.SetLabel("CPU reference, " + std::to_string(setup().threads) + " threads");
    for (auto _ : state)
        benchmark::DoNotOptimize(
            reference::render(setup().scene, setup().camera, setup().settings, {setup().threads}));
    state.counters["Mrays/s"] =
        benchmark::Counter(primaryRays() * 1e-6 * double(state.iterations()), benchmark::Counter::kIsRate);
}

// Prints the ratio of the rates after the usual table.
class RatioReporter : public benchmark::ConsoleReporter {
public:
    // Colour only on a terminal, so the table can be pasted into BENCHMARKS.md.
    RatioReporter() : ConsoleReporter(::isatty(1) ? OO_ColorTabular : OO_Tabular) {}
    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs)
            if (run.run_type == Run::RT_Iteration && run.counters.count("Mrays/s"))
                rates_[run.benchmark_name()] = run.counters.at("Mrays/s");
    }
    void Finalize() override {
        ConsoleReporter::Finalize();
        double gpu = 0, cpu = 0, all = 0;
        for (const auto& [name, rate] : rates_) {
            if (name.rfind("gpuRender/0", 0) == 0) gpu = rate;
            if (name.rfind("gpuRender/1", 0) == 0) all = rate;
            if (name.rfind("cpuRender", 0) == 0) cpu = rate;
        }
        if (gpu > 0 && cpu > 0)
            std::printf("\nGPU (scene variant) %.2f Mrays/s, CPU reference %.2f Mrays/s: ratio "
                        "GPU/CPU = %.2f\n", gpu, cpu, gpu / cpu);
        if (gpu > 0 && all > 0)
            std::printf("scene variant / all-features variant = %.2f\n", gpu / all);
    }

private:
    std::map<std::string, double> rates_;
};

}  // namespace

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    const fs::path root = fs::path(argv[0]).parent_path().parent_path();
    std::string scenePath = (root / "scenes/default.sdl").string();
    std::vector<char*> rest{argv[0]};
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--scene" && i + 1 < argc) scenePath = argv[++i];
        else if (arg == "--size" && i + 1 < argc) {
            std::sscanf(argv[++i], "%dx%d", &setup().settings.width, &setup().settings.height);
        } else rest.push_back(argv[i]);
    }
    int restCount = int(rest.size());
    benchmark::Initialize(&restCount, rest.data());

    try {
        Setup& s = setup();
        s.scene = loadScene(scenePath, {true}, nullptr);
        const Camera camera = s.scene.camera ? *s.scene.camera : autoCamera(s.scene);
        s.camera = makeCameraBasis(camera, s.settings.width, s.settings.height);
        s.shaderDir = (fs::path(argv[0]).parent_path() / "shaders").string();
        s.threads = int(std::max(1u, std::thread::hardware_concurrency()));
        const char* lp = std::getenv("LP_NUM_THREADS");
        std::printf("scene %s, %dx%d, LP_NUM_THREADS=%s, %d CPU reference threads\n",
                    scenePath.c_str(), s.settings.width, s.settings.height, lp ? lp : "(unset)",
                    s.threads);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkray_bench: %s\n", e.what());
        return 1;
    }
    // Wall-clock time for both (UseRealTime): what a user waits for, including
    // upload and readback on the GPU side and all threads on the CPU side.
    benchmark::RegisterBenchmark("gpuRender", gpuRender)->Arg(0)->Arg(1)->UseRealTime()
        ->Unit(benchmark::kMillisecond)->MinTime(2.0);
    benchmark::RegisterBenchmark("cpuRender", cpuRender)->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
    RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}
