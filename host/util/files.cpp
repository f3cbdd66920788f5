#include "util/files.h"

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace vkray {

namespace {

std::string readFailure(const std::string& path, int errorNumber, std::uint64_t size,
                        std::uint64_t limit) {
    if (errorNumber != 0) return "cannot read " + path + ": " + std::strerror(errorNumber);
    if (size != 0)
        return "cannot read " + path + ": the file is " + std::to_string(size) +
               " bytes, above vkray's limit of " + std::to_string(limit);
    return "cannot read " + path + ": the file is larger than vkray's limit of " +
           std::to_string(limit) + " bytes";
}

struct FileCloser {
    int fd;
    ~FileCloser() { ::close(fd); }
};

std::string temporaryPathFor(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

[[noreturn]] void cannotWrite(const std::string& path, int error) {
    throw Error("cannot write " + path + ": " + std::strerror(error));
}

}  // namespace

FileReadError::FileReadError(const std::string& path, int errorNumber, std::uint64_t size,
                             std::uint64_t limit)
    : Error(readFailure(path, errorNumber, size, limit)), errorNumber_(errorNumber), size_(size) {}

std::string readFile(const std::string& path, std::uint64_t maxBytes) {
    const auto fail = [&](int error) { return FileReadError(path, error, 0, maxBytes); };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw fail(errno);
    const FileCloser closer{fd};  // on every exit, including the throws below
    struct stat info {};
    if (::fstat(fd, &info) != 0) throw fail(errno);
    if (S_ISDIR(info.st_mode)) throw fail(EISDIR);
    if (S_ISREG(info.st_mode) && std::uint64_t(info.st_size) > maxBytes)
        throw FileReadError(path, 0, std::uint64_t(info.st_size), maxBytes);
    std::string bytes;
    if (S_ISREG(info.st_mode)) bytes.reserve(size_t(info.st_size));
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw fail(errno);
        if (n == 0) break;
        if (bytes.size() + size_t(n) > maxBytes) throw FileReadError(path, 0, 0, maxBytes);
        bytes.append(buffer, size_t(n));
    }
    return bytes;
}

std::optional<std::string> readFileIfPresent(const std::string& path) {
    try {
        return readFile(path);
    } catch (const FileReadError&) {
        return std::nullopt;
    }
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    StagedFiles files;
    files.stage(path, bytes);
    files.commit();
}

StagedFiles::~StagedFiles() {
    for (const auto& file : staged_) ::unlink(file.first.c_str());
    release();
}

void StagedFiles::release() {
    if (holding_) ::pthread_sigmask(SIG_SETMASK, &previousMask_, nullptr);
    holding_ = false;
}

void StagedFiles::stage(const std::string& path, const std::string& bytes) {
    if (!holding_) {
        sigset_t stopSignals;
        sigemptyset(&stopSignals);
        for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stopSignals, signal);
        holding_ = ::pthread_sigmask(SIG_BLOCK, &stopSignals, &previousMask_) == 0;
    }
    // A folder in the way would fail only at commit(), after other files of
    // the set were renamed: refuse it now, while nothing has changed.
    struct stat destination {};
    if (::stat(path.c_str(), &destination) == 0 && S_ISDIR(destination.st_mode))
        cannotWrite(path, EISDIR);
    const std::string temporary = temporaryPathFor(path);
    // O_EXCL: never write through a stale temporary or a link someone left there.
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) cannotWrite(path, errno);
    staged_.emplace_back(temporary, path);  // from here on, the destructor removes it

    size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int error = errno;
            ::close(fd);
            cannotWrite(path, error);
        }
        written += size_t(n);
    }
    // fsync before rename: after a crash the destination is the old or the new
    // file, never a renamed but still empty one.
    if (::fsync(fd) != 0) {
        const int error = errno;
        ::close(fd);
        cannotWrite(path, error);
    }
    if (::close(fd) != 0) cannotWrite(path, errno);
}

void StagedFiles::commit() {
    // Renames within one folder: each is atomic, and none can run out of space.
    while (!staged_.empty()) {
        const auto& [temporary, path] = staged_.front();
        if (::rename(temporary.c_str(), path.c_str()) != 0) cannotWrite(path, errno);
        staged_.erase(staged_.begin());
    }
    release();
}

}  // namespace vkray
