#include "util/child_process.h"

#include "util/error.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>

namespace vkray {

namespace {

// The child's answer: one byte saying how `work` ended, the length of what
// follows (8 bytes), then its bytes or its error's message; the length lets
// the parent take them into one buffer, copied once.
constexpr char kReturned = 'r', kThrew = 't';
constexpr size_t kHeader = 1 + sizeof(std::uint64_t);

void writeAll(int fd, const char* data, size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;  // the parent is gone or stopped reading
        data += n;
        size -= size_t(n);
    }
}

[[noreturn]] void answerAndExit(int fd, char how, const std::string& bytes) {
    char header[kHeader];
    header[0] = how;
    const std::uint64_t length = bytes.size();
    std::memcpy(header + 1, &length, sizeof length);
    writeAll(fd, header, sizeof header);
    writeAll(fd, bytes.data(), bytes.size());
    ::close(fd);
    // _exit: no atexit handlers or static destructors of the parent's state
    // (its Vulkan device, MPI) run in the child.
    ::_exit(0);
}

std::string secondsText(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", seconds);
    return text;
}

}  // namespace

std::string runInChild(const std::function<std::string()>& work, double seconds,
                       const std::string& what) {
    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0)
        throw Error(what + ": cannot make a pipe: " + std::strerror(errno));
    const pid_t child = ::fork();
    if (child < 0) {
        const int error = errno;
        ::close(pipeFds[0]);
        ::close(pipeFds[1]);
        throw Error(what + ": cannot start a process: " + std::strerror(error));
    }
    if (child == 0) {
        ::close(pipeFds[0]);
        try {
            answerAndExit(pipeFds[1], kReturned, work());
        } catch (const std::exception& e) {
            answerAndExit(pipeFds[1], kThrew, e.what());
        } catch (...) {
            answerAndExit(pipeFds[1], kThrew, what + ": an unknown exception");
        }
    }
    ::close(pipeFds[1]);

    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    char header[kHeader];
    size_t headerRead = 0;
    std::string answer;
    size_t answerRead = 0;
    bool timedOut = false;
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            timedOut = true;
            break;
        }
        pollfd readable{pipeFds[0], POLLIN, 0};
        const int ready = ::poll(&readable, 1, int(std::min<long long>(left.count(), 1 << 30)));
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0) continue;  // the deadline is checked above
        const bool inHeader = headerRead < kHeader;
        char* into = inHeader ? header + headerRead : answer.data() + answerRead;
        const size_t room = inHeader ? kHeader - headerRead : answer.size() - answerRead;
        if (room == 0) break;  // all there; the child is ending
        const ssize_t n = ::read(pipeFds[0], into, room);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;  // the child closed its end: finished or died
        if (!inHeader) {
            answerRead += size_t(n);
            continue;
        }
        headerRead += size_t(n);
        if (headerRead == kHeader) {
            std::uint64_t length = 0;
            std::memcpy(&length, header + 1, sizeof length);
            answer.resize(length);
        }
    }
    ::close(pipeFds[0]);
    if (timedOut) ::kill(child, SIGKILL);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (timedOut)
        throw Error(what + " did not finish within " + secondsText(seconds) +
                    " s and was stopped; the file may be damaged or made to stall its reader");
    if (WIFSIGNALED(status))
        throw Error(what + " crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
                    ::strsignal(WTERMSIG(status)) + "); the file may be damaged");
    if (headerRead < kHeader || answerRead < answer.size() ||
        (header[0] != kReturned && header[0] != kThrew))
        throw Error(what + " ended without an answer (exit status " +
                    std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
    if (header[0] == kThrew) throw Error(answer);
    return answer;
}

}  // namespace vkray
