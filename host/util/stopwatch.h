// Wall-clock seconds since a start, on the steady clock (never jumps with the
// system time), and the process's CPU seconds.
#pragma once

#include <time.h>
#include <chrono>

namespace vkray {

class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::chrono::steady_clock::time_point start_;
};

// CPU seconds of the whole process, its worker threads (lavapipe's too)
// included: on a machine shared with other work it stays about the work done.
inline double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Wall-clock and process CPU seconds of one stretch of work: a stage's
// cost, told apart from the stages beside it.
struct Elapsed {
    double wall = 0, cpu = 0;
    Elapsed& operator+=(const Elapsed& other) {
        wall += other.wall;
        cpu += other.cpu;
        return *this;
    }
};

class StageClock {
public:
    Elapsed elapsed() const { return {wall_.seconds(), processCpuSeconds() - cpu_}; }

private:
    Stopwatch wall_;
    double cpu_ = processCpuSeconds();
};

}  // namespace vkray
