// `vkray render`, `vkray stress` and `vkray report` across MPI ranks: the
// image is the one-rank image, bit for bit, the reports hold what one rank's
// hold (timings aside), and a failing rank ends the run naming itself.
#include "support/cli_fixture.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace vkray::test {
namespace {

#ifndef VKRAY_MPIRUN
#define VKRAY_MPIRUN ""
#endif

std::string readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// mpirun as root (CI runs as root) with more ranks than cores allowed; a
// run that hangs is ended by `timeout` so that the test fails, not stalls.
RunResult mpirun(const std::string& ranksAndArgs) {
    return runShell(std::string("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ") +
                    "timeout 120 " + VKRAY_MPIRUN + " --oversubscribe " + ranksAndArgs);
}

class Mpi : public CliTest {
protected:
    void SetUp() override {
        if (std::string(VKRAY_MPIRUN).empty())
            GTEST_SKIP() << "built without MPI (cmake -DVKRAY_MPI=ON requires it)";
        CliTest::SetUp();
    }
    static std::string binary() { return VKRAY_BINARY; }
};

TEST_F(Mpi, VersionSaysMpiIsBuiltIn) {
    const RunResult run = vkray("--version");
    EXPECT_EQ(run.status, 0);
    EXPECT_NE(run.output.find("MPI: built in (Open MPI"), std::string::npos) << run.output;
    const RunResult ranks = mpirun("-np 2 " + binary() + " --version");
    EXPECT_EQ(ranks.status, 0) << ranks.output;
    EXPECT_EQ(ranks.output.find("MPI: built in"), ranks.output.rfind("MPI: built in"))
        << "rank 0 alone answers:\n"
        << ranks.output;
}

TEST_F(Mpi, TwoRanksRenderTheSameBytesAsOne) {
    // Every feature that draws random numbers or recurses: antialiasing,
    // shadows, reflection, refraction, textures.
    const std::string scene = std::string(VKRAY_SOURCE_DIR) + "/scenes/whitted.sdl";
    const std::string common = " --size 200x150 --spp 4 --seed 7 --quiet";
    const RunResult one =
        vkray("render " + scene + " -o " + path("one.png") + " --aov " + path("one") + common);
    ASSERT_EQ(one.status, 0) << one.output;
    const RunResult two = mpirun("-np 2 " + binary() + " render " + scene + " -o " +
                                 path("two.png") + " --aov " + path("two") + common);
    ASSERT_EQ(two.status, 0) << two.output;
    EXPECT_NE(two.output.find("on 2 MPI ranks"), std::string::npos) << two.output;
    // Only rank 0 speaks and writes.
    EXPECT_EQ(two.output.find("scene: "), two.output.rfind("scene: ")) << two.output;
    for (const char* suffix : {".png", ".depth.pfm", ".normal.pfm", ".id.pfm"}) {
        const std::string a = readBytes(path(std::string("one") + suffix));
        ASSERT_FALSE(a.empty()) << suffix;
        EXPECT_TRUE(a == readBytes(path(std::string("two") + suffix))) << suffix << " differs";
    }
}

// A CSV report without its "time s" column (the third in both reports).
std::string withoutTimes(const std::string& csv) {
    std::istringstream lines(csv);
    std::string kept;
    for (std::string line; std::getline(lines, line);) {
        const size_t second = line.find(',', line.find(',') + 1);
        const size_t third = line.find(',', second + 1);
        kept += line.substr(0, second) + line.substr(third) + "\n";
    }
    return kept;
}

TEST_F(Mpi, StressAndReportHoldWhatOneRankFinds) {
    const std::string cases = std::string(VKRAY_SOURCE_DIR) + "/scenes/stress";
    const std::string stress = " stress --size 40x30 --cases sphere --cases-dir " + cases;
    ASSERT_EQ(vkray(stress + " --out " + path("one")).status, 0);
    const RunResult two = mpirun("-np 2 " + binary() + stress + " --out " + path("two"));
    ASSERT_EQ(two.status, 0) << two.output;
    EXPECT_NE(two.output.find("2 MPI ranks"), std::string::npos) << two.output;
    const std::string oneCsv = readBytes(path("one/stress.csv"));
    EXPECT_GT(std::count(oneCsv.begin(), oneCsv.end(), '\n'), 8) << oneCsv;  // 5 cases x 4 modes
    EXPECT_EQ(withoutTimes(oneCsv), withoutTimes(readBytes(path("two/stress.csv"))));

    const std::string report = std::string(" report ") + VKRAY_SOURCE_DIR +
                               "/scenes/default.sdl --size 24x18 --precision robust";
    ASSERT_EQ(vkray(report + " --out " + path("r1")).status, 0);
    const RunResult twoReport = mpirun("-np 2 " + binary() + report + " --out " + path("r2"));
    ASSERT_EQ(twoReport.status, 0) << twoReport.output;
    const std::string oneReport = readBytes(path("r1/report.csv"));
    EXPECT_GT(std::count(oneReport.begin(), oneReport.end(), '\n'), 10) << oneReport;
    EXPECT_EQ(withoutTimes(oneReport), withoutTimes(readBytes(path("r2/report.csv"))));
}

TEST_F(Mpi, AFailingRankEndsTheRunNamingItselfAndWritesNothing) {
    // Rank 1 alone finds no compute device (the test hook of docs/reliability.md).
    const std::string scene = std::string(VKRAY_SOURCE_DIR) + "/scenes/default.sdl";
    const std::string render =
        binary() + " render " + scene + " -o " + path("out.png") + " --size 320x240 --quiet";
    const auto start = std::chrono::steady_clock::now();
    const RunResult run =
        mpirun("-np 1 " + render + " : -np 1 -x VKRAY_FAULT=no-compute " + render);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("[rank 1 on "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("no Vulkan device with a compute queue"), std::string::npos)
        << run.output;
    EXPECT_LT(seconds, 60) << "ended by the timeout, not by the failing rank:\n" << run.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
    expectNoOutputs();
}

TEST_F(Mpi, CommandsThatDoNotDistributeAreRefused) {
    const std::string scene = std::string(VKRAY_SOURCE_DIR) + "/scenes/default.sdl";
    const RunResult pixel = mpirun("-np 2 " + binary() + " pixel " + scene + " 10 10");
    EXPECT_EQ(pixel.status, 1) << pixel.output;
    EXPECT_NE(
        pixel.output.find("only `vkray render`, `vkray stress` and `vkray report` run across"),
        std::string::npos)
        << pixel.output;
    const RunResult cpu =
        mpirun("-np 2 " + binary() + " render " + scene + " -o " + path("out.png") + " --cpu");
    EXPECT_EQ(cpu.status, 1) << cpu.output;
    EXPECT_NE(cpu.output.find("--cpu renders in one process"), std::string::npos) << cpu.output;
    expectNoOutputs();
}

}  // namespace
}  // namespace vkray::test
