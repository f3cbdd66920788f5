// The one thread pool: runs a body for every index of a range on several
// threads, the calling thread among them.
#pragma once

#include <cstddef>
#include <functional>
#include <stop_token>

namespace vkray {

// Threads to use for `requested` (0 or less: one per hardware thread, at least 1).
int threadCount(int requested);

// Calls body(i) for every i in [0, count), indices handed out in increasing
// order to up to threadCount(threads) threads (fewer when the system grants
// fewer; never more than count). Each index runs once, so a body whose
// effect depends only on its index gives the same result for any thread count.
//
// The first exception a body throws stops the hand-out; every worker finishes
// the index it holds, and the exception is rethrown here once all have
// stopped. A stop requested on `stop` also stops the hand-out; parallelFor
// then returns false (true: every index ran).
bool parallelFor(std::size_t count, const std::function<void(std::size_t)>& body, int threads = 0,
                 std::stop_token stop = {});

}  // namespace vkray
