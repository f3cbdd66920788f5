// The progress of a render, on stderr. On a terminal, one line redrawn in
// place (at most ten times a second):
//   gpu render  42% [########------------]  12.30 Mrays/s, 5 s left
// Elsewhere (a log file, a pipe), plain lines, at most one a second and one
// per 10 %:
//   gpu render: 40% (1677722 of 4194304 rays), 12.30 Mrays/s, 5 s left
// A render that ends within its first second shows nothing.
#pragma once

#include <cstddef>
#include <functional>
#include <mutex>
#include <ostream>
#include <string>

namespace vkray {

class ProgressDisplay {
public:
    enum class Style { Terminal, Lines, Off };
    using Clock = std::function<double()>;  // seconds since any fixed moment

    // Terminal when stderr is one, else Lines; Off with --quiet.
    static Style styleForStderr(bool quiet);

    // `clock` defaults to a steady clock; tests pass their own.
    ProgressDisplay(std::ostream& out, Style style, std::string label, Clock clock = nullptr);
    ~ProgressDisplay();  // ends a terminal line left open
    ProgressDisplay(const ProgressDisplay&) = delete;
    ProgressDisplay& operator=(const ProgressDisplay&) = delete;

    // `done` of `total` rays are traced. Thread-safe (the CPU reference's
    // workers call it).
    void update(std::size_t done, std::size_t total);
    // The render ended: a terminal line is drawn once more and ended.
    void finish();

private:
    std::string figures(std::size_t done, std::size_t total, double now) const;

    std::ostream& out_;
    Style style_;
    std::string label_;
    Clock clock_;
    std::mutex mutex_;
    double start_ = -1;  // the first update's time
    // The first piece of work done: the time left is estimated from the rate
    // after it, since the first piece also pays for start-up (lavapipe
    // compiles the shader at the first dispatch).
    double firstPieceTime_ = -1;
    std::size_t firstPieceDone_ = 0;
    double lastShown_ = 0;  // when the last line was drawn or printed
    int lastDecile_ = -1;   // Lines: the 10 % step of the last line printed
    bool shown_ = false;    // Terminal: a line is open
    std::size_t done_ = 0, total_ = 0;
    std::size_t drawn_ = 0;  // Terminal: the `done` the open line shows
};

// "5 s", "2 min 05 s", "1 h 02 min"
std::string durationText(double seconds);

}  // namespace vkray
