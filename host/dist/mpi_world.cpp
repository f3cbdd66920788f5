#include "dist/mpi_world.h"

#include "util/error.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#if VKRAY_WITH_MPI
#include <mpi.h>
#endif

namespace vkray::dist {

namespace {

World* joined = nullptr;

// mpirun (Open MPI, MPICH, or any PMIx launcher) tells its processes so.
bool startedByMpirun() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
        if (std::getenv(name)) return true;
    return false;
}

// lavapipe starts one thread per core it can see. Ranks bound to their own
// cores (mpirun's default for a few ranks) use those; unbound ranks split
// the node's cores evenly, so that K ranks never start K x cores threads.
[[maybe_unused]] void shareCoresForLavapipe(int ranksOnNode) {
    if (std::getenv("LP_NUM_THREADS")) return;
    cpu_set_t mask;
    CPU_ZERO(&mask);
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    long threads = online;
    if (sched_getaffinity(0, sizeof mask, &mask) == 0 && CPU_COUNT(&mask) < online)
        threads = CPU_COUNT(&mask);
    else
        threads = online / std::max(ranksOnNode, 1);
    setenv("LP_NUM_THREADS", std::to_string(std::max(threads, 1L)).c_str(), 1);
}

}  // namespace

World& World::current() {
    static World one;
    return joined ? *joined : one;
}

std::string World::describeRank() const {
    return "rank " + std::to_string(rank_) + " on " + host_;
}

#if VKRAY_WITH_MPI

World& World::join(int& argc, char**& argv) {
    static World world;
    joined = &world;
    if (!startedByMpirun()) return world;
    // The rank that hands out tiles answers the others from a thread of its
    // own while its main thread renders.
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
    world.joined_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &world.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &world.size_);
    char name[MPI_MAX_PROCESSOR_NAME] = {};
    int length = 0;
    MPI_Get_processor_name(name, &length);
    world.host_.assign(name, size_t(length));
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, world.rank_, MPI_INFO_NULL, &node);
    int ranksOnNode = 1;
    MPI_Comm_rank(node, &world.localRank_);
    MPI_Comm_size(node, &ranksOnNode);
    MPI_Comm_free(&node);
    if (provided < MPI_THREAD_MULTIPLE && world.size_ > 1) {
        std::cerr << "vkray: error: " << world.describeRank()
                  << ": this MPI library does not allow calls from several threads "
                     "(MPI_THREAD_MULTIPLE), which vkray's tile hand-out needs\n";
        world.abort(1);
    }
    shareCoresForLavapipe(ranksOnNode);
    return world;
}

void World::abort(int exitCode) const {
    std::cerr.flush();
    if (joined_) MPI_Abort(MPI_COMM_WORLD, exitCode);
    std::exit(exitCode);
}

void World::finish() {
    if (!joined_) return;
    joined_ = false;
    // MPI_Finalize waits for every rank, spinning: ranks done early (while
    // rank 0 writes the image, or checks it on the CPU) would take its cores.
    // They wait here asleep instead.
    MPI_Request everyone;
    MPI_Ibarrier(MPI_COMM_WORLD, &everyone);
    for (int done = 0; !done;) {
        MPI_Test(&everyone, &done, MPI_STATUS_IGNORE);
        if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    MPI_Finalize();
}

std::string World::support() {
    char version[MPI_MAX_LIBRARY_VERSION_STRING] = {};
    int length = 0;
    MPI_Get_library_version(version, &length);
    std::string text(version, size_t(length));
    text = text.substr(0, text.find_first_of(",\n"));  // "Open MPI v4.1.4, package: ..."
    return "built in (" + text + ")";
}

#else

World& World::join(int&, char**&) {
    static World world;
    joined = &world;
    if (startedByMpirun())
        throw Error(
            "this vkray was built without MPI, but mpirun started it: every rank would "
            "render and write the whole image. Install libopenmpi-dev and rebuild "
            "(cmake -DVKRAY_MPI=ON), or run vkray without mpirun");
    return world;
}

void World::abort(int exitCode) const {
    std::cerr.flush();
    std::exit(exitCode);
}

void World::finish() {}

std::string World::support() {
    return "not built in (rebuild with libopenmpi-dev installed)";
}

#endif

}  // namespace vkray::dist
