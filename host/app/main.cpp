// The vkray binary: parses the command line, runs the command, and alone
// prints errors and chooses the exit status (0 success, 1 error, 2 images
// beyond tolerance, 130 interrupted). Library errors arrive as exceptions.
#include "app/commands.h"
#include "app/compare_command.h"
#include "app/devices_command.h"
#include "app/difftest_command.h"
#include "app/features_command.h"
#include "app/options.h"
#include "app/pixel_command.h"
#include "app/render_command.h"
#include "app/shaders_check_command.h"
#include "app/stress_command.h"
#include "app/view_command.h"
#include "dist/mpi_world.h"
#include "util/error.h"

#include <iostream>
#include <sstream>

namespace vkray {
namespace {

// The command itself, on this rank.
int runOnRank(const Options& o, std::ostream& out, std::ostream& err) {
    switch (o.command) {
    case Command::Help: out << o.helpText; return 0;
    case Command::Version: out << "vkray 0.1.0\nMPI: " << dist::World::support() << "\n"; return 0;
    case Command::Render: return runRender(o, out, err);
    case Command::Pixel: return runPixel(o, out, err);
    case Command::ShadersCheck: return runShadersCheck(o, out, err);
    case Command::Compare: return runCompare(o, out);
    case Command::Devices: return runDevices(out);
    case Command::Stress: return runStress(o, out, err);
    case Command::Difftest: return runDifftest(o, out, err);
    case Command::Report: return runReport(o, out, err);
    case Command::Features: return runFeatures(o, out, err);
    case Command::View: return runView(o, out, err);
    }
    return 1;
}

int runCommand(const Options& o, std::ostream& out, std::ostream& err) {
    const dist::World& world = dist::World::current();
    if (world.distributed()) {
        const bool spreads = o.command == Command::Render || o.command == Command::Stress ||
                             o.command == Command::Report;
        const bool trivial = o.command == Command::Version || o.command == Command::Help;
        if (!spreads && !trivial)
            throw ErrorOnEveryRank(
                "only `vkray render`, `vkray stress` and `vkray report` run across MPI "
                "ranks; run this command without mpirun");
        if (trivial && world.rank() != 0) return 0;  // rank 0 answers
        if (world.rank() != 0) {
            // Only rank 0 speaks; the others' errors still reach stderr.
            std::ostream quiet(nullptr);
            return runOnRank(o, quiet, quiet);
        }
    }
    return runOnRank(o, out, err);
}

}  // namespace
}  // namespace vkray

int main(int argc, char** argv) {
    using namespace vkray;
    int status = 1;
    std::string message;
    try {
        dist::World& world = dist::World::join(argc, argv);
        const Options options = [&] {
            try {
                return parseOptions(std::vector<std::string>(argv + 1, argv + argc));
            } catch (const Error& e) {
                throw ErrorOnEveryRank(e);  // every rank reads the same command line
            }
        }();
        status = runCommand(options, std::cout, std::cerr);
        world.finish();
        return status;
    } catch (const Interrupted&) {
        // Under mpirun the signal is as likely mpirun ending the job after
        // another rank failed (that rank has said why) as a Ctrl-C.
        message = dist::World::current().distributed()
                      ? "vkray: stopped by a signal (Ctrl-C, or mpirun ending the job because "
                        "another rank failed); nothing was written\n"
                      : "vkray: interrupted; nothing was written (existing files are as they "
                        "were)\n";
        status = 130;
    } catch (const ErrorOnEveryRank& e) {
        dist::World& world = dist::World::current();
        if (world.rank() == 0) printError(e, std::cerr);
        world.finish();
        return 1;
    } catch (const Error& e) {
        std::ostringstream text;
        printError(e, text);
        message = text.str();
    } catch (const std::bad_alloc&) {
        message = "vkray: error: out of memory; render a smaller image or scene\n";
    } catch (const std::exception& e) {
        // Vulkan errors (device lost, out of device memory) arrive here.
        message = std::string("vkray: error: ") + e.what() +
                  "\n  (a Vulkan or system failure; `vkray devices` shows the devices, "
                  "--cpu renders without Vulkan)\n";
    }
    // In an MPI job, a failing rank says which it is and ends every rank: the
    // others would otherwise wait for it for ever.
    const dist::World& world = dist::World::current();
    if (world.distributed()) {
        // One write: mpirun interleaves the ranks' output write by write.
        std::cerr << "[" + world.describeRank() + "] " + message << std::flush;
        world.abort(status);
    }
    std::cerr << message;
    return status;
}
