// Jobs numbered 0..n-1 handed out across the ranks of an MPI job as the
// ranks ask for them: a rank asks again the moment it is done, so a faster
// or less busy rank simply does more. Rank 0 answers from a thread of its
// own and does jobs too. Tiles of a frame (distributed_render.h) and cases
// of `vkray stress` / settings of `vkray report` travel this way.
//
// The conversation, per worker: "ask" (the result of the job it just did, if
// any) and "give" (the next job and what the worker needs to know of it, or
// none), until there is none.
#pragma once

#include "dist/mpi_world.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace vkray::dist {

// Rank 0's side.
class JobHandOut {
public:
    // What a worker needs to know of a job beyond its number (may be empty).
    using Describe = std::function<std::string(std::size_t job)>;
    // A worker's result; called on the answering thread, one call at a time.
    using Receive = std::function<void(std::size_t job, int rank, std::string&& result)>;

    // Starts answering the other ranks at once.
    JobHandOut(const World& world, std::size_t jobs, Describe describe, Receive receive);
    // Unwinding from an error or Ctrl-C while a worker may still ask: the
    // thread stops calling describe and receive, and is left to the
    // caller's World::abort.
    ~JobHandOut();

    // Rank 0's own next job, or none.
    std::optional<std::size_t> take();
    // Waits until every worker has sent its last result and been told that
    // there is no more.
    void wait();
    // Time the answering thread spent receiving, finding the next job, replying.
    double answeringSeconds() const;

private:
    struct State;
    std::shared_ptr<State> state_;
    std::thread thread_;
};

// A worker's side: sends the result of the job just done (none at first),
// and receives the next job with its description, or none.
struct GivenJob {
    std::size_t index = 0;
    std::string description;
};
std::optional<GivenJob> askRankZero(const std::optional<std::pair<std::size_t, std::string>>& done);

// Rank 0's `bytes` on every rank (they replace the others' own).
void shareFromRankZero(const World& world, std::string& bytes);

// Every job run once, somewhere; on rank 0 the results in job order, on the
// others nothing. `run` may throw: the rank reports and ends the job.
std::vector<std::string> runJobsAcrossRanks(const World& world, std::size_t jobs,
                                            const std::function<std::string(std::size_t)>& run);

}  // namespace vkray::dist
