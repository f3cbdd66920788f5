// The binary as a user runs it, for the CLI tests: run it with arguments,
// collect exit status and output, write scene files into a per-test folder.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>

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

// Runs the binary with `args`; `environment` ("NAME=value ...") is set for it alone.
inline RunResult vkray(const std::string& args, const std::string& environment = "") {
    const std::string command =
        "env " + environment + " " + std::string(VKRAY_BINARY) + " " + args + " 2>&1";
    RunResult run{-1, ""};
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return run;
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::path(::testing::TempDir()) /
              ("vkray-cli-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
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
        RunResult run = vkray("render " + file + " -o " + path("out.png") + " --aov " + path("aov") +
                        " --size 32x24 " + extra);
        EXPECT_EQ(run.status, 1) << run.output;
        EXPECT_NE(run.output.find(expected), std::string::npos) << run.output;
        expectNoOutputs();
    }
    fs::path dir;
};

}  // namespace vkray::test
