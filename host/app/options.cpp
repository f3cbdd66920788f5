#include "app/options.h"

#include "app/option_flags.h"
#include "util/error.h"

#include <CLI/CLI.hpp>

#include <cctype>
#include <filesystem>
#include <map>

namespace vkray {

namespace {

int parsePixelCoordinate(const char* what, const std::string& text) {
    return parseInt(std::string("pixel ") + what, text, 0, kMaxRenderSide - 1);
}

const char* const kShadersExpected = "shaders: expected `vkray shaders check`";

// A command's flags with their help lines, "" for the default one.
using FlagList = std::vector<std::pair<const char*, const char*>>;

const FlagList kCameraFlags = {{"--eye", ""}, {"--look", ""}, {"--up", ""}, {"--fov", ""}};

struct CommandSpec {
    const char* name;  // "shaders check": a subcommand of a subcommand
    Command command;
    const char* help;
    std::vector<const char*> positionals;  // their names, each a string
    const char* positionalError;           // too few or too many of them
    FlagList flags;
    const char* footer = "";
};

const char* const kModeOnlyHelp =
    "naive, robust or fp64: only that mode (default: all three; docs/numerics.md)";

const std::vector<CommandSpec>& commandSpecs() {
    static const std::vector<CommandSpec> specs = [] {
        std::vector<CommandSpec> s;
        FlagList render = {{"-o", ""},       {"--size", ""}, {"--device", ""},
                           {"--block", ""},  {"--spp", ""},  {"--seed", ""},
                           {"--aov", ""},    {"--cpu", ""},  {"--check", ""},
                           {"--diff", ""},   {"--fail", ""}, {"--failpercent", ""},
                           {"--lenient", ""}};
        render.insert(render.end(), kCameraFlags.begin(), kCameraFlags.end());
        render.insert(render.end(), {{"--threads", ""},
                                     {"--shader-dir", ""},
                                     {"--variant", ""},
                                     {"--validation", ""},
                                     {"--watch", ""},
                                     {"-D", ""},
                                     {"--dump-spirv", ""},
                                     {"--quiet", ""},
                                     {"--precision", ""},
                                     {"--traversal", ""}});
        s.push_back(
            {"render",
             Command::Render,
             "render a scene on the GPU (or --cpu)",
             {"SCENE"},
             "render: expected one scene file, e.g. `vkray render scenes/default.sdl -o out.png`",
             render,
             "Ctrl-C (SIGINT, SIGTERM) stops a render between tiles: nothing is written, "
             "existing files stay as they were, exit status 130.\n"
             "exit status: 0 success, 1 error, 2 images differ beyond tolerance, 130 interrupted"});

        FlagList pixel = {{"--size", ""}, {"--device", ""}, {"--block", ""},  {"--spp", ""},
                          {"--seed", ""}, {"--sample", ""}, {"--lenient", ""}};
        pixel.insert(pixel.end(), kCameraFlags.begin(), kCameraFlags.end());
        pixel.insert(pixel.end(), {{"--shader-dir", ""},
                                   {"--variant", ""},
                                   {"--validation", ""},
                                   {"-D", ""},
                                   {"--dump-spirv", ""},
                                   {"--quiet", ""},
                                   {"--precision", ""}});
        s.push_back(
            {"pixel",
             Command::Pixel,
             "trace one pixel on GPU and CPU, side by side",
             {"SCENE", "X", "Y"},
             "pixel: expected a scene file and a pixel, e.g. `vkray pixel scene.sdl 320 240`",
             pixel});

        s.push_back({"compare",
                     Command::Compare,
                     "compare two images: PNG, PFM, EXR or BMP; ids from .id.pfm or an .exr's id "
                     "channel (found beside A and B too)",
                     {"A", "B"},
                     "compare: expected two image files A B",
                     {{"--ids", ""},
                      {"--diff", "write a diff image"},
                      {"--fail", "per-pixel error threshold (idiff --fail)"},
                      {"--failpercent", "percent of pixels allowed over T (idiff --failpercent)"}},
                     "exit status: 0 within tolerance, 1 error, 2 images differ beyond tolerance"});

        s.push_back({"stress",
                     Command::Stress,
                     "precision modes against the oracle, on the stress cases",
                     {},
                     "stress: takes no arguments",
                     {{"--cases", ""},
                      {"--cases-dir", ""},
                      {"--size", ""},
                      {"--out", "where the CSV, JSON and HTML go (default stress-report)"},
                      {"--device", ""},
                      {"--threads", ""},
                      {"--shader-dir", ""},
                      {"--precision", kModeOnlyHelp}}});

        FlagList report = {{"--size", ""},
                           {"--out", "where the CSV, JSON and HTML go (default report-SCENE)"},
                           {"--lenient", ""}};
        report.insert(report.end(), kCameraFlags.begin(), kCameraFlags.end());
        report.insert(report.end(), {{"--device", ""},
                                     {"--threads", ""},
                                     {"--shader-dir", ""},
                                     {"--precision", kModeOnlyHelp}});
        s.push_back({"report",
                     Command::Report,
                     "error against run time over the knobs, for one scene",
                     {"SCENE"},
                     "report: expected one scene file, e.g. `vkray report scenes/default.sdl`",
                     report});

        s.push_back({"features",
                     Command::Features,
                     "the scene's features, shader variant and buffers",
                     {"SCENE"},
                     "features: expected one scene file, e.g. `vkray features scenes/default.sdl`",
                     {{"--variant", ""},
                      {"--spp", ""},
                      {"--precision", ""},
                      {"--traversal", ""},
                      {"--device", ""},
                      {"--lenient", ""},
                      {"-D", ""},
                      {"--shader-dir", ""}}});

        s.push_back(
            {"difftest",
             Command::Difftest,
             "random scenes on GPU and CPU, compared",
             {},
             "difftest: takes no arguments",
             {{"--scenes", ""},
              {"--seed", "the first scene's seed (default 0): the same seeds draw the same scenes"},
              {"--precision",
               "draw scenes for this mode only, inside its envelope (default: "
               "half the seeds open, past every envelope, in the mode auto "
               "chooses, the rest robust or fp64; naive, the textbook's float, "
               "disagrees by design and comes only on request)"},
              {"--variant",
               "all: render every scene with the all-features shader (faster "
               "for long runs: lavapipe compiles it once; default: each "
               "scene's own variant)"},
              {"--out",
               "where the scenes that disagree are kept, each with its command "
               "(default difftest)"},
              {"--traversal", ""},
              {"--device", ""},
              {"--threads", ""},
              {"--shader-dir", ""}}});

        FlagList view = {{"--size", "image size (default 960x540; each side <= 16384)"},
                         {"--spp", "samples per pixel of the progression (default 16)"},
                         {"--seed", ""}};
        view.insert(view.end(), kCameraFlags.begin(), kCameraFlags.end());
        view.insert(view.end(),
                    {{"--fail", "the difference view's threshold (default 0.02, as --check's)"},
                     {"--events", ""},
                     {"--frames", ""},
                     {"--screenshot", ""},
                     {"--device", ""},
                     {"--precision", ""},
                     {"--traversal", ""},
                     {"--variant", ""},
                     {"-D", ""},
                     {"--shader-dir", ""},
                     {"--lenient", ""},
                     {"--threads", ""},
                     {"--validation", ""}});
        s.push_back({"view",
                     Command::View,
                     "a window that renders progressively and reloads on change",
                     {"SCENE"},
                     "view: expected one scene file, e.g. `vkray view scenes/default.sdl`",
                     view,
                     "keys: mouse left orbits, right pans, wheel zooms; r resets the camera, p "
                     "prints it;\n  1 colour, 2 depth, 3 normal, 4 object id; c CPU reference, d "
                     "GPU - CPU difference;\n  s saves a PNG; q or Esc quits"});

        s.push_back({"devices",
                     Command::Devices,
                     "list Vulkan devices",
                     {},
                     "devices: takes no arguments",
                     {}});
        s.push_back({"shaders check",
                     Command::ShadersCheck,
                     "compile the shader variants",
                     {},
                     "shaders check: takes no arguments",
                     {{"--all", ""}, {"--precision", ""}, {"--shader-dir", ""}}});
        return s;
    }();
    return specs;
}

std::string positionalHelp(const std::string& name) {
    if (name == "SCENE") return "the scene file (.sdl)";
    if (name == "X") return "the pixel's column, 0 at the left";
    if (name == "Y") return "the pixel's row, 0 at the top";
    return "an image: .png, .pfm, .exr or .bmp";
}

// Messages for CLI11's `needs` and `excludes`, keyed by the two flags: the
// project's own words (tests and scripts read them).
std::string needsMessage(const std::string& flag, const std::string& needed) {
    if (needed == "--check") return flag + " needs --check (or use `vkray compare`)";
    if (flag == "--screenshot")
        return "--screenshot needs --frames N: the pass after which it is taken";
    return flag + " needs " + needed;
}

std::string excludesMessage(std::string a, std::string b) {
    if (a != "--cpu") std::swap(a, b);
    if (a == "--cpu") {
        if (b == "--check") return "--cpu and --check: --check already renders with both";
        if (b == "--validation") return "--validation applies to the GPU; drop --cpu";
        if (b == "-D" || b == "--dump-spirv")
            return "-D and --dump-spirv apply to the GPU shader; drop --cpu";
        if (b == "--precision")
            return "--precision applies to the GPU; --cpu always renders in double";
        if (b == "--traversal") return "--traversal applies to the GPU's walk; drop --cpu";
    }
    return a + " and " + b + " cannot be given together";
}

// The command line, as CLI11 sees it; binds into `o`.
struct Parser {
    CLI::App app{
        "vkray: a Vulkan compute-shader ray tracer for SDL scenes, checked against a "
        "double-precision CPU reference",
        "vkray"};
    std::map<const CLI::App*, const CommandSpec*> specs;
    std::map<const CommandSpec*, std::vector<std::string>> positionals;
    bool version = false;

