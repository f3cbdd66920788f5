// What a user meets when something is wrong, as the binary shows it: a scene
// beyond the device's limits, absurd numbers, a device that fails, Ctrl-C in
// the middle of a render. Each case: the message, the exit status, and the
// files left (none new; an existing output untouched).
#include "shaders/layout.h"
#include "support/cli_fixture.h"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using vkray::test::BackgroundVkray;
using vkray::test::RunResult;
using vkray::test::vkray;
using Reliability = vkray::test::CliTest;

const char* kGoodScene = "camera eye 0 0 5\nlight 5 5 5 1 1 1\nsphere\n";

// `count` spheres in a row: 128 bytes each on the GPU.
std::string spheres(int count) {
    std::ostringstream text;
    text << "camera eye 0 0 40\nlight 5 5 40 1 1 1\n";
    for (int i = 0; i < count; ++i)
        text << "push translate " << (i % 10) * 2 - 9 << " " << (i / 10) * 2 - 9
             << " 0 sphere pop\n";
    return text.str();
}

// Enough teapots (each a few thousand triangles) that a large image takes
// many seconds on lavapipe: time to interrupt it.
std::string teapots() {
    std::ostringstream text;
    text << "camera eye 0 2 30 look 0 0 0\nlight 10 20 30 1 1 1\n";
    for (int i = 0; i < 36; ++i)
        text << "push translate " << (i % 6) * 4 - 10 << " " << (i / 6) * 3 - 8 << " 0 rotate "
             << i * 10 << " 0 1 0 teapot pop\n";
    return text.str();
}

std::string readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The folder holds exactly `names` (no temporaries, nothing new).
void expectOnly(const fs::path& dir, std::set<std::string> names) {
    std::set<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir)) found.insert(entry.path().filename());
    EXPECT_EQ(found, names);
}

// ---- limits of the device ----------------------------------------------------

TEST_F(Reliability, ObjectsBeyondTheTexelBufferLimitAreRefusedBeforeAllocating) {
    // 100 objects of 4 texels (GpuObjectGeometry) are 400 texels; 256 allowed.
    const std::string s = scene("s.sdl", spheres(100));
    RunResult run =
        vkray("render " + s + " -o " + path("out.png") + " --size 32x24", "VKRAY_MAX_TEXELS=256");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("vkray: error: the scene's 100 objects need 400 texels in one "
                              "texel buffer; "),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("allows at most 256 (maxTexelBufferElements), room for 64 objects. "
                              "Use fewer objects, or render with --cpu"),
              std::string::npos)
        << run.output;
    expectNoOutputs();
    // The advice holds: the CPU reference has no such limit.
    RunResult cpu = vkray("render " + s + " --cpu -o " + path("out.png") + " --size 32x24",
                          "VKRAY_MAX_TEXELS=256");
    EXPECT_EQ(cpu.status, 0) << cpu.output;
}

TEST_F(Reliability, TrianglesBeyondTheTexelBufferLimitNameTheTriangles) {
    // The teapot: 16256 triangles of 6 texels (and 16325 BVH nodes of 2, which fit).
    const std::string s = scene("s.sdl", "camera eye 0 0 5\nlight 5 5 5 1 1 1\nteapot\n");
    RunResult run =
        vkray("render " + s + " -o " + path("out.png") + " --size 32x24", "VKRAY_MAX_TEXELS=60000");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("the scene's 16256 triangles need 97536 texels in one texel buffer"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("room for 10000 triangles. Use fewer or smaller meshes, or render "
                              "with --cpu"),
              std::string::npos)
        << run.output;
    expectNoOutputs();
}

TEST_F(Reliability, SmallBufferLimitShrinksTheTilesInstead) {
    // 8 KiB holds a 16x16 tile of 32-byte pixels (a lit sphere is traced in
    // one pass: no ray progress): more tiles, same image (the tiles whose
    // rays all miss the sphere take no dispatch).
    const std::string s = scene("s.sdl", kGoodScene);
    RunResult big = vkray("render " + s + " -o " + path("a.png") + " --size 40x30");
    RunResult small = vkray("render " + s + " -o " + path("b.png") + " --size 40x30",
                            "VKRAY_MAX_BUFFER_BYTES=8192");
    ASSERT_EQ(big.status, 0) << big.output;
    ASSERT_EQ(small.status, 0) << small.output;
    EXPECT_NE(big.output.find(", 1 tile in 1 dispatch,"), std::string::npos) << big.output;
    EXPECT_NE(small.output.find(", 6 tiles in "), std::string::npos) << small.output;
    EXPECT_EQ(readBytes(dir / "a.png"), readBytes(dir / "b.png"));
}

