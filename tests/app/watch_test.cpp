// FileWatcher: what counts as a change of a watched file, and that a change
// made after watching began is kept until it is asked for, however late.
#include "app/watch.h"

#include "support/temp_folder.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace vkray {
namespace {

namespace fs = std::filesystem;

// Asks changed() until it says yes, for at most 10 s: a change settles
// 100 ms after its last event.
bool changeSeen(FileWatcher& watcher) {
    for (int i = 0; i < 500; ++i) {
        if (watcher.changed()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

// As an editor saves: written beside, renamed over.
void saveByRename(const fs::path& file, const std::string& text) {
    std::ofstream(file.string() + ".new") << text;
    fs::rename(file.string() + ".new", file);
}

TEST(FileWatcher, AChangeMadeBeforeItIsAskedForIsKept) {
    const test::TempFolder scratch("vkray-watch");
    const fs::path scene = scratch.path() / "s.sdl";
    std::ofstream(scene) << "sphere\n";
    FileWatcher watcher;
    watcher.watchFile(scene.string());
    // The save comes while the caller is busy (a render): nothing asks yet.
    saveByRename(scene, "cube\n");
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    EXPECT_TRUE(changeSeen(watcher));
    // In place, as some editors write.
    std::ofstream(scene, std::ios::app) << "sphere\n";
    EXPECT_TRUE(changeSeen(watcher));
}

TEST(FileWatcher, WatchingMoreFilesOfAFolderKeepsTheFirst) {
    const test::TempFolder scratch("vkray-watch");
    const fs::path scene = scratch.path() / "s.sdl", mesh = scratch.path() / "m.3vn";
    std::ofstream(scene) << "sphere\n";
    std::ofstream(mesh) << "";
    FileWatcher watcher;
    watcher.watchFile(scene.string());
    watcher.watchFile(mesh.string());  // the same folder, watched again
    saveByRename(scene, "cube\n");
    EXPECT_TRUE(changeSeen(watcher));
    saveByRename(mesh, "3\n");
    EXPECT_TRUE(changeSeen(watcher));
}

TEST(FileWatcher, OtherFilesOfTheFolderAreNotAChange) {
    const test::TempFolder scratch("vkray-watch");
    const fs::path scene = scratch.path() / "s.sdl";
    std::ofstream(scene) << "sphere\n";
    FileWatcher watcher;
    watcher.watchFile(scene.string());
    std::ofstream(scratch.path() / "out.png") << "image";
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    EXPECT_FALSE(watcher.changed());
    saveByRename(scene, "cube\n");  // ... while the scene is
    EXPECT_TRUE(changeSeen(watcher));
}

TEST(FileWatcher, AnyFileBelowAWatchedFolderIsAChange) {
    const test::TempFolder scratch("vkray-watch");
    fs::create_directories(scratch.path() / "shapes");
    std::ofstream(scratch.path() / "shapes" / "plane.glsl") << "// plane\n";
    FileWatcher watcher;
    watcher.watchFolder(scratch.path().string());
    saveByRename(scratch.path() / "shapes" / "plane.glsl", "// edited\n");
    EXPECT_TRUE(changeSeen(watcher));
    EXPECT_FALSE(watcher.changed());  // one change, reported once
}

}  // namespace
}  // namespace vkray