    explicit Parser(Options& o) {
        app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
        app.require_subcommand(0, 1);
        app.add_flag("--version", version, "print the version and whether MPI is built in");
        app.get_formatter()->label("Subcommands", "Commands");
        app.get_formatter()->label("SUBCOMMAND", "COMMAND");
        app.footer(
            "`vkray COMMAND --help` lists the command's options (docs/usage.md has them "
            "all).\nexit status: 0 success, 1 error, 2 images differ beyond tolerance, "
            "130 interrupted");
        CLI::App* shaders = nullptr;
        for (const CommandSpec& spec : commandSpecs()) {
            CLI::App* sub = nullptr;
            const std::string name = spec.name;
            if (name.rfind("shaders ", 0) == 0) {
                if (!shaders) {
                    shaders = app.add_subcommand("shaders", "shader tools: `vkray shaders check`");
                    shaders->require_subcommand(0, 1);
                    specs[shaders] = &spec;
                }
                sub = shaders->add_subcommand(name.substr(8), spec.help);
            } else {
                sub = app.add_subcommand(name, spec.help);
            }
            specs[sub] = &spec;
            if (*spec.footer) sub->footer(spec.footer);
            std::vector<std::string>& values = positionals[&spec];
            values.resize(spec.positionals.size());
            for (size_t i = 0; i < spec.positionals.size(); ++i)
                sub->add_option(spec.positionals[i], values[i], positionalHelp(spec.positionals[i]))
                    ->type_name("")
                    ->required();
            for (const auto& [flag, help] : spec.flags) addFlag(*sub, o, flag, help);
            if (spec.command == Command::Render) {
                CLI::Option* cpu = sub->get_option("--cpu");
                for (const char* gpuOnly : {"--check", "--validation", "-D", "--dump-spirv",
                                            "--precision", "--traversal"})
                    cpu->excludes(sub->get_option(gpuOnly));
                for (const char* checkOnly : {"--diff", "--fail", "--failpercent"})
                    sub->get_option(checkOnly)->needs(sub->get_option("--check"));
            }
            if (spec.command == Command::View)
                sub->get_option("--screenshot")->needs(sub->get_option("--frames"));
        }
    }

