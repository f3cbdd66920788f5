// The MPI job this process belongs to, if any. vkray joins MPI only when
// mpirun started it (a plain run pays nothing and needs no MPI at all); a
// binary built without MPI refuses to run under mpirun rather than have every
// rank write the same file.
#pragma once

#include <string>

namespace vkray::dist {

class World {
public:
    // Joins the job when mpirun started this process; a world of one
    // otherwise. Also shares the node's cores out among its ranks for
    // lavapipe (LP_NUM_THREADS, unless set). Call once, before any thread.
    static World& join(int& argc, char**& argv);
    // The world joined, or a world of one before join().
    static World& current();

    int rank() const { return rank_; }
    int size() const { return size_; }
    int localRank() const { return localRank_; }  // index among the ranks on this node
    bool distributed() const { return size_ > 1; }
    const std::string& host() const { return host_; }
    // "rank 1 on node7": how messages name a rank.
    std::string describeRank() const;

    // Ends every rank of the job now with `exitCode` (after this rank has
    // printed why); a world of one just exits.
    [[noreturn]] void abort(int exitCode) const;
    // Leaves the job (MPI_Finalize) after a normal end; safe to call twice.
    void finish();

    // "built in (Open MPI v4.1.4)" or "not built in".
    static std::string support();

private:
    World() = default;
    int rank_ = 0, size_ = 1, localRank_ = 0;
    std::string host_ = "this host";
    bool joined_ = false;
};

}  // namespace vkray::dist
