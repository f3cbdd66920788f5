// Where the tests find the corpus of real SDL scenes (users' files that the
// repository does not hold): the folder named by the environment variable
// VKRAY_SDL_CORPUS, and nowhere else. The suite needs only the repository;
// tests that read the corpus skip when it is not there, and CI runs them in
// an extra stage with the variable set. Every such test has "Corpus" in its
// ctest name, so `ctest -R Corpus` selects exactly them.
//
// Nothing here may touch the file system before a test runs: test names
// (parameter lists included) must not depend on the corpus being present.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace vkray::test {

// The corpus folder as an absolute path without a trailing '/', or nullopt
// when VKRAY_SDL_CORPUS is unset, empty or not a folder.
inline std::optional<std::string> corpusDir() {
    const char* value = std::getenv("VKRAY_SDL_CORPUS");
    if (value == nullptr || *value == '\0') return std::nullopt;
    std::error_code error;
    if (!std::filesystem::is_directory(value, error)) return std::nullopt;
    std::filesystem::path folder = std::filesystem::absolute(value, error).lexically_normal();
    if (error) return std::nullopt;
    std::string path = folder.string();
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    return path;
}

// A file of the corpus; call only after VKRAY_NEED_CORPUS().
inline std::string corpusFile(const std::string& name) {
    return corpusDir().value_or("<VKRAY_SDL_CORPUS unset>") + "/" + name;
}

// Why the corpus is missing, for the skip message.
inline std::string corpusSkipReason() {
    const char* value = std::getenv("VKRAY_SDL_CORPUS");
    const std::string why = value == nullptr || *value == '\0'
                                ? std::string("VKRAY_SDL_CORPUS is not set")
                                : "VKRAY_SDL_CORPUS is not a folder: '" + std::string(value) + "'";
    return why + " (the sdl-corpus check is an extra CI stage)";
}

}  // namespace vkray::test

// In a test body: skip the test unless the corpus is there.
#define VKRAY_NEED_CORPUS()                                                                 \
    do {                                                                                    \
        if (!::vkray::test::corpusDir()) GTEST_SKIP() << ::vkray::test::corpusSkipReason(); \
    } while (false)
