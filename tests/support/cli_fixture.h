// The binary as a user runs it, for the CLI tests: run it with arguments,
// collect exit status and output, write scene files into a per-test folder.
#pragma once

#include "support/temp_folder.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#ifndef VKRAY_BINARY
#define VKRAY_BINARY "vkray"
#endif
#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray::test {

namespace fs = std::filesystem;

struct RunResult {
    int status;
    std::string output;  // stdout and stderr together
};

// Runs a shell command line, stderr with stdout.
inline RunResult runShell(const std::string& commandLine) {
    const std::string command = commandLine + " 2>&1";
    RunResult run{-1, ""};
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return run;
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        run.output.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

// Runs the binary with `args`; `environment` ("NAME=value ...") is set for it alone.
inline RunResult vkray(const std::string& args, const std::string& environment = "") {
    return runShell("env " + environment + " " + std::string(VKRAY_BINARY) + " " + args);
}

// The binary in a child process (--watch, a render to interrupt): stdout and
// stderr go to `log`, which the test reads while it runs. `environment`
// holds NAME=value entries set for the child alone.
class BackgroundVkray {
public:
    BackgroundVkray(const std::string& args, const fs::path& log,
                    const std::vector<std::string>& environment = {})
        : log_(log) {
        pid_ = ::fork();
        if (pid_ == 0) {
            const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            ::dup2(fd, 1);
            ::dup2(fd, 2);
            for (const std::string& entry : environment) ::putenv(const_cast<char*>(entry.c_str()));
            // The arguments hold no spaces (temporary paths), so split on them.
            std::vector<std::string> words{VKRAY_BINARY};
            std::istringstream in(args);
            for (std::string word; in >> word;) words.push_back(word);
            std::vector<char*> argv;
            for (std::string& word : words) argv.push_back(word.data());
            argv.push_back(nullptr);
            ::execv(argv[0], argv.data());
            ::_exit(127);
        }
    }
    ~BackgroundVkray() {
        if (pid_ > 0) stop(SIGKILL);
    }
    bool started() const { return pid_ > 0; }
    BackgroundVkray(const BackgroundVkray&) = delete;
    BackgroundVkray& operator=(const BackgroundVkray&) = delete;

    // Waits up to 60 s until `text` has appeared `count` times in the output.
    bool waitFor(const std::string& text, int count = 1) {
        for (int i = 0; i < 600; ++i) {
            if (occurrences(text) >= count) return true;
            if (exited()) return occurrences(text) >= count;
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        return false;
    }
    int occurrences(const std::string& text) const {
        const std::string all = output();
        int n = 0;
        for (size_t at = all.find(text); at != std::string::npos; at = all.find(text, at + 1)) ++n;
        return n;
    }
    std::string output() const {
        std::ifstream in(log_);
        return std::string((std::istreambuf_iterator<char>(in)), {});
    }
    // Sends `signal` (SIGINT is what Ctrl-C sends) and returns the exit
    // status, or -1 when the child did not exit on its own (a signal killed it).
    int stop(int signal = SIGINT) {
        if (!exited_ && pid_ > 0) {  // never kill(-1) or kill(0): only our child
            ::kill(pid_, signal);
            ::waitpid(pid_, &status_, 0);
            exited_ = true;
        }
        pid_ = -1;
        return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
    }
    // True once the child has exited (on its own or by a signal).
    bool exited() {
        if (pid_ <= 0) return true;  // fork failed
        if (!exited_ && ::waitpid(pid_, &status_, WNOHANG) == pid_) exited_ = true;
        return exited_;
    }

private:
    fs::path log_;
    pid_t pid_ = -1;
    bool exited_ = false;
    int status_ = 0;  // waitpid's, once exited_
};

class CliTest : public ::testing::Test {
protected:
    std::string scene(const std::string& name, const std::string& text) {
        fs::path p = dir / name;
        std::ofstream(p) << text;
        return p.string();
    }
    std::string path(const std::string& name) { return (dir / name).string(); }
    // Nothing but the scene files the test wrote is left in the folder.
    void expectNoOutputs() {
        for (const auto& entry : fs::directory_iterator(dir))
            EXPECT_EQ(entry.path().extension(), ".sdl") << "left behind: " << entry.path();
    }
    // A failed render: exit 1, the message holds `expected`, no output file.
    void expectRenderError(const std::string& sceneText, const std::string& expected,
                           const std::string& extra = "") {
        const std::string file = scene("bad.sdl", sceneText);
        RunResult run = vkray("render " + file + " -o " + path("out.png") + " --aov " +
                              path("aov") + " --size 32x24 " + extra);
        EXPECT_EQ(run.status, 1) << run.output;
        EXPECT_NE(run.output.find(expected), std::string::npos) << run.output;
        expectNoOutputs();
    }

private:
    TempFolder scratch_{"vkray-cli"};

protected:
    const fs::path dir = scratch_.path();
};

}  // namespace vkray::test
