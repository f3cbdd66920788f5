// The command line, parsed by CLI11 into a plain struct (pbrt-v4's Options
// style): each command a subcommand with its own flags and generated --help;
// `--x v` and `--x=v` both work; unknown flags, values out of range and
// flags that need or exclude another are errors that name the flag.
#pragma once

#include "gpu/precision.h"
#include "gpu/traversal.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vkray {

enum class Command {
    Help,
    Version,
    Render,
    Pixel,
    Compare,
    Devices,
    ShadersCheck,
    Stress,
    Report,
    Features,
    Difftest,
    View
};

// The largest image vkray renders: each side at most kMaxRenderSide and at
// most kMaxRenderPixels in all (a Frame costs 32 bytes a pixel on the host).
inline constexpr int kMaxRenderSide = 16384;
inline constexpr long long kMaxRenderPixels = 64ll * 1024 * 1024;

struct Options {
    Command command = Command::Help;
    std::string helpText;  // Command::Help: the usage asked for (`vkray [COMMAND] --help`)

    // render
    std::string scenePath;
    std::string outputPath;  // -o; default: the scene's name with .png, in the current folder
    int width = 640;
    int height = 480;
    int device = -1;  // --device N; -1 = automatic choice
    int block = 1;
    int spp = 1;             // --spp N: samples per pixel (anti-aliasing)
    std::uint32_t seed = 0;  // --seed S: the sample positions' seed
    std::string aovPrefix;
    bool cpu = false;
    bool check = false;
    bool lenient = false;
    bool validation = false;
    bool allFeatures = false;  // --variant all
    int threads = 0;           // CPU reference threads; 0 = all cores
    std::string shaderDirectory;
    std::optional<glm::dvec3> eye, look, up;
    std::optional<double> fov;
    std::vector<std::pair<std::string, std::string>> defines;  // -D NAME=VALUE
    std::string dumpSpirvDirectory;                            // --dump-spirv DIR
    bool watch = false;                                        // --watch
    bool quiet = false;                                        // --quiet: no progress display

    bool everyVariant = false;  // shaders check --all

    // view SCENE [--frames N --screenshot FILE] [--events FILE]; its --size
    // defaults to 960x540 and its --spp to 16
    int frames = 0;              // --frames N: quit after N passes (0: stay open)
    std::string screenshotPath;  // --screenshot FILE: with --frames, the last frame saved there
    std::string eventsPath;      // --events FILE: input replayed (app/view_events.h)

    // render, pixel: --precision auto|naive|robust|fp64 (gpu/precision.h);
    // auto (precisionGiven false) is resolved per scene by precisionInForce.
    Precision precision = Precision::Robust;
    bool precisionGiven = false;
    // render, view, features, difftest: --traversal auto|own|rayquery (gpu/traversal.h).
    gpu::Traversal traversal = gpu::Traversal::Auto;

    // stress [--cases PATTERN] [--cases-dir DIR] [--out DIR]; report SCENE [--out DIR]
    std::string casesPattern;
    std::string casesDirectory;  // default: scenes/stress here, else beside the binary's folder
    std::string outDirectory;    // default: stress-report / report-SCENE

    // difftest [--scenes N] [--seed S]: scenes drawn from seeds S .. S + N - 1
    int difftestScenes = 100;

    // pixel SCENE X Y
    int pixelX = 0, pixelY = 0;
    int pixelSample = 0;  // --sample K: which of the pixel's --spp samples `pixel` traces

    // compare (and render --check)
    std::string imageA, imageB;
    std::string idsA, idsB;  // --ids A B
    std::string diffPath;
    std::optional<double> failThreshold;
    std::optional<double> failPercent;
};

// Throws Error (message names the flag or value) on bad usage. `--help`, at
// the top or after a command, gives Command::Help with that usage in helpText.
Options parseOptions(const std::vector<std::string>& args);

// `vkray --help`: the commands, generated from the parser's own table.
std::string usageText();

}  // namespace vkray
