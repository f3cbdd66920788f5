#include "app/option_flags.h"

#include "render/camera.h"
#include "util/error.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace vkray {

int parseInt(const std::string& flag, const std::string& text, int lo, int hi) {
    long long value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        throw Error(flag + ": '" + text + "' is not a whole number");
    if (value < lo || value > hi)
        throw Error(flag + ": " + text + " is out of range (" + std::to_string(lo) + " .. " +
                    std::to_string(hi) + ")");
    return int(value);
}

namespace {

double parseNumber(const std::string& flag, const std::string& text) {
    double value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        throw Error(flag + ": '" + text + "' is not a number");
    return value;
}

glm::dvec3 parseVector(const std::string& flag, const std::string& text) {
    glm::dvec3 v;
    size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        size_t comma = text.find(',', start);
        if ((i < 2) != (comma != std::string::npos))
            throw Error(flag + ": expected three numbers x,y,z, found '" + text + "'");
        v[i] = parseNumber(flag, text.substr(start, comma - start));
        start = comma + 1;
    }
    return v;
}

// --size WxH
void parseSize(const std::string& text, Options& o) {
    size_t x = text.find('x');
    if (x == std::string::npos)
        throw Error("--size: expected WIDTHxHEIGHT, e.g. 640x480, found '" + text + "'");
    o.width = parseInt("--size", text.substr(0, x), 1, kMaxRenderSide);
    o.height = parseInt("--size", text.substr(x + 1), 1, kMaxRenderSide);
    if ((long long)o.width * o.height > kMaxRenderPixels)
        throw Error("--size: " + text + " is " + std::to_string((long long)o.width * o.height) +
                    " pixels, more than the limit of " + std::to_string(kMaxRenderPixels) +
                    "; render a smaller image");
}

// -D NAME=VALUE (or -DNAME=VALUE; VALUE defaults to 1), as a C compiler takes it.
void parseDefine(const std::string& text, Options& o) {
    const size_t eq = text.find('=');
    const std::string name = text.substr(0, eq);
    const std::string value = eq == std::string::npos ? "1" : text.substr(eq + 1);
    const bool identifier = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                            std::all_of(name.begin(), name.end(), [](char c) {
                                return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                            });
    if (!identifier) throw Error("-D: '" + text + "' is not NAME=VALUE with NAME a C identifier");
    if (value.find_first_of("\n\r") != std::string::npos)
        throw Error("-D " + name + ": the value must be one line");
    o.defines.emplace_back(name, value);
}

// A CLI11 range check in vkray's words: "--spp: 0 is out of range (1 .. 4096)".
CLI::Validator wholeNumberIn(long long lo, long long hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            long long value = 0;
            auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (ec != std::errc() || end != text.data() + text.size())
                return "'" + text + "' is not a whole number";
            if (value < lo || value > hi)
                return text + " is out of range (" + std::to_string(lo) + " .. " +
                       std::to_string(hi) + ")";
            return "";
        },
        "[" + std::to_string(lo) + " .. " + std::to_string(hi) + "]");
}

// --seed: any 32-bit unsigned value.
const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
        unsigned long long value = 0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size() || value > 0xffffffffull)
            return "'" + text + "' is not a whole number from 0 to 4294967295";
        return "";
    },
    "[0 .. 4294967295]");

// Every flag of every command: how it is parsed and its default help line.
// A command takes the flags it names (commandSpecs below), with its own help
// line where the meaning differs.
using AddFlag = CLI::Option* (*)(CLI::App&, Options&, const std::string& help);
struct FlagSpec {
    const char* name;
    const char* help;
    AddFlag add;
};

template <class Apply>
CLI::Option* valueFlag(CLI::App& app, const std::string& names, const std::string& help,
                       const char* typeName, Apply apply) {
    return app.add_option_function<std::string>(names, apply, help)->type_name(typeName);
}

