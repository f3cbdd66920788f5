#include "util/files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "support/temp_folder.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

// Each test gets its own empty folder, removed afterwards.
class Files : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return (dir / name).string(); }
    std::size_t fileCount() const {
        return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    }
    std::string readBytes(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    test::TempFolder scratch_{"vkray-files"};
    const fs::path dir = scratch_.path();
};

TEST_F(Files, AtomicWriteReplacesTheWholeFile) {
    writeFileAtomically(path("f.txt"), "a long old content");
    writeFileAtomically(path("f.txt"), "new");
    EXPECT_EQ(readBytes("f.txt"), "new");
    writeFileAtomically(path("empty.txt"), "");
    EXPECT_EQ(readBytes("empty.txt"), "");
    EXPECT_EQ(fileCount(), 2u);  // no temporaries left
}

TEST_F(Files, StagedFilesAppearOnlyOnCommit) {
    {
        StagedFiles files;
        files.stage(path("a.txt"), "a");
        files.stage(path("b.txt"), "b");
        EXPECT_FALSE(fs::exists(path("a.txt")));
        // Destroyed without commit(): neither the files nor their temporaries remain.
    }
    EXPECT_EQ(fileCount(), 0u);
    StagedFiles files;
    files.stage(path("a.txt"), "a");
    files.stage(path("b.txt"), "b");
    files.commit();
    EXPECT_EQ(readBytes("a.txt"), "a");
    EXPECT_EQ(readBytes("b.txt"), "b");
    EXPECT_EQ(fileCount(), 2u);
}

TEST_F(Files, StagingOntoAFolderIsRefusedBeforeAnythingChanges) {
    fs::create_directory(dir / "taken");
    StagedFiles files;
    EXPECT_EQ(errorOf([&] { files.stage(path("taken"), "x"); }),
              "cannot write " + path("taken") + ": Is a directory");
    EXPECT_EQ(fileCount(), 1u);
}

TEST_F(Files, ReadFileReturnsEveryByte) {
    const std::string bytes("a\0b\r\n\xff", 6);
    writeFileAtomically(path("f.bin"), bytes);
    EXPECT_EQ(readFile(path("f.bin")), bytes);
    EXPECT_EQ(readFileIfPresent(path("f.bin")), bytes);
}

TEST_F(Files, ReadFailuresNameThePathAndTheReason) {
    EXPECT_EQ(errorOf([&] { readFile(path("nope")); }),
              "cannot read " + path("nope") + ": No such file or directory");
    fs::create_directory(dir / "d");
    try {
        readFile(path("d"));
        ADD_FAILURE() << "a folder was read";
    } catch (const FileReadError& e) {
        EXPECT_EQ(e.errorNumber(), EISDIR);
        EXPECT_EQ(std::string(e.what()), "cannot read " + path("d") + ": Is a directory");
    }
    EXPECT_FALSE(readFileIfPresent(path("nope")).has_value());
}

TEST_F(Files, AFileAboveTheLimitIsRefusedWithItsSize) {
    writeFileAtomically(path("big"), std::string(10, 'x'));
    EXPECT_EQ(readFile(path("big"), 10), std::string(10, 'x'));
    try {
        readFile(path("big"), 9);
        ADD_FAILURE() << "the limit was not applied";
    } catch (const FileReadError& e) {
        EXPECT_EQ(e.errorNumber(), 0);
        EXPECT_EQ(e.size(), 10u);
        EXPECT_EQ(std::string(e.what()), "cannot read " + path("big") +
                                             ": the file is 10 bytes, above vkray's limit of 9");
    }
}

}  // namespace
}  // namespace vkray
