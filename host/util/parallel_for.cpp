#include "util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace vkray {

int threadCount(int requested) {
    return requested > 0 ? requested : int(std::max(1u, std::thread::hardware_concurrency()));
}

bool parallelFor(std::size_t count, const std::function<void(std::size_t)>& body, int threads,
                 std::stop_token stop) {
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr failure;
    std::mutex failureMutex;
    const auto worker = [&] {
        try {
            while (!failed && !stop.stop_requested()) {
                const std::size_t i = next++;
                if (i >= count) return;
                body(i);
            }
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failureMutex);
            if (!failure) failure = std::current_exception();
            failed = true;
        }
    };
    const std::size_t wanted = std::min<std::size_t>(std::size_t(threadCount(threads)), count);
    std::vector<std::thread> pool;
    for (std::size_t i = 1; i < wanted; ++i) {
        try {
            pool.emplace_back(worker);
        } catch (const std::system_error&) {
            break;  // no more threads to be had: the ones there are finish the range
        }
    }
    worker();  // the calling thread works too
    for (std::thread& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
    return next >= count;
}

}  // namespace vkray
