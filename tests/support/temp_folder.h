// A test's scratch folder, its own: named after the test and its process, so
// two suites running at once (a build and its sanitizer build, two checkouts)
// never write into each other's files. Emptied when made; removed afterwards
// unless the test failed, so that a failure can be looked at.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <string>

namespace vkray::test {

class TempFolder {
public:
    explicit TempFolder(const std::string& prefix)
        : path_(std::filesystem::path(::testing::TempDir()) /
                (prefix + "-" + testName() + "-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempFolder() {
        std::error_code ignored;
        if (!::testing::Test::HasFailure()) std::filesystem::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }

private:
    static std::string testName() {
        const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
        return test ? test->name() : "none";
    }
    std::filesystem::path path_;
};

}  // namespace vkray::test