TEST_F(Reliability, MemoryBeyondTheDeviceHeapIsRefusedBeforeAllocating) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                          "VKRAY_DEVICE_MEMORY_BYTES=1000000");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_TRUE(std::regex_search(
        run.output,
        std::regex(
            R"(the scene needs about \d+ bytes \(\d\.\d MiB\) of device memory \((ray progress|tile pixels) 2097152 bytes \(2\.0 MiB\), (ray progress|tile pixels) 2097152 bytes \(2\.0 MiB\), )")))
        << run.output;
    EXPECT_NE(run.output.find("memory heap holds 1000000 bytes. Use fewer objects or smaller "
                              "meshes, or render with --cpu"),
              std::string::npos)
        << run.output;
    expectNoOutputs();
}

TEST_F(Reliability, BadLimitHookIsAnError) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                          "VKRAY_MAX_BUFFER_BYTES=lots");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("VKRAY_MAX_BUFFER_BYTES='lots' is not a whole number"),
              std::string::npos)
        << run.output;
}

// ---- numbers in scenes -------------------------------------------------------

TEST_F(Reliability, AbsurdNumbersAreRefusedAtTheirPlaceOnGpuAndCpu) {
    for (const char* renderer : {"", "--cpu"}) {
        expectRenderError("sphere\ntranslate 0 0 1e39\nsphere\n",
                          "bad.sdl:2:15: error: number '1e39' after 'translate' is beyond",
                          renderer);
        expectRenderError("sphere\nscale 1e-39 1 1\ncube\n",
                          "bad.sdl:2:1: error: 'scale' makes the inverse transform hold 1e+39",
                          renderer);
        expectRenderError("camera eye 1 1 1 look 1 1 1\nsphere\n",
                          "bad.sdl:1:1: error: camera: eye and look are the same point", renderer);
        expectRenderError("sphere\ncamera eye 0 9 0 up 0 -1 0\n",
                          "bad.sdl:2:1: error: camera: the up vector (0, -1, 0) is parallel",
                          renderer);
        expectRenderError("rotate 10 0 0 0\nsphere\n",
                          "bad.sdl:1:1: error: rotate axis 0 0 0 has no direction", renderer);
    }
    expectRenderError(kGoodScene, "camera: eye and look are the same point (0, 0, 0)",
                      "--eye 0,0,0 --look 0,0,0");
}

// ---- devices -----------------------------------------------------------------

TEST_F(Reliability, DeviceIndexOutOfRangeNamesTheDevices) {
    RunResult run =
        vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") + " --device 99");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("--device 99: there are only "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("`vkray devices` lists them"), std::string::npos) << run.output;
    expectNoOutputs();
}

TEST_F(Reliability, NoDeviceWithComputeSaysWhatToInstall) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                          "VKRAY_FAULT=no-compute");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("no Vulkan device with a compute queue"), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("mesa-vulkan-drivers"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("--cpu"), std::string::npos) << run.output;
    expectNoOutputs();
    RunResult chosen =
        vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") + " --device 0",
              "VKRAY_FAULT=no-compute");
    EXPECT_EQ(chosen.status, 1) << chosen.output;
    EXPECT_NE(chosen.output.find("--device 0 ("), std::string::npos) << chosen.output;
    EXPECT_NE(chosen.output.find("has no compute queue"), std::string::npos) << chosen.output;
}

// On every device (those with ray queries made to lack them): --traversal
// rayquery refused, naming the device and what to do, nothing written;
// auto takes the own walk and says why.
TEST_F(Reliability, RayQueriesOnADeviceWithoutThemAreRefused) {
    RunResult run = vkray(
        "render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") + " --traversal rayquery",
        "VKRAY_FAULT=no-ray-query");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("--traversal rayquery: the device 0 ("), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find(") has no ray queries (VK_KHR_ray_query"), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("render with --traversal own"), std::string::npos) << run.output;
    expectNoOutputs();
    RunResult automatic = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                                "VKRAY_FAULT=no-ray-query");
    EXPECT_EQ(automatic.status, 0) << automatic.output;
    EXPECT_NE(automatic.output.find("gpu render: traversal own walk (auto: the device 0 ("),
              std::string::npos)
        << automatic.output;
}

