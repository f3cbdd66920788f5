#include "app/stress_command.h"

#include "app/commands.h"
#include "app/data_folder.h"
#include "dist/bytes.h"
#include "dist/job_hand_out.h"
#include "gpu/context.h"
#include "numerics/report_sweep.h"
#include "numerics/stress_pictures.h"
#include "numerics/stress_report.h"
#include "numerics/stress_suite.h"
#include "scene/scene_geometry.h"
#include "util/error.h"

#include <algorithm>
#include <filesystem>
#include <ostream>

namespace vkray {

namespace fs = std::filesystem;

namespace {

// --cases-dir, else scenes/stress next to the binary (where the build copies
// it, as it copies shaders/), else the installed share/vkray/stress
// (app/data_folder.h); the current folder does not matter.
std::string casesDirectory(const Options& o) {
    if (!o.casesDirectory.empty()) return o.casesDirectory;
    const DataFolder cases = findDataFolder("scenes/stress", "stress");
    if (cases.path.empty())
        throw Error("stress: cannot find the stress cases " + cases.whereLooked() +
                    "; pass --cases-dir DIR (the project's scenes/stress folder)");
    return cases.path;
}

std::string deviceText(const gpu::Context& context) {
    const gpu::DeviceInfo& d = context.device();
    return d.name + " (" + d.driverName + ")";
}

std::string commandLine(const Options& o, const std::string& verb) {
    std::string text = "vkray " + verb;
    if (!o.scenePath.empty()) text += " " + o.scenePath;
    text += " --size " + std::to_string(o.width) + "x" + std::to_string(o.height);
    if (!o.casesPattern.empty()) text += " --cases " + o.casesPattern;
    return text;
}

// ", 2 MPI ranks" when the work is spread over several.
std::string ranksText(const dist::World& world) {
    return world.distributed() ? ", " + std::to_string(world.size()) + " MPI ranks" : "";
}

// The output folder exists and is writable before any work starts.
void prepareOutDirectory(const std::string& directory) {
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec || !fs::is_directory(directory))
        throw Error("--out " + directory + ": cannot create the folder" +
                    (ec ? " (" + ec.message() + ")" : std::string()));
}

}  // namespace

int runStress(const Options& o, std::ostream& out, std::ostream& err) {
    const std::vector<numerics::StressCase> cases =
        numerics::findStressCases(casesDirectory(o), o.casesPattern);
    const std::string outDirectory = o.outDirectory.empty() ? "stress-report" : o.outDirectory;
    prepareOutDirectory(outDirectory);
    const dist::World& world = dist::World::current();
    gpu::Context context(gpu::ContextOptions{o.device, false, world.localRank()});
    const std::string device = deviceText(context);
    out << "stress: " << cases.size() << " cases, " << o.width << "x" << o.height << ", device "
        << device << ranksText(world) << "\n";
    numerics::StressOptions options;
    options.width = o.width;
    options.height = o.height;
    options.shaderDirectory = shaderDirectoryFor(o);
    options.threads = o.threads;
    if (o.precisionGiven) options.gpuModes = {o.precision};
    // Under mpirun the cases are handed out across the ranks; rank 0 reports.
    // Each case's result: its rows, then its pictures.
    const std::vector<std::string> results =
        dist::runJobsAcrossRanks(world, cases.size(), [&](std::size_t job) {
            numerics::StressPicture picture;
            const auto caseRows =
                numerics::runStressCase(cases[job], &context, options, &err, &picture);
            dist::ByteWriter writer;
            writer << numerics::encodeRows(caseRows) << numerics::encodePicture(picture);
            return writer.bytes();
        });
    if (world.rank() != 0) return 0;
    std::vector<numerics::ModeMetrics> rows;
    std::vector<numerics::StressPicture> pictures;
    for (const std::string& result : results) {
        dist::ByteReader reader(result);
        std::string rowBytes, pictureBytes;
        reader >> rowBytes >> pictureBytes;
        const std::vector<numerics::ModeMetrics> caseRows = numerics::decodeRows(rowBytes);
        rows.insert(rows.end(), caseRows.begin(), caseRows.end());
        pictures.push_back(numerics::decodePicture(pictureBytes));
    }
    numerics::Report report = numerics::stressReport(rows, cases, commandLine(o, "stress"), device);
    numerics::addStressPictures(report, pictures);
    out << numerics::formatTable(report.table);
    numerics::writeReportFiles(report, outDirectory, "stress", out);
    // Robust and double must pass every case; naive must fail those built to
    // break it. A row whose mode did not run is never as expected.
    int failures = 0, expected = 0, notRun = 0;
    for (const numerics::ModeMetrics& m : rows) {
        if (!m.ran) {
            ++notRun;
            continue;
        }
        const auto c =
            std::find_if(cases.begin(), cases.end(),
                         [&](const numerics::StressCase& sc) { return sc.name == m.caseName; });
        const bool expectPass = m.mode != "naive" || !c->naiveFails;
        if (numerics::withinBounds(m) == expectPass) {
            ++expected;
            continue;
        }
        ++failures;
        out << "unexpected: " << m.caseName << " " << m.mode
            << (expectPass ? " is beyond its bounds\n" : " passes a case built to break it\n");
    }
    for (const std::string& line : numerics::notRunSummary(rows, cases.size())) out << line << "\n";
    if (notRun > 0)
        out << "  a mode that did not run is not a pass: run on a device that has what it needs "
               "(`vkray devices`), or ask for the other modes with --precision MODE\n";
    out << "result: " << expected << " of " << rows.size() << " rows as expected"
        << (notRun ? " (" + std::to_string(notRun) + " not run)" : std::string())
        << (failures || notRun ? " (FAIL)\n" : " (PASS)\n");
    return failures || notRun ? 2 : 0;
}

int runReport(const Options& o, std::ostream& out, std::ostream& err) {
    std::vector<std::string> warnings;
    const Scene scene = loadScene(o.scenePath, {o.lenient}, &warnings);
    for (const std::string& w : warnings) err << w << "\n";
    Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    if (o.eye) camera.eye = *o.eye;
    if (o.look) camera.look = *o.look;
    if (o.up) camera.up = *o.up;
    if (o.fov) camera.fovDegrees = *o.fov;
    makeCameraBasis(camera, o.width, o.height);  // a bad camera fails before any render
    const std::string outDirectory =
        o.outDirectory.empty() ? "report-" + fs::path(o.scenePath).stem().string() : o.outDirectory;
    prepareOutDirectory(outDirectory);
    const dist::World& world = dist::World::current();
    gpu::Context context(gpu::ContextOptions{o.device, false, world.localRank()});
    const std::string device = deviceText(context);
    out << "report: " << o.scenePath << ", " << o.width << "x" << o.height << ", device " << device
        << ranksText(world) << "\n";
    numerics::SweepOptions options;
    options.width = o.width;
    options.height = o.height;
    options.shaderDirectory = shaderDirectoryFor(o);
    options.threads = o.threads;
    if (o.precisionGiven) options.precision = o.precision;
    const std::vector<numerics::SweepPoint> points =
        numerics::runSweep(scene, camera, context, options, &err);
    if (world.rank() != 0) return 0;  // rank 0 reports
    const numerics::Report report = numerics::sweepReport(o.scenePath, points, device);
    out << numerics::formatTable(report.table);
    numerics::writeReportFiles(report, outDirectory, "report", out);
    return 0;
}

}  // namespace vkray
