#include "app/options.h"

#include "render/camera.h"
#include "util/error.h"

#include <charconv>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>

namespace vkray {

namespace {

double parseNumber(const std::string& flag, const std::string& text) {
    double value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        throw Error(flag + ": '" + text + "' is not a number");
    return value;
}

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

// --seed: any 32-bit unsigned value.
std::uint32_t parseSeed(const std::string& text) {
    unsigned long long value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value > 0xffffffffull)
        throw Error("--seed: '" + text + "' is not a whole number from 0 to 4294967295");
    return std::uint32_t(value);
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
    if (x == std::string::npos) throw Error("--size: expected WIDTHxHEIGHT, e.g. 640x480, found '" + text + "'");
    o.width = parseInt("--size", text.substr(0, x), 1, kMaxRenderSide);
    o.height = parseInt("--size", text.substr(x + 1), 1, kMaxRenderSide);
    if ((long long)o.width * o.height > kMaxRenderPixels)
        throw Error("--size: " + text + " is " + std::to_string((long long)o.width * o.height) +
                    " pixels, more than the limit of " + std::to_string(kMaxRenderPixels) +
                    "; render a smaller image");
}

struct Flag {
    bool takesValue;
    std::function<void(Options&, const std::string&)> apply;
};

const std::map<std::string, Flag>& renderFlags() {
    static const std::map<std::string, Flag> flags = {
        {"-o", {true, [](Options& o, const std::string& v) { o.outputPath = v; }}},
        {"--output", {true, [](Options& o, const std::string& v) { o.outputPath = v; }}},
        {"--size", {true, [](Options& o, const std::string& v) { parseSize(v, o); }}},
        {"--device", {true, [](Options& o, const std::string& v) { o.device = parseInt("--device", v, 0, 1023); }}},
        {"--block", {true, [](Options& o, const std::string& v) { o.block = parseInt("--block", v, 1, 1024); }}},
        {"--spp", {true, [](Options& o, const std::string& v) { o.spp = parseInt("--spp", v, 1, kMaxSpp); }}},
        {"--seed", {true, [](Options& o, const std::string& v) { o.seed = parseSeed(v); }}},
        {"--aov", {true, [](Options& o, const std::string& v) { o.aovPrefix = v; }}},
        {"--cpu", {false, [](Options& o, const std::string&) { o.cpu = true; }}},
        {"--check", {false, [](Options& o, const std::string&) { o.check = true; }}},
        {"--lenient", {false, [](Options& o, const std::string&) { o.lenient = true; }}},
        {"--validation", {false, [](Options& o, const std::string&) { o.validation = true; }}},
        {"--variant", {true, [](Options& o, const std::string& v) {
             if (v != "all" && v != "scene")
                 throw Error("--variant: expected 'all' or 'scene', found '" + v + "'");
             o.allFeatures = v == "all";
         }}},
        {"--threads", {true, [](Options& o, const std::string& v) { o.threads = parseInt("--threads", v, 1, 1024); }}},
        {"--shader-dir", {true, [](Options& o, const std::string& v) { o.shaderDirectory = v; }}},
        {"--eye", {true, [](Options& o, const std::string& v) { o.eye = parseVector("--eye", v); }}},
        {"--look", {true, [](Options& o, const std::string& v) { o.look = parseVector("--look", v); }}},
        {"--up", {true, [](Options& o, const std::string& v) { o.up = parseVector("--up", v); }}},
        {"--fov", {true, [](Options& o, const std::string& v) {
             o.fov = parseNumber("--fov", v);
             if (!(*o.fov > 0 && *o.fov < 180)) throw Error("--fov: must be between 0 and 180 degrees");
         }}},
        {"--dump-spirv", {true, [](Options& o, const std::string& v) { o.dumpSpirvDirectory = v; }}},
        {"--watch", {false, [](Options& o, const std::string&) { o.watch = true; }}},
        {"--quiet", {false, [](Options& o, const std::string&) { o.quiet = true; }}},
        {"--all", {false, [](Options& o, const std::string&) { o.everyVariant = true; }}},
        {"--precision", {true, [](Options& o, const std::string& v) {
             o.precision = parsePrecision("--precision", v);
             o.precisionGiven = true;
         }}},
        {"--out", {true, [](Options& o, const std::string& v) { o.outDirectory = v; }}},
        {"--frames", {true, [](Options& o, const std::string& v) { o.frames = parseInt("--frames", v, 1, 1000000); }}},
        {"--screenshot", {true, [](Options& o, const std::string& v) { o.screenshotPath = v; }}},
        {"--events", {true, [](Options& o, const std::string& v) { o.eventsPath = v; }}},
        {"--scenes", {true, [](Options& o, const std::string& v) { o.difftestScenes = parseInt("--scenes", v, 1, 100000000); }}},
        {"--cases", {true, [](Options& o, const std::string& v) { o.casesPattern = v; }}},
        {"--cases-dir", {true, [](Options& o, const std::string& v) { o.casesDirectory = v; }}},
        {"--diff", {true, [](Options& o, const std::string& v) { o.diffPath = v; }}},
        {"--fail", {true, [](Options& o, const std::string& v) {
             o.failThreshold = parseNumber("--fail", v);
             if (*o.failThreshold < 0) throw Error("--fail: must not be negative");
         }}},
        {"--failpercent", {true, [](Options& o, const std::string& v) {
             o.failPercent = parseNumber("--failpercent", v);
             if (*o.failPercent < 0 || *o.failPercent > 100) throw Error("--failpercent: must be between 0 and 100");
         }}},
    };
    return flags;
}

// -D NAME=VALUE (or -DNAME=VALUE; VALUE defaults to 1), as a C compiler takes it.
void parseDefine(const std::string& text, Options& o) {
    const size_t eq = text.find('=');
    const std::string name = text.substr(0, eq);
    const std::string value = eq == std::string::npos ? "1" : text.substr(eq + 1);
    const bool identifier =
        !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
        std::all_of(name.begin(), name.end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!identifier)
        throw Error("-D: '" + text + "' is not NAME=VALUE with NAME a C identifier");
    if (value.find_first_of("\n\r") != std::string::npos)
        throw Error("-D " + name + ": the value must be one line");
    o.defines.emplace_back(name, value);
}

// Which flags each command takes, besides render's full set.
bool accepts(Command command, const std::string& flag) {
    const bool numericsOnly = flag == "--out" || flag == "--cases" || flag == "--cases-dir";
    const bool viewOnly = flag == "--frames" || flag == "--screenshot" || flag == "--events";
    switch (command) {
    case Command::Render: return flag != "--all" && !numericsOnly && !viewOnly;
    case Command::View:
        return viewOnly || flag == "--size" || flag == "--device" || flag == "--spp" ||
               flag == "--seed" || flag == "--lenient" || flag == "--validation" ||
               flag == "--variant" || flag == "--threads" || flag == "--shader-dir" ||
               flag == "--eye" || flag == "--look" || flag == "--up" || flag == "--fov" ||
               flag == "-D" || flag == "--precision" || flag == "--fail";
    case Command::Pixel:
        if (viewOnly) return false;
        return flag != "-o" && flag != "--output" && flag != "--aov" && flag != "--cpu" &&
               flag != "--check" && flag != "--diff" && flag != "--fail" &&
               flag != "--failpercent" && flag != "--watch" && flag != "--threads" &&
               flag != "--all" && flag != "--spp" && flag != "--seed" && !numericsOnly;
    case Command::Stress:
        return flag == "--size" || flag == "--device" || flag == "--threads" ||
               flag == "--shader-dir" || flag == "--precision" || numericsOnly;
    case Command::Report:
        return flag == "--size" || flag == "--device" || flag == "--threads" ||
               flag == "--shader-dir" || flag == "--out" || flag == "--lenient" ||
               flag == "--precision" ||
               flag == "--eye" || flag == "--look" || flag == "--up" || flag == "--fov";
    case Command::Compare: return flag == "--diff" || flag == "--fail" || flag == "--failpercent";
    case Command::Difftest:
        return flag == "--scenes" || flag == "--seed" || flag == "--precision" || flag == "--out" ||
               flag == "--device" || flag == "--threads" || flag == "--shader-dir" ||
               flag == "--variant";
    case Command::ShadersCheck: return flag == "--shader-dir" || flag == "--all" || flag == "--precision";
    case Command::Features:
        return flag == "--lenient" || flag == "--variant" || flag == "--shader-dir" || flag == "-D" ||
               flag == "--spp" || flag == "--precision";
    default: return false;
    }
}

int parsePixelCoordinate(const char* what, const std::string& text) {
    return parseInt(std::string("pixel ") + what, text, 0, kMaxRenderSide - 1);
}

}  // namespace