TEST_F(Reliability, RenderReportsTheDeviceTimeOrThatItWasNotMeasured) {
    RunResult timed = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"));
    EXPECT_EQ(timed.status, 0) << timed.output;
    EXPECT_NE(timed.output.find("gpu render: device time "), std::string::npos) << timed.output;
    EXPECT_NE(timed.output.find(" s (timestamp queries, "), std::string::npos) << timed.output;
    RunResult untimed = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                              "VKRAY_FAULT=no-timestamps");
    EXPECT_EQ(untimed.status, 0) << untimed.output;
    EXPECT_NE(untimed.output.find("gpu render: device time not measured (the device's queue has "
                                  "no timestamps)"),
              std::string::npos)
        << untimed.output;
}

TEST_F(Reliability, DeviceLostDuringTheRenderSuggestsCpuAndWritesNothing) {
    std::ofstream(dir / "out.png") << "the previous image";
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") +
                              " --aov " + path("aov") + " --size 600x300",
                          "VKRAY_FAULT=device-lost");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("vkray: error: the Vulkan device was lost during the render"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("VK_ERROR_DEVICE_LOST"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("nothing was written"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("render with --cpu"), std::string::npos) << run.output;
    EXPECT_EQ(readBytes(dir / "out.png"), "the previous image");
    expectOnly(dir, {"s.sdl", "out.png"});
}

TEST_F(Reliability, OutOfDeviceMemorySuggestsCpuAndWritesNothing) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                          "VKRAY_FAULT=out-of-device-memory");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("vkray: error: out of device memory during the render"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("render with --cpu"), std::string::npos) << run.output;
    expectNoOutputs();
}

TEST_F(Reliability, UnknownFaultIsAnError) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                          "VKRAY_FAULT=gremlins");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("VKRAY_FAULT='gremlins' is not a fault"), std::string::npos)
        << run.output;
}

// ---- output: whole files only ------------------------------------------------

TEST_F(Reliability, ExistingOutputIsReplacedOnlyByACompleteNewOne) {
    const std::string s = scene("s.sdl", kGoodScene);
    std::ofstream(dir / "out.png") << "the previous image";
    // One output of the set cannot be written (a folder is in its way): the
    // image, written first, must not replace the old one either.
    fs::create_directory(dir / "out.depth.pfm");
    RunResult failed =
        vkray("render " + s + " -o " + path("out.png") + " --aov " + path("out") + " --size 32x24");
    EXPECT_EQ(failed.status, 1) << failed.output;
    EXPECT_NE(failed.output.find("cannot write " + path("out.depth.pfm") + ": Is a directory"),
              std::string::npos)
        << failed.output;
    EXPECT_EQ(readBytes(dir / "out.png"), "the previous image");
    expectOnly(dir, {"s.sdl", "out.png", "out.depth.pfm"});

    fs::remove(dir / "out.depth.pfm");
    RunResult ok =
        vkray("render " + s + " -o " + path("out.png") + " --aov " + path("out") + " --size 32x24");
    ASSERT_EQ(ok.status, 0) << ok.output;
    // A whole PNG: it reads back.
    RunResult read = vkray("compare " + path("out.png") + " " + path("out.png"));
    EXPECT_EQ(read.status, 0) << read.output;
    expectOnly(dir, {"s.sdl", "out.png", "out.depth.pfm", "out.normal.pfm", "out.id.pfm"});
}

TEST_F(Reliability, SameSceneAndOptionsGiveTheSameBytesOnTheGpu) {
    const std::string s = scene("s.sdl", spheres(30) + "push translate 0 0 2 torus pop\n");
    for (const char* name : {"a", "b"}) {
        RunResult run = vkray("render " + s + " -o " + path(std::string(name) + ".png") +
                              " --aov " + path(name) + " --size 160x120");
        ASSERT_EQ(run.status, 0) << run.output;
    }
    for (const char* suffix : {".png", ".depth.pfm", ".normal.pfm", ".id.pfm"})
        EXPECT_EQ(readBytes(dir / (std::string("a") + suffix)),
                  readBytes(dir / (std::string("b") + suffix)))
            << suffix;
}

// ---- interruption and progress -----------------------------------------------