    // The innermost command given, else the application itself.
    CLI::App* selected() {
        CLI::App* at = &app;
        while (!at->get_subcommands().empty()) at = at->get_subcommands().front();
        return at;
    }

    std::string commandLine(const CLI::App* sub) const {
        std::string line;
        for (; sub; sub = sub->get_parent())
            line = sub->get_name() + (line.empty() ? "" : " ") + line;
        return line;
    }

    // A CLI11 parse error in vkray's words, naming the flag or value.
    [[noreturn]] void fail(const CLI::ParseError& e) {
        const std::string what = e.what();
        CLI::App* sub = selected();
        const std::string verb = commandLine(sub);
        // What was left unparsed: an unknown flag is named first, whatever
        // else is wrong.
        std::string extra;
        for (CLI::App* at = sub; at && extra.empty(); at = at->get_parent())
            if (!at->remaining(false).empty()) extra = at->remaining(false).front();
        const bool isFlag = extra.size() > 1 && extra[0] == '-' &&
                            !std::isdigit(static_cast<unsigned char>(extra[1]));
        if (isFlag) {
            extra = extra.substr(0, extra.find('='));
            throw Error("unknown option '" + extra + "' for `" + verb + "`; try `" + verb +
                        " --help`");
        }
        if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
            if (sub == &app) throw Error("unknown command '" + extra + "'; try `vkray --help`");
            if (sub->get_name() == "shaders") throw Error(kShadersExpected);
            throw Error(specs.at(sub)->positionalError);
        }
        if (dynamic_cast<const CLI::RequiredError*>(&e) && sub != &app)
            throw Error(specs.at(sub)->positionalError);  // a positional is missing
        if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
            const std::string flag = what.substr(0, what.find(':'));
            if (flag == "--ids") throw Error(kIdsExpected);
            if (flag == "-D") throw Error("-D: expects NAME=VALUE");
            throw Error(flag + ": expects a value");
        }
        if (dynamic_cast<const CLI::RequiresError*>(&e)) {
            const size_t at = what.find(" requires ");
            throw Error(needsMessage(what.substr(0, at), what.substr(at + 10)));
        }
        if (dynamic_cast<const CLI::ExcludesError*>(&e)) {
            const size_t at = what.find(" excludes ");
            throw Error(excludesMessage(what.substr(0, at), what.substr(at + 10)));
        }
        throw Error(what);  // ValidationError: "--spp: 0 is out of range (1 .. 4096)"
    }
};

}  // namespace

