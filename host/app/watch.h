// `render --watch`: waiting for a file to change (inotify), and stopping
// cleanly on Ctrl-C.
#pragma once

#include <chrono>
#include <map>
#include <optional>
#include <set>
#include <string>

namespace vkray {

// While one exists, SIGINT and SIGTERM only set a flag (stopRequested()), so
// the current render finishes and writes whole files before vkray exits.
class StopOnSignal {
public:
    StopOnSignal();
    ~StopOnSignal();
    StopOnSignal(const StopOnSignal&) = delete;
    StopOnSignal& operator=(const StopOnSignal&) = delete;
};
bool stopRequested();

// Watches folders rather than files: editors often save by writing a new
// file and renaming it over the old one, which a watch on the file misses.
class FileWatcher {
public:
    FileWatcher();  // throws Error when inotify is not available
    ~FileWatcher();
    FileWatcher(const FileWatcher&) = delete;
    FileWatcher& operator=(const FileWatcher&) = delete;

    void watchFile(const std::string& path);      // a change to this file
    void watchFolder(const std::string& folder);  // any file in it or below

    // Blocks until a watched file changes (true) or a stop is requested
    // (false). Changes that follow within 100 ms count as the same one.
    bool waitForChange();

    // Without waiting (`vkray view` between tiles): true once a watched file
    // has changed and 100 ms have passed without another change.
    bool changed();

private:
    void addWatch(const std::string& folder, const std::string& name);
    // Reads the events there are; true when one is about a watched file.
    bool readEvents();
    std::optional<std::chrono::steady_clock::time_point> lastChange_;
    int fd_ = -1;
    std::map<int, std::set<std::string>> names_;  // watch -> names; "" = any
};

}  // namespace vkray
