// A virtual X server for the tests of `vkray view`: Xvfb on a display number
// it picks itself (-displayfd), ready once it has written that number. When
// Xvfb is not installed or cannot start, there is none and why() says so:
// the tests skip with that message.
#pragma once

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>
#include <csignal>
#include <string>

namespace vkray::test {

class VirtualDisplay {
public:
    VirtualDisplay() {
        int fds[2];
        if (::pipe(fds) != 0) {
            why_ = "no pipe for Xvfb's display number";
            return;
        }
        pid_ = ::fork();
        if (pid_ == 0) {
            ::close(fds[0]);
            const std::string fd = std::to_string(fds[1]);
            ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1024x768x24",
                     "-nolisten", "tcp", static_cast<char*>(nullptr));
            ::_exit(127);
        }
        ::close(fds[1]);
        std::string number;
        // Xvfb writes the number once it accepts clients; EOF: it did not start.
        for (char c; number.find('\n') == std::string::npos;) {
            pollfd p{fds[0], POLLIN, 0};
            if (::poll(&p, 1, 60000) <= 0 || ::read(fds[0], &c, 1) != 1) break;
            number += c;
        }
        ::close(fds[0]);
        if (number.find('\n') == std::string::npos) {
            why_ = "no X server could start (Xvfb, from the xvfb package: scripts/install-deps.sh)";
            stop();
            return;
        }
        display_ = ":" + number.substr(0, number.find('\n'));
    }
    ~VirtualDisplay() { stop(); }
    VirtualDisplay(const VirtualDisplay&) = delete;
    VirtualDisplay& operator=(const VirtualDisplay&) = delete;

    bool ready() const { return !display_.empty(); }
    const std::string& display() const { return display_; }  // ":N"
    const std::string& why() const { return why_; }

private:
    void stop() {
        if (pid_ > 0) {  // only our own child
            ::kill(pid_, SIGTERM);
            ::waitpid(pid_, nullptr, 0);
        }
        pid_ = -1;
    }
    pid_t pid_ = -1;
    std::string display_, why_;
};

}  // namespace vkray::test
