// vkray_bench's command line (CLI11): what to measure and how often. Apart
// from the harness so that the tests can call the parser.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vkray::bench {

struct BenchOptions {
    std::vector<std::string> sceneNames;  // --scenes a,b,...: names from the harness's list
    std::vector<std::string> sceneFiles;  // --scene FILE.sdl (repeatable)
    int randomScenes = 0;                 // --random N: scenes drawn by difftest's generator
    std::optional<std::uint32_t>
        seed;  // --seed S: the first one's seed, as difftest's (none: a fresh one)
    int width = 1920, height = 1080;
    int repeat = 2;
    int threads = 2;
    int tile = 0;  // the GPU tracer's tile side
    std::string shaderDirectory;
    int allWidth = 0, allHeight = 0;  // the all-features variant's image; 0: --size
    bool all = true, cpu = true, embree = true, fma = true;
    bool rayQuery = true;  // the ray-query traversal's column, where the device has ray queries
    bool shaded = false;   // keep lights and secondary rays
    bool experiments = false, onlyExperiments = false;  // the tuning table (docs/benchmarks.md)
    std::string
        againstDirectory;  // --against: the tuning table is these shaders against --shader-dir's
    std::string helpText;  // --help: the usage to print (nothing else is set then)
};

// `defaults` holds the default values (its sceneNames the default list);
// `knownScenes` the names --scenes may use. Throws Error naming the flag or
// value on bad usage: `--repeat abc` is an error, not 1.
BenchOptions parseBenchOptions(const std::vector<std::string>& args, const BenchOptions& defaults,
                               const std::vector<std::string>& knownScenes);

}  // namespace vkray::bench