// A long render, stopped by `signal` once it is under way: exit 130,
// "interrupted", no temporary left, the existing output as it was.
void expectCleanInterruption(const fs::path& dir, const std::string& extra, int signal,
                             const std::string& progressLabel) {
    const fs::path scene = dir / "teapots.sdl";
    std::ofstream(scene) << teapots();
    std::ofstream(dir / "out.png") << "the previous image";
    // Paced (25 ms a progress report), so that it is still under way when
    // stopped however fast the machine.
    BackgroundVkray render("render " + scene.string() + " -o " + (dir / "out.png").string() +
                               " --aov " + (dir / "out").string() + " --size 3000x3000 " + extra,
                           dir / "log.txt", {"VKRAY_FAULT=slow-progress"});
    ASSERT_TRUE(render.started());
    // The first progress line comes a second into the render.
    ASSERT_TRUE(render.waitFor(progressLabel + ": ")) << render.output();
    EXPECT_EQ(render.stop(signal), 130) << render.output();
    const std::string output = render.output();
    EXPECT_NE(output.find("vkray: interrupted; nothing was written"), std::string::npos) << output;
    EXPECT_EQ(output.find("wrote "), std::string::npos) << output;
    EXPECT_EQ(readBytes(dir / "out.png"), "the previous image");
    expectOnly(dir, {"teapots.sdl", "out.png", "log.txt"});
}

TEST_F(Reliability, CtrlCStopsAGpuRenderBetweenTiles) {
    expectCleanInterruption(dir, "", SIGINT, "gpu render");
}

TEST_F(Reliability, SigtermStopsACpuRenderBetweenRows) {
    expectCleanInterruption(dir, "--cpu", SIGTERM, "cpu reference");
}

TEST_F(Reliability, ProgressLinesWhenStderrIsNotATerminal) {
    const fs::path scene = dir / "teapots.sdl";
    std::ofstream(scene) << teapots();
    // Paced: 144 tiles of at least 25 ms each, so at least two lines (one
    // a second at most) however fast the machine.
    BackgroundVkray render(
        "render " + scene.string() + " -o " + path("out.png") + " --size 3000x3000",
        dir / "log.txt", {"VKRAY_FAULT=slow-progress"});
    ASSERT_TRUE(render.waitFor("gpu render: ", 2)) << render.output();
    render.stop(SIGINT);
    // gpu render: 10% (900000 of 9000000 rays), 1.23 Mrays/s, 1 min 05 s left
    const std::regex line(R"(gpu render: (\d+)% \((\d+) of 9000000 rays\), \d+\.\d\d Mrays/s, )"
                          R"(((\d+ h )?(\d+ min )?\d+ s left))");
    std::istringstream lines(render.output());
    int progressLines = 0, lastDecile = -1;
    for (std::string text; std::getline(lines, text);) {
        if (text.rfind("gpu render: ", 0) != 0 || text.find("rays)") == std::string::npos) continue;
        std::smatch match;
        ASSERT_TRUE(std::regex_match(text, match, line)) << text;
        const int percent = std::stoi(match[1]);
        EXPECT_GT(percent / 10, lastDecile) << "one line per 10 % at most:\n" << text;
        lastDecile = percent / 10;
        ++progressLines;
    }
    EXPECT_GE(progressLines, 2) << render.output();
    EXPECT_EQ(render.output().find('\r'), std::string::npos) << "no terminal redraws in a log";
}

TEST_F(Reliability, QuietShowsNoProgress) {
    const fs::path scene = dir / "teapots.sdl";
    std::ofstream(scene) << teapots();
    BackgroundVkray render(
        "render " + scene.string() + " -o " + path("out.png") + " --size 1500x1500 --quiet",
        dir / "log.txt");
    ASSERT_TRUE(render.waitFor("scene: ")) << render.output();
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    render.stop(SIGINT);
    // A fast machine may finish within the wait and print its summary line
    // ("gpu render: 1.46 s, 36 tiles, ..."), which --quiet keeps; progress lines
    // ("gpu render: 40% (...)") and terminal redraws are what it must leave out.
    const std::regex progress(R"(gpu render:? +\d+%)");
    EXPECT_FALSE(std::regex_search(render.output(), progress)) << render.output();
    EXPECT_EQ(render.output().find('\r'), std::string::npos) << render.output();
}

}  // namespace