std::string usageText() {
    return R"(usage:
  vkray render SCENE.sdl [-o out.png] [options]   render on the GPU (or --cpu)
  vkray pixel SCENE.sdl X Y [options]             trace one pixel on GPU and CPU, side by side
  vkray compare A B [--ids IDS_A IDS_B] [--diff FILE] [--fail T] [--failpercent P]
                                                  PNG, PFM, EXR or BMP; ids from .id.pfm or an
                                                  .exr's id channel (found beside A and B too)
  vkray stress [--cases PATTERN] [--size WxH] [--out DIR]   precision modes against the oracle
  vkray report SCENE.sdl [--size WxH] [--out DIR]          error against run time over the knobs
  vkray features SCENE.sdl [--variant all] [--spp N] [--precision MODE] [--lenient] [-D NAME=VALUE]
                                                  the scene's features, shader variant and buffers
  vkray difftest [--scenes N] [--seed S] [--precision MODE] [--out DIR]
                                                  random scenes on GPU and CPU, compared
  vkray view SCENE.sdl [options]                  a window that renders progressively and
                                                  reloads on change (docs/usage.md, "view")
  vkray devices                                   list Vulkan devices
  vkray shaders check [--all] [--precision MODE] [--shader-dir DIR]
                                                  compile the shader variants
  vkray --version | --help

render options:
  -o, --output FILE     image to write: .png (default: SCENE's name with .png), .pfm, or
                        .exr (linear float, unclamped)
  --size WxH            image size (default 640x480; each side <= 16384)
  --device N            Vulkan device index (see `vkray devices`)
  --block N             one ray per NxN block, the block filled with its colour
  --spp N               samples per pixel (1..4096, default 1): stratified, jittered
  --seed S              seed of the sample positions (0..4294967295, default 0)
  --aov PREFIX          also write PREFIX.depth.pfm, PREFIX.normal.pfm, PREFIX.id.pfm
  --aov NAME.exr        ... or one OpenEXR file: R,G,B  Z  N.X,N.Y,N.Z  id  P.X,P.Y,P.Z
  --cpu                 render with the CPU reference instead of the GPU
  --check               render with both and compare (exit 2 beyond tolerance)
  --diff FILE           with --check: write a diff image
  --fail T              with --check: per-pixel error threshold (idiff --fail)
  --failpercent P       with --check: percent of pixels allowed over T (idiff --failpercent)
  --lenient             skip unknown words and unsupported shapes, with warnings
  --eye X,Y,Z --look X,Y,Z --up X,Y,Z --fov DEG   override the scene's camera
  --threads N           CPU reference threads (default: all cores)
  --shader-dir DIR      GLSL folder (default: shaders/ next to the binary,
                        else ../share/vkray/shaders)
  --variant all|scene   compile every shape in, or only the scene's (default)
  --validation          enable the Khronos validation layer; any message fails
  --watch               re-render when the scene, a file it reads or a shader changes
  -D NAME=VALUE         define for the shader compile (repeatable)
  --dump-spirv DIR      write the SPIR-V of the variant used to DIR
  --quiet               no progress display on stderr
  --precision MODE      naive, robust (default) or fp64: float care on the GPU (docs/numerics.md);
                        for stress and report: only that mode (default: all)

Ctrl-C (SIGINT, SIGTERM) stops a render between tiles: nothing is written,
existing files stay as they were, exit status 130.

stress and report options:
  --out DIR             where the CSV, JSON and HTML go (default stress-report, report-SCENE)
  --cases PATTERN       stress: only the cases whose name contains PATTERN
  --cases-dir DIR       stress: the cases' folder (default scenes/stress next to the binary,
                        else ../share/vkray/stress)

view options (besides the camera, --size (default 960x540), --spp (default 16),
--seed, --device, --precision, --variant, -D, --shader-dir, --lenient, --threads, --validation):
  --fail T              the difference view's threshold (default 0.02, as --check's)
  --events FILE         replay input: `key p`, `drag left 100 0`, `wheel 3`, `wait-pass`,
                        `wait-cpu`, `wait-reload`, one a line
  --frames N            quit after N passes of the progression (after the events)
  --screenshot FILE     with --frames: save the last frame there, as the `s` key would
