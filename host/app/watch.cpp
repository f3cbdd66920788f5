#include "app/watch.h"

#include "util/error.h"

#include <poll.h>
#include <sys/inotify.h>
#include <unistd.h>
#include <csignal>
#include <cstring>
#include <filesystem>

namespace vkray {

namespace fs = std::filesystem;

namespace {

volatile std::sig_atomic_t stopFlag = 0;
void onStopSignal(int) {
    stopFlag = 1;
}

using SignalHandler = void (*)(int);
SignalHandler previousInt = SIG_DFL, previousTerm = SIG_DFL;

}  // namespace

StopOnSignal::StopOnSignal() {
    stopFlag = 0;
    previousInt = std::signal(SIGINT, onStopSignal);
    previousTerm = std::signal(SIGTERM, onStopSignal);
}

StopOnSignal::~StopOnSignal() {
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
}

bool stopRequested() {
    return stopFlag != 0;
}

FileWatcher::FileWatcher() : fd_(::inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) {
    if (fd_ < 0)
        throw Error(std::string("--watch: cannot watch files (inotify: ") + std::strerror(errno) +
                    ")");
}

FileWatcher::~FileWatcher() {
    ::close(fd_);
}

void FileWatcher::addWatch(const std::string& folder, const std::string& name) {
    const int wd = ::inotify_add_watch(
        fd_, folder.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MODIFY);
    if (wd < 0) throw Error("--watch: cannot watch '" + folder + "': " + std::strerror(errno));
    names_[wd].insert(name);
}

void FileWatcher::watchFile(const std::string& path) {
    const fs::path p(path);
    const fs::path folder = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (fs::is_directory(folder)) addWatch(folder.string(), p.filename().string());
}

void FileWatcher::watchFolder(const std::string& folder) {
    addWatch(folder, "");
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_directory()) addWatch(entry.path().string(), "");
}

bool FileWatcher::readEvents() {
    alignas(inotify_event) char buffer[16 * 1024];
    bool changed = false;
    for (ssize_t n; (n = ::read(fd_, buffer, sizeof buffer)) > 0;) {
        for (ssize_t at = 0; at < n;) {
            const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
            const auto watched = names_.find(event->wd);
            if (event->mask & IN_Q_OVERFLOW) changed = true;  // events were lost: assume ours
            if (watched != names_.end() && event->len > 0)
                changed = changed || watched->second.count("") > 0 ||
                          watched->second.count(event->name) > 0;
            at += ssize_t(sizeof(inotify_event) + event->len);
        }
    }
    return changed;
}

bool FileWatcher::waitForChange() {
    bool changed = false;
    while (!stopRequested()) {
        pollfd p{fd_, POLLIN, 0};
        // Once a change is seen, wait out the burst an editor's save makes.
        const int ready = ::poll(&p, 1, changed ? 100 : 200);
        if (ready == 0 && changed) return true;
        if (ready <= 0) continue;  // timeout or EINTR: look at the stop flag again
        changed = readEvents() || changed;
    }
    return false;
}

bool FileWatcher::changed() {
    const auto now = std::chrono::steady_clock::now();
    if (readEvents()) lastChange_ = now;
    if (!lastChange_ || now - *lastChange_ < std::chrono::milliseconds(100)) return false;
    lastChange_.reset();
    return true;
}

}  // namespace vkray
