#include "bench/bench_options.h"

#include "util/error.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>

namespace vkray::bench {

namespace {

// WxH, each side 1 .. 16384.
void parseSize(const std::string& flag, const std::string& text, int& width, int& height) {
    const auto side = [&](const std::string& part, int& value) {
        auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
        return ec == std::errc() && end == part.data() + part.size() && value >= 1 &&
               value <= 16384;
    };
    const size_t x = text.find('x');
    if (x == std::string::npos || !side(text.substr(0, x), width) ||
        !side(text.substr(x + 1), height))
        throw Error(flag + ": expected WxH, each side 1 .. 16384, found '" + text + "'");
}

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ",") + name;
    return text;
}

}  // namespace

BenchOptions parseBenchOptions(const std::vector<std::string>& args, const BenchOptions& defaults,
                               const std::vector<std::string>& knownScenes) {
    BenchOptions o = defaults;
    CLI::App app{
        "vkray's benchmark harness: primary rays per second of the GPU tracer, the CPU "
        "reference and Embree on the same scenes (docs/benchmarks.md)",
        "vkray_bench"};
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    std::string names = joined(defaults.sceneNames);
    CLI::Option* scenes =
        app.add_option("--scenes", names, "the scenes to measure, from the list below")
            ->type_name("a,b,...");
    app.add_option("--scene", o.sceneFiles,
                   "an SDL scene file to measure too (repeatable; alone, "
                   "instead of the default list)")
        ->type_name("FILE.sdl")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--random", o.randomScenes,
                   "N scenes drawn by `vkray difftest`'s generator (inside the envelope), each "
                   "traced primary and shaded, with min / median / max of the ratios; alone, "
                   "instead of the default list")
        ->check(CLI::Range(1, 100000));
    app.add_option("--seed", o.seed,
                   "the random set's first seed, the others following it (default: a fresh "
                   "one, printed)")
        ->type_name("S");
    app.add_option_function<std::string>(
           "--size", [&o](const std::string& v) { parseSize("--size", v, o.width, o.height); },
           "image size (default 1920x1080)")
        ->type_name("WxH");
    app.add_option("--repeat", o.repeat, "timed runs per engine, the best kept (default 2)")
        ->check(CLI::Range(1, 100));
    app.add_option("--threads", o.threads, "CPU threads, and LP_NUM_THREADS when unset (default 2)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--tile", o.tile,
                   "the GPU tracer's tile side (default: the device's, 256 on a CPU such as "
                   "lavapipe, 1024 on a GPU)")
        ->check(CLI::Range(8, 16384));
    app.add_option("--shader-dir", o.shaderDirectory, "GLSL folder (default: the build's shaders/)")
        ->type_name("DIR");
    app.add_option_function<std::string>(
           "--all-size",
           [&o](const std::string& v) { parseSize("--all-size", v, o.allWidth, o.allHeight); },
           "the all-features variant's image size (default: --size)")
        ->type_name("WxH");
    bool noAll = false, noCpu = false, noEmbree = false, noFma = false, noRayQuery = false;
    app.add_flag("--no-all", noAll, "leave out the all-features variant");
    app.add_flag("--no-cpu", noCpu, "leave out the CPU reference");
    app.add_flag("--no-embree", noEmbree, "leave out Embree");
    app.add_flag("--no-ray-query", noRayQuery,
                 "leave out the GPU's ray-query traversal (--traversal rayquery; only where the "
                 "device has ray queries)");
    app.add_flag("--no-fma", noFma, "leave out the FMA peak");
    app.add_flag("--shaded", o.shaded,
                 "keep the scenes' lights and secondary rays (default: primary "
                 "rays only, the same rays for every engine)");
    app.add_flag("--experiments", o.experiments,
                 "add the tuning table: workgroup shapes, tile "
                 "sizes and order, an early-out");
    app.add_flag("--only-experiments", o.onlyExperiments, "the tuning table alone");
    app.add_option("--against", o.againstDirectory,
                   "the tuning table alone, as the shaders of DIR against --shader-dir's, their "
                   "runs interleaved in one process (an A/B test of a shader change)")
        ->type_name("DIR")
        ->check(CLI::ExistingDirectory);
    app.footer("scenes: " + joined(knownScenes) + "\ndefault list: " + joined(defaults.sceneNames));

    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them so
    try {
        app.parse(reversed);
    } catch (const CLI::CallForHelp&) {
        o.helpText = app.help();
        return o;
    } catch (const CLI::ParseError& e) {
        throw Error(e.what());
    }
    o.all = !noAll;
    o.cpu = !noCpu;
    o.embree = !noEmbree;
    o.rayQuery = !noRayQuery;
    o.fma = !noFma;
    o.onlyExperiments = o.onlyExperiments || !o.againstDirectory.empty();
    o.experiments = o.experiments || o.onlyExperiments;
    if (o.allWidth == 0) {
        o.allWidth = o.width;
        o.allHeight = o.height;
    }
    o.sceneNames.clear();
    if (scenes->count() == 0 && (!o.sceneFiles.empty() || o.randomScenes > 0)) names.clear();
    if (o.seed && o.randomScenes == 0)
        throw Error("--seed: the seed of --random's scenes; give --random N too");
    for (size_t start = 0; start <= names.size();) {
        size_t comma = std::min(names.find(',', start), names.size());
        const std::string name = names.substr(start, comma - start);
        start = comma + 1;
        if (name.empty()) continue;
        if (std::find(knownScenes.begin(), knownScenes.end(), name) == knownScenes.end())
            throw Error("--scenes: unknown scene '" + name +
                        "'; the scenes: " + joined(knownScenes));
        o.sceneNames.push_back(name);
    }
    return o;
}

}  // namespace vkray::bench
