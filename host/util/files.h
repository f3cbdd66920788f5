// Whole files in and out: reading a file into memory, and writing files so
// that a failed or interrupted run never leaves a partial one (each write goes
// to a temporary file beside its destination, fsync'd, then renamed into place).
#pragma once

#include <csignal>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "util/error.h"

namespace vkray {

// A whole-file read that failed. what() is "cannot read PATH: REASON"; callers
// with a message format of their own build it from errorNumber() and size().
class FileReadError : public Error {
public:
    FileReadError(const std::string& path, int errorNumber, std::uint64_t size,
                  std::uint64_t limit);
    // errno (EISDIR for a folder), or 0 when the file is above the limit.
    int errorNumber() const { return errorNumber_; }
    // Above the limit: the file's size, or 0 when it grew past the limit while
    // being read (a pipe, a growing file).
    std::uint64_t size() const { return size_; }

private:
    int errorNumber_;
    std::uint64_t size_;
};

inline constexpr std::uint64_t kNoSizeLimit = std::numeric_limits<std::uint64_t>::max();

// The bytes of the file at `path`, at most `maxBytes` of them. Throws
// FileReadError.
std::string readFile(const std::string& path, std::uint64_t maxBytes = kNoSizeLimit);

// The same, or nothing when the file cannot be read (a cache entry, say).
std::optional<std::string> readFileIfPresent(const std::string& path);

// Writes `bytes` to `path` atomically (temporary file in the same folder,
// fsync, rename). Throws Error naming the path.
void writeFileAtomically(const std::string& path, const std::string& bytes);

// Files that appear together or not at all (an image, its AOVs, a diff):
// stage() writes each in full to a temporary file beside its destination
// (fsync'd), commit() renames them all into place. Destroyed before
// commit(), it removes its temporaries, so a failed or interrupted run
// leaves every destination as it was. From the first stage() to the end,
// SIGINT, SIGTERM and SIGHUP are held back in the calling thread, so that a
// single-threaded command is not killed with a temporary on disk (render
// installs handlers of its own, which every thread obeys).
class StagedFiles {
public:
    StagedFiles() = default;
    ~StagedFiles();
    StagedFiles(const StagedFiles&) = delete;
    StagedFiles& operator=(const StagedFiles&) = delete;

    void stage(const std::string& path, const std::string& bytes);  // throws Error naming path
    void commit();

private:
    void release();
    std::vector<std::pair<std::string, std::string>> staged_;  // temporary, destination
    bool holding_ = false;
    sigset_t previousMask_{};
};

}  // namespace vkray