const std::vector<FlagSpec>& flagSpecs() {
    static const std::vector<FlagSpec> specs = {
        {"-o",
         "image to write: .png (default: SCENE's name with .png), .pfm, or .exr (linear float, "
         "unclamped)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("-o,--output", o.outputPath, h)->type_name("FILE");
         }},
        {"--size", "image size (default 640x480; each side <= 16384)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--size", h, "WxH",
                              [&o](const std::string& v) { parseSize(v, o); });
         }},
        {"--device", "Vulkan device index (see `vkray devices`; default: automatic)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--device", o.device, h)
                 ->type_name("N")
                 ->check(wholeNumberIn(0, 1023));
         }},
        {"--block", "one ray per NxN block, the block filled with its colour",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--block", o.block, h)
                 ->type_name("N")
                 ->check(wholeNumberIn(1, 1024));
         }},
        {"--spp", "samples per pixel (default 1): stratified, jittered",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--spp", o.spp, h)
                 ->type_name("N")
                 ->check(wholeNumberIn(1, kMaxSpp));
         }},
        {"--seed", "seed of the sample positions (default 0)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--seed", o.seed, h)->type_name("S")->check(kSeed);
         }},
        {"--sample", "the sample to trace, of the pixel's --spp (0 to N-1, default 0)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--sample", o.pixelSample, h)
                 ->type_name("K")
                 ->check(wholeNumberIn(0, kMaxSpp - 1));
         }},
        {"--aov",
         "also write PREFIX.depth.pfm, PREFIX.normal.pfm, PREFIX.id.pfm; or, given "
         "NAME.exr, one OpenEXR file: R,G,B  Z  N.X,N.Y,N.Z  id  P.X,P.Y,P.Z",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--aov", o.aovPrefix, h)->type_name("PREFIX|NAME.exr");
         }},
        {"--cpu", "render with the CPU reference instead of the GPU",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--cpu", o.cpu, h);
         }},
        {"--check", "render with both and compare (exit 2 beyond tolerance)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--check", o.check, h);
         }},
        {"--lenient", "skip unknown words and unsupported shapes, with warnings",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--lenient", o.lenient, h);
         }},
        {"--validation", "enable the Khronos validation layer; any message fails",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--validation", o.validation, h);
         }},
        {"--variant", "compile every shape in (all), or only the scene's (scene, the default)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--variant", h, "all|scene", [&o](const std::string& v) {
                 if (v != "all" && v != "scene")
                     throw Error("--variant: expected 'all' or 'scene', found '" + v + "'");
                 o.allFeatures = v == "all";
             });
         }},
        {"--threads", "CPU reference threads (default: all cores)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--threads", o.threads, h)
                 ->type_name("N")
                 ->check(wholeNumberIn(1, 1024));
         }},
        {"--shader-dir",
         "GLSL folder (default: shaders/ next to the binary, else ../share/vkray/shaders)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--shader-dir", o.shaderDirectory, h)->type_name("DIR");
         }},
        {"--eye", "override the scene's camera: the eye",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--eye", h, "X,Y,Z",
                              [&o](const std::string& v) { o.eye = parseVector("--eye", v); });
         }},
        {"--look", "override the scene's camera: the point looked at",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--look", h, "X,Y,Z",
                              [&o](const std::string& v) { o.look = parseVector("--look", v); });
         }},
        {"--up", "override the scene's camera: the up direction",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--up", h, "X,Y,Z",
                              [&o](const std::string& v) { o.up = parseVector("--up", v); });
         }},
        {"--fov", "override the scene's camera: the vertical field of view, in degrees",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--fov", h, "DEG", [&o](const std::string& v) {
                 o.fov = parseNumber("--fov", v);
                 if (!(*o.fov > 0 && *o.fov < 180))
                     throw Error("--fov: must be between 0 and 180 degrees");
             });
         }},
        {"-D", "define for the shader compile (repeatable; -DNAME=VALUE too)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a
                 .add_option_function<std::vector<std::string>>(
                     "-D",
                     [&o](const std::vector<std::string>& values) {
                         for (const std::string& v : values) parseDefine(v, o);
                     },
                     h)
                 ->type_name("NAME=VALUE")
                 ->allow_extra_args(false)
                 ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
         }},
        {"--dump-spirv", "write the SPIR-V of the variant used to DIR",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--dump-spirv", o.dumpSpirvDirectory, h)->type_name("DIR");
         }},
        {"--watch", "re-render when the scene, a file it reads or a shader changes",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--watch", o.watch, h);
         }},
        {"--quiet", "no progress display on stderr",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--quiet", o.quiet, h);
         }},
        {"--all", "every variant, not only one per shape",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_flag("--all", o.everyVariant, h);
         }},
        {"--precision",
         "auto (default: robust, or fp64 where the scene is outside robust's envelope), naive, "
         "robust or fp64: float care on the GPU (docs/numerics.md)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--precision", h, "MODE", [&o](const std::string& v) {
                 o.precisionGiven = v != "auto";
                 o.precision =
                     o.precisionGiven ? parsePrecision("--precision", v) : Precision::Robust;
             });
         }},
        {"--traversal",
         "auto (default: the own walk, or ray queries where they measured faster), own (vkray's "
         "BVH walk in GLSL) or rayquery (the driver's acceleration structure, VK_KHR_ray_query): "
         "the walk that finds the objects (docs/ray-queries.md)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--traversal", h, "WALK", [&o](const std::string& v) {
                 o.traversal = gpu::parseTraversal("--traversal", v);
             });
         }},
        {"--out", "where the outputs go",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--out", o.outDirectory, h)->type_name("DIR");
         }},
        {"--frames", "quit after N passes of the progression (after the events)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--frames", o.frames, h)
                 ->type_name("N")
                 ->check(wholeNumberIn(1, 1000000));
         }},
        {"--screenshot", "with --frames: save the last frame there (a .png), as the `s` key would",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--screenshot", o.screenshotPath, h)->type_name("FILE");
         }},
        {"--events",
         "replay input: `key p`, `drag left 100 0`, `wheel 3`, `wait-pass`, `wait-cpu`, "
         "`wait-reload`, one a line",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--events", o.eventsPath, h)->type_name("FILE");
         }},
        {"--scenes", "how many scenes to draw (default 100)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--scenes", o.difftestScenes, h)
                 ->type_name("N")
                 ->check(wholeNumberIn(1, 100000000));
         }},
        {"--cases",
         "only the cases PATTERN selects: a glob (tiny*, *sphere?) or a part of the name",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--cases", o.casesPattern, h)->type_name("PATTERN");
         }},
        {"--cases-dir",
         "the cases' folder (default scenes/stress next to the binary, else ../share/vkray/stress)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--cases-dir", o.casesDirectory, h)->type_name("DIR");
         }},
        {"--diff", "with --check: write a diff image",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a.add_option("--diff", o.diffPath, h)->type_name("FILE");
         }},
        {"--fail", "with --check: colour difference threshold (default 0.02, relative above 1)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--fail", h, "T", [&o](const std::string& v) {
                 o.failThreshold = parseNumber("--fail", v);
                 if (*o.failThreshold < 0) throw Error("--fail: must not be negative");
             });
         }},
        {"--failpercent",
         "with --check: percent of pixels allowed to differ unexplained (default 0)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return valueFlag(a, "--failpercent", h, "P", [&o](const std::string& v) {
                 o.failPercent = parseNumber("--failpercent", v);
                 if (*o.failPercent < 0 || *o.failPercent > 100)
                     throw Error("--failpercent: must be between 0 and 100");
             });
         }},
        {"--ids",
         "object ids of A and B: .id.pfm files, or .exr files with an id channel (default: "
         "found beside A and B)",
         [](CLI::App& a, Options& o, const std::string& h) {
             return a
                 .add_option_function<std::vector<std::string>>(
                     "--ids",
                     [&o](const std::vector<std::string>& files) {
                         if (files.size() != 2) throw Error(kIdsExpected);
                         o.idsA = files.at(0);
                         o.idsB = files.at(1);
                     },
                     h)
                 ->type_name("IDS_A IDS_B")
                 ->expected(2);
         }},
    };
    return specs;
}

}  // namespace

CLI::Option* addFlag(CLI::App& app, Options& o, const std::string& name, const std::string& help) {
    for (const FlagSpec& spec : flagSpecs())
        if (name == spec.name)
            return spec.add(app, o, help.empty() ? std::string(spec.help) : help);
    throw Error("internal error: no flag " + name);
}

}  // namespace vkray
