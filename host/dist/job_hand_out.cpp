#include "dist/job_hand_out.h"

#include "util/error.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <mutex>

#if VKRAY_WITH_MPI
#include <mpi.h>
#endif

namespace vkray::dist {

std::vector<std::string> runJobsAcrossRanks(const World& world, std::size_t jobs,
                                            const std::function<std::string(std::size_t)>& run) {
    std::vector<std::string> results(world.rank() == 0 ? jobs : 0);
    if (!world.distributed()) {
        for (std::size_t job = 0; job < jobs; ++job) results[job] = run(job);
        return results;
    }
    if (world.rank() != 0) {
        std::optional<std::pair<std::size_t, std::string>> done;
        while (const std::optional<GivenJob> job = askRankZero(done))
            done.emplace(job->index, run(job->index));
        return results;
    }
    JobHandOut handOut(
        world, jobs, [](std::size_t) { return std::string(); },
        [&](std::size_t job, int, std::string&& result) { results[job] = std::move(result); });
    while (const std::optional<std::size_t> job = handOut.take()) results[*job] = run(*job);
    handOut.wait();
    return results;
}

#if VKRAY_WITH_MPI

namespace {

constexpr int kAsk = 1, kGive = 2;
constexpr std::int64_t kNone = -1;

// Open MPI's blocking calls spin on their core, which is the core the rank
// works on (mpirun binds each of a few ranks to its own): poll, and sleep
// between polls instead.
MPI_Status waitForMessage(int source, int tag) {
    MPI_Status status;
    for (auto pause = std::chrono::microseconds(20);;
         pause = std::min(pause * 2, std::chrono::microseconds(1000))) {
        int arrived = 0;
        MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
        if (arrived) return status;
        std::this_thread::sleep_for(pause);
    }
}

// A message: a job number (kNone: no job), then bytes.
void sendMessage(int rank, int tag, std::int64_t job, const std::string& bytes) {
    std::string message(sizeof job, '\0');
    std::memcpy(message.data(), &job, sizeof job);
    message += bytes;
    MPI_Send(message.data(), int(message.size()), MPI_BYTE, rank, tag, MPI_COMM_WORLD);
}

std::pair<std::int64_t, std::string> receiveMessage(const MPI_Status& status) {
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::string message(std::size_t(count), '\0');
    MPI_Recv(message.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    std::int64_t job = kNone;
    if (message.size() < sizeof job) return {kNone, {}};
    std::memcpy(&job, message.data(), sizeof job);
    return {job, message.substr(sizeof job)};
}

}  // namespace

struct JobHandOut::State {
    std::size_t jobs = 0;
    int workers = 0;
    Describe describe;
    Receive receive;
    std::mutex mutex;
    std::size_t nextJob = 0;
    bool abandoned = false;  // the owner is gone: call nothing of it any more
    double answeringSeconds = 0;

    std::optional<std::size_t> take() {
        const std::lock_guard lock(mutex);
        if (nextJob == jobs) return std::nullopt;
        return nextJob++;
    }

    void answerWorkers() {
        for (int working = workers; working > 0;) {
            const MPI_Status status = waitForMessage(MPI_ANY_SOURCE, kAsk);
            const Stopwatch answering;
            auto [done, result] = receiveMessage(status);
            std::optional<std::size_t> job;
            std::string description;
            {
                const std::lock_guard lock(mutex);
                if (abandoned) return;
                if (done >= 0 && std::size_t(done) < jobs)
                    receive(std::size_t(done), status.MPI_SOURCE, std::move(result));
                if (nextJob < jobs) {
                    job = nextJob++;
                    description = describe(*job);
                }
            }
            if (!job) --working;
            sendMessage(status.MPI_SOURCE, kGive, job ? std::int64_t(*job) : kNone, description);
            answeringSeconds += answering.seconds();
        }
    }
};

JobHandOut::JobHandOut(const World& world, std::size_t jobs, Describe describe, Receive receive)
    : state_(std::make_shared<State>()) {
    state_->jobs = jobs;
    state_->workers = world.size() - 1;
    state_->describe = std::move(describe);
    state_->receive = std::move(receive);
    thread_ = std::thread([state = state_] { state->answerWorkers(); });
}

JobHandOut::~JobHandOut() {
    if (!thread_.joinable()) return;
    const std::lock_guard lock(state_->mutex);
    state_->abandoned = true;
    thread_.detach();
}

std::optional<std::size_t> JobHandOut::take() {
    return state_->take();
}

void JobHandOut::wait() {
    thread_.join();
}

double JobHandOut::answeringSeconds() const {
    return state_->answeringSeconds;
}

void shareFromRankZero(const World& world, std::string& bytes) {
    if (!world.distributed()) return;
    std::uint64_t size = bytes.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    bytes.resize(size);
    // In pieces: MPI counts in int.
    constexpr std::uint64_t kPiece = 1u << 30;
    for (std::uint64_t at = 0; at < size; at += kPiece)
        MPI_Bcast(bytes.data() + at, int(std::min(kPiece, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
}

std::optional<GivenJob> askRankZero(
    const std::optional<std::pair<std::size_t, std::string>>& done) {
    sendMessage(0, kAsk, done ? std::int64_t(done->first) : kNone,
                done ? done->second : std::string());
    auto [job, description] = receiveMessage(waitForMessage(0, kGive));
    if (job < 0) return std::nullopt;
    return GivenJob{std::size_t(job), std::move(description)};
}

#else

struct JobHandOut::State {};

JobHandOut::JobHandOut(const World&, std::size_t, Describe, Receive) {
    throw Error("this vkray was built without MPI support");
}
JobHandOut::~JobHandOut() = default;
std::optional<std::size_t> JobHandOut::take() {
    return std::nullopt;
}
void JobHandOut::wait() {}
double JobHandOut::answeringSeconds() const {
    return 0;
}
std::optional<GivenJob> askRankZero(const std::optional<std::pair<std::size_t, std::string>>&) {
    throw Error("this vkray was built without MPI support");
}
void shareFromRankZero(const World&, std::string&) {}

#endif

}  // namespace vkray::dist
