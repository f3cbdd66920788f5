// Work in a child process under a time limit: its bytes come back whole,
// its errors as they were thrown, and a child that stalls or crashes is an
// Error naming the work, never a hang of the caller.
#include "util/child_process.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

namespace vkray {
namespace {

std::string errorOf(const std::function<std::string()>& work, double seconds) {
    try {
        runInChild(work, seconds, "the work");
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no Error thrown";
    return "";
}

TEST(ChildProcess, ReturnsTheChildsBytesWhole) {
    // More than a pipe holds at once, and every byte value.
    std::string bytes(3 << 20, '\0');
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 7 + i / 4096);
    EXPECT_EQ(runInChild([&] { return bytes; }, 60, "the work"), bytes);
    EXPECT_EQ(runInChild([] { return std::string(); }, 60, "the work"), "");
}

TEST(ChildProcess, TheChildsErrorIsRethrownAsItWas) {
    EXPECT_EQ(errorOf([]() -> std::string { throw Error("f.obj: error: no triangles"); }, 60),
              "f.obj: error: no triangles");
}

TEST(ChildProcess, AChildThatNeverFinishesIsStoppedAtTheLimit) {
    const std::string error = errorOf(
        []() -> std::string {
            for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
        },
        0.2);
    EXPECT_EQ(error.find("the work did not finish within 0.2"), 0u) << error;
}

TEST(ChildProcess, AChildThatCrashesIsAnErrorWithItsSignal) {
    const std::string error = errorOf(
        []() -> std::string {
            std::abort();  // not a SIGSEGV: the sanitizers would catch that and exit 1
        },
        60);
    EXPECT_EQ(error.find("the work crashed (signal 6"), 0u) << error;
}

}  // namespace
}  // namespace vkray
