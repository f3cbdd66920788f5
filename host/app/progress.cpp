#include "app/progress.h"

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace vkray {

namespace {

constexpr double kQuietStart = 1.0;      // seconds before anything is shown
constexpr double kLineInterval = 1.0;    // Lines: at most one a second
constexpr double kRedrawInterval = 0.1;  // Terminal: at most ten redraws a second
constexpr int kBarWidth = 20;

double steadySeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::string durationText(double seconds) {
    const long long s = std::llround(std::max(seconds, 0.0));
    char text[64];
    if (s < 60)
        std::snprintf(text, sizeof text, "%lld s", s);
    else if (s < 3600)
        std::snprintf(text, sizeof text, "%lld min %02lld s", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%lld h %02lld min", s / 3600, s / 60 % 60);
    return text;
}

ProgressDisplay::Style ProgressDisplay::styleForStderr(bool quiet) {
    if (quiet) return Style::Off;
    return ::isatty(STDERR_FILENO) ? Style::Terminal : Style::Lines;
}

ProgressDisplay::ProgressDisplay(std::ostream& out, Style style, std::string label, Clock clock)
    : out_(out),
      style_(style),
      label_(std::move(label)),
      clock_(clock ? std::move(clock) : steadySeconds) {}

ProgressDisplay::~ProgressDisplay() {
    // Left open by an error or an interruption: end the line so that the
    // message that follows starts on its own.
    if (shown_) out_ << "\n" << std::flush;
}

std::string ProgressDisplay::figures(std::size_t done, std::size_t total, double now) const {
    const double elapsed = now - start_;
    const double rate = elapsed > 0 ? double(done) / elapsed : 0;
    char text[96];
    std::snprintf(text, sizeof text, "%.2f Mrays/s, ", rate / 1e6);
    std::string result = text;
    if (done >= total) return result + "done in " + durationText(elapsed);
    double recentRate = rate;
    if (firstPieceTime_ >= 0 && done > firstPieceDone_ && now > firstPieceTime_)
        recentRate = double(done - firstPieceDone_) / (now - firstPieceTime_);
    return result +
           (recentRate > 0 ? durationText(double(total - done) / recentRate) : std::string("?")) +
           " left";
}

void ProgressDisplay::update(std::size_t done, std::size_t total) {
    if (style_ == Style::Off || total == 0) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    const double now = clock_();
    if (start_ < 0) start_ = now;
    // Workers report out of order; only progress forward counts.
    if (done < done_) return;
    done_ = done;
    total_ = total;
    if (firstPieceTime_ < 0 && done > 0) {
        firstPieceTime_ = now;
        firstPieceDone_ = done;
    }
    const double elapsed = now - start_;
    if (elapsed < kQuietStart) return;
    const int percent = int(100.0 * double(done) / double(total));
    if (style_ == Style::Lines) {
        if (percent / 10 <= lastDecile_ || (lastDecile_ >= 0 && now - lastShown_ < kLineInterval))
            return;
        lastDecile_ = percent / 10;
        lastShown_ = now;
        out_ << label_ << ": " << percent << "% (" << done << " of " << total << " rays), "
             << figures(done, total, now) << "\n"
             << std::flush;
        return;
    }
    if (shown_ && now - lastShown_ < kRedrawInterval && done < total) return;
    lastShown_ = now;
    shown_ = true;
    drawn_ = done;
    const int filled = int(double(kBarWidth) * double(done) / double(total));
    char head[64];
    std::snprintf(head, sizeof head, "%3d%% [", percent);
    // \r and "erase to the end of the line": the line is redrawn in place.
    out_ << "\r\x1b[K" << label_ << " " << head << std::string(size_t(filled), '#')
         << std::string(size_t(kBarWidth - filled), '-') << "] " << figures(done, total, now)
         << std::flush;
}

void ProgressDisplay::finish() {
    if (style_ != Style::Terminal) return;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!shown_) return;
        lastShown_ = -1e300;  // the next update redraws whatever the time
    }
    if (drawn_ != total_) update(total_, total_);
    const std::lock_guard<std::mutex> lock(mutex_);
    out_ << "\n" << std::flush;
    shown_ = false;
}

}  // namespace vkray