std::string usageText() {
    Options unused;
    Parser parser(unused);
    return parser.app.help();
}

Options parseOptions(const std::vector<std::string>& args) {
    Options o;
    if (args.empty() || args[0] == "help") {
        o.helpText = usageText();
        return o;
    }
    Parser parser(o);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them so
    try {
        parser.app.parse(reversed);
    } catch (const CLI::CallForHelp&) {
        o.command = Command::Help;
        o.helpText = parser.app.help();
        return o;
    } catch (const CLI::CallForAllHelp&) {
        o.command = Command::Help;
        o.helpText = parser.app.help("", CLI::AppFormatMode::All);
        return o;
    } catch (const CLI::ParseError& e) {
        parser.fail(e);
    }

    CLI::App* sub = parser.selected();
    if (sub == &parser.app) {
        if (parser.version)
            o.command = Command::Version;
        else
            o.helpText = usageText();
        return o;
    }
    const CommandSpec& spec = *parser.specs.at(sub);
    if (sub->get_name() == "shaders") throw Error(kShadersExpected);  // without `check`
    o.command = spec.command;
    const std::vector<std::string>& positional = parser.positionals.at(&spec);

    if (o.command == Command::View) {
        if (sub->get_option("--size")->count() == 0) {
            o.width = 960;
            o.height = 540;
        }
        if (sub->get_option("--spp")->count() == 0) o.spp = 16;
        if (!o.screenshotPath.empty() &&
            std::filesystem::path(o.screenshotPath).extension() != ".png")
            throw Error("--screenshot " + o.screenshotPath + ": the screenshot is a .png file");
    }
    if (o.command == Command::Compare) {
        o.imageA = positional[0];
        o.imageB = positional[1];
    } else if (!positional.empty()) {
        o.scenePath = positional[0];
    }
    if (o.command == Command::Pixel) {
        o.pixelX = parsePixelCoordinate("X", positional[1]);
        o.pixelY = parsePixelCoordinate("Y", positional[2]);
        if (o.pixelX >= o.width || o.pixelY >= o.height)
            throw Error("pixel: (" + positional[1] + ", " + positional[2] + ") is outside the " +
                        std::to_string(o.width) + "x" + std::to_string(o.height) +
                        " image; pass --size or a smaller X Y");
        if (o.pixelSample >= o.spp)
            throw Error("pixel: --sample " + std::to_string(o.pixelSample) + " is not one of the " +
                        std::to_string(o.spp) + " samples of --spp " + std::to_string(o.spp) +
                        " (0 to " + std::to_string(o.spp - 1) +
                        "); pass a smaller --sample or a larger --spp");
    }
    return o;
}

}  // namespace vkray
