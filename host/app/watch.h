// `render --watch`: waiting for a file to change (inotify), and stopping
// cleanly on Ctrl-C.
#pragma once

#include <map>
#include <set>
#include <string>

namespace vkray {

// While one exists, SIGINT, SIGTERM and SIGHUP only set a flag
// (stopRequested()): a render stops between tiles or rows and writes
// nothing, --watch stops waiting; either way no partial file is left.
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

private:
    void addWatch(const std::string& folder, const std::string& name);
    int fd_ = -1;
    std::map<int, std::set<std::string>> names_;  // watch -> names; "" = any
};

}  // namespace vkray