keys: mouse left orbits, right pans, wheel zooms; r resets the camera, p prints it;
  1 colour, 2 depth, 3 normal, 4 object id; c CPU reference, d GPU - CPU difference;
  s saves a PNG; q or Esc quits

difftest options:
  --scenes N            how many scenes to draw (default 100)
  --seed S              the first scene's seed (default 0): the same seeds draw the same scenes
  --precision MODE      draw scenes for this mode only (default: robust or fp64, drawn by seed;
                        naive, the textbook's float, disagrees by design and comes only on request)
  --variant all         render every scene with the all-features shader (faster for long runs:
                        lavapipe compiles it once; default: each scene's own variant)
  --out DIR             where the scenes that disagree are kept, each with its command
                        (default difftest)

exit status: 0 success, 1 error, 2 images differ beyond tolerance, 130 interrupted
)";
}

Options parseOptions(const std::vector<std::string>& args) {
    Options o;
    if (args.empty()) return o;
    const std::string& verb = args[0];
    if (verb == "--help" || verb == "-h" || verb == "help") return o;
    if (verb == "--version") {
        o.command = Command::Version;
        return o;
    }
    size_t first = 1;
    if (verb == "render") o.command = Command::Render;
    else if (verb == "pixel") o.command = Command::Pixel;
    else if (verb == "compare") o.command = Command::Compare;
    else if (verb == "devices") o.command = Command::Devices;
    else if (verb == "stress") o.command = Command::Stress;
    else if (verb == "report") o.command = Command::Report;
    else if (verb == "features") o.command = Command::Features;
    else if (verb == "difftest") o.command = Command::Difftest;
    else if (verb == "view") {
        o.command = Command::View;
        o.width = 960;
        o.height = 540;
        o.spp = 16;
    }
    else if (verb == "shaders" && args.size() > 1 && args[1] == "check") {
        o.command = Command::ShadersCheck;
        first = 2;
    } else if (verb == "shaders") throw Error("shaders: expected `vkray shaders check`");
    else throw Error("unknown command '" + verb + "'; try `vkray --help`");

    std::vector<std::string> positional;
    for (size_t i = first; i < args.size(); ++i) {
        std::string arg = args[i], value;
        // A lone '-' or a negative number is a positional argument.
        if (arg.size() < 2 || arg[0] != '-' || std::isdigit(static_cast<unsigned char>(arg[1]))) {
            positional.push_back(arg);
            continue;
        }
        if (arg.rfind("-D", 0) == 0 && accepts(o.command, "-D")) {
            if (arg.size() == 2 && i + 1 >= args.size()) throw Error("-D: expects NAME=VALUE");
            parseDefine(arg.size() > 2 ? arg.substr(2) : args[++i], o);
            continue;
        }
        if (size_t eq = arg.find('='); eq != std::string::npos && arg.rfind("--", 0) == 0) {
            value = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
        }
        if (o.command == Command::Compare && arg == "--ids") {
            if (i + 2 >= args.size())
                throw Error("--ids: expected two files, A.id.pfm B.id.pfm (or A.exr B.exr)");
            o.idsA = args[++i];
            o.idsB = args[++i];
            continue;
        }
        auto it = renderFlags().find(arg);
        if (it == renderFlags().end() || !accepts(o.command, arg))
            throw Error("unknown option '" + arg + "' for `vkray " + verb + "`; try `vkray --help`");
        if (it->second.takesValue && value.empty()) {
            if (i + 1 >= args.size()) throw Error(arg + ": expects a value");
            value = args[++i];
        }
        it->second.apply(o, value);
    }

    if (o.command == Command::Render) {
        if (positional.size() != 1)
            throw Error("render: expected one scene file, e.g. `vkray render scenes/default.sdl -o out.png`");
        o.scenePath = positional[0];
        if (o.cpu && o.check) throw Error("--cpu and --check: --check already renders with both");
        if (!o.diffPath.empty() && !o.check) throw Error("--diff needs --check (or use `vkray compare`)");
        if (o.failThreshold && !o.check) throw Error("--fail needs --check (or use `vkray compare`)");
        if (o.failPercent && !o.check) throw Error("--failpercent needs --check (or use `vkray compare`)");
        if (o.cpu && o.validation) throw Error("--validation applies to the GPU; drop --cpu");
        if (o.cpu && (!o.defines.empty() || !o.dumpSpirvDirectory.empty()))
            throw Error("-D and --dump-spirv apply to the GPU shader; drop --cpu");
        if (o.cpu && o.precisionGiven)
            throw Error("--precision applies to the GPU; --cpu always renders in double");
    } else if (o.command == Command::Pixel) {
        if (positional.size() != 3)
            throw Error("pixel: expected a scene file and a pixel, e.g. `vkray pixel scene.sdl 320 240`");
        o.scenePath = positional[0];
        o.pixelX = parsePixelCoordinate("X", positional[1]);
        o.pixelY = parsePixelCoordinate("Y", positional[2]);
        if (o.pixelX >= o.width || o.pixelY >= o.height)
            throw Error("pixel: (" + positional[1] + ", " + positional[2] + ") is outside the " +
                        std::to_string(o.width) + "x" + std::to_string(o.height) +
                        " image; pass --size or a smaller X Y");
    } else if (o.command == Command::View) {
        if (positional.size() != 1)
            throw Error("view: expected one scene file, e.g. `vkray view scenes/default.sdl`");
        o.scenePath = positional[0];
        if (!o.screenshotPath.empty() && o.frames == 0)
            throw Error("--screenshot needs --frames N: the pass after which it is taken");
        if (!o.screenshotPath.empty() && std::filesystem::path(o.screenshotPath).extension() != ".png")
            throw Error("--screenshot " + o.screenshotPath + ": the screenshot is a .png file");
    } else if (o.command == Command::Report) {
        if (positional.size() != 1)
            throw Error("report: expected one scene file, e.g. `vkray report scenes/default.sdl`");
        o.scenePath = positional[0];
    } else if (o.command == Command::Features) {
        if (positional.size() != 1)
            throw Error("features: expected one scene file, e.g. `vkray features scenes/default.sdl`");
        o.scenePath = positional[0];
    } else if (o.command == Command::Compare) {
        if (positional.size() != 2) throw Error("compare: expected two image files A B");
        o.imageA = positional[0];
        o.imageB = positional[1];
    } else if (!positional.empty()) {
        throw Error(verb + ": takes no arguments");
    }
    return o;
}

}  // namespace vkray
