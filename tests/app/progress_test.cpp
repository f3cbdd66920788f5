// The progress display on a made-up clock: what it prints, and when.
#include "app/progress.h"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace vkray {
namespace {

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

TEST(Progress, DurationText) {
    EXPECT_EQ(durationText(0.4), "0 s");
    EXPECT_EQ(durationText(59.4), "59 s");
    EXPECT_EQ(durationText(125), "2 min 05 s");
    EXPECT_EQ(durationText(3725), "1 h 02 min");
}

TEST(Progress, LinesAtMostOneASecondAndOnePerTenPercent) {
    double now = 100;
    std::ostringstream out;
    {
        ProgressDisplay display(out, ProgressDisplay::Style::Lines, "gpu render",
                                [&now] { return now; });
        const std::size_t total = 1'000'000;
        display.update(0, total);
        now = 100.5;
        display.update(100'000, total);  // within the first second: nothing
        EXPECT_EQ(out.str(), "");
        now = 101;
        display.update(250'000, total);  // 25 % after 1 s: the first line
        now = 101.5;
        display.update(400'000, total);  // a new 10 % step, but within the second
        now = 102.5;
        display.update(450'000, total);  // 45 %: a second later, a new step
        now = 103.6;
        display.update(480'000, total);  // still 40-49 %: nothing
        now = 104;
        display.update(1'000'000, total);
        display.finish();
    }
    const std::vector<std::string> lines = linesOf(out.str());
    ASSERT_EQ(lines.size(), 3u) << out.str();
    EXPECT_EQ(lines[0], "gpu render: 25% (250000 of 1000000 rays), 0.25 Mrays/s, 3 s left");
    EXPECT_EQ(lines[1], "gpu render: 45% (450000 of 1000000 rays), 0.18 Mrays/s, 3 s left");
    EXPECT_EQ(lines[2], "gpu render: 100% (1000000 of 1000000 rays), 0.25 Mrays/s, done in 4 s");
}

TEST(Progress, TimeLeftDiscountsTheSlowFirstPiece) {
    // The first tile takes 2 s (lavapipe compiles the shader then), the next
    // 100 000 rays 1 s: 890 000 left at 100 000 a second is 9 s, not the 24 s
    // the average since the start would say.
    double now = 0;
    std::ostringstream out;
    ProgressDisplay display(out, ProgressDisplay::Style::Lines, "gpu render",
                            [&now] { return now; });
    display.update(0, 1'000'000);
    now = 2;
    display.update(10'000, 1'000'000);
    now = 3;
    display.update(110'000, 1'000'000);
    EXPECT_EQ(out.str(),
              "gpu render: 1% (10000 of 1000000 rays), 0.01 Mrays/s, 3 min 18 s left\n"
              "gpu render: 11% (110000 of 1000000 rays), 0.04 Mrays/s, 9 s left\n");
}

TEST(Progress, ShortRenderShowsNothing) {
    double now = 0;
    std::ostringstream out;
    for (const auto style : {ProgressDisplay::Style::Lines, ProgressDisplay::Style::Terminal}) {
        ProgressDisplay display(out, style, "cpu reference", [&now] { return now; });
        display.update(0, 10);
        now += 0.9;
        display.update(10, 10);
        display.finish();
    }
    EXPECT_EQ(out.str(), "");
}

TEST(Progress, TerminalRedrawsOneLineInPlace) {
    double now = 0;
    std::ostringstream out;
    ProgressDisplay display(out, ProgressDisplay::Style::Terminal, "gpu render",
                            [&now] { return now; });
    display.update(0, 1000);
    now = 2;
    display.update(500, 1000);
    now = 2.05;
    display.update(600, 1000);  // within a tenth of a second: not redrawn
    now = 4;
    display.update(1000, 1000);
    display.finish();
    const std::string text = out.str();
    // Each redraw returns to the start of the line and erases it; one newline, at the end.
    EXPECT_EQ(text,
              "\r\x1b[Kgpu render  50% [##########----------] 0.00 Mrays/s, 2 s left"
              "\r\x1b[Kgpu render 100% [####################] 0.00 Mrays/s, done in 4 s\n");
}

TEST(Progress, InterruptedTerminalLineIsEnded) {
    double now = 0;
    std::ostringstream out;
    {
        ProgressDisplay display(out, ProgressDisplay::Style::Terminal, "cpu reference",
                                [&now] { return now; });
        display.update(0, 100);
        now = 1.5;
        display.update(30, 100);
    }  // destroyed without finish(), as when a render throws
    EXPECT_EQ(out.str().back(), '\n');
    EXPECT_NE(out.str().find(" 30% ["), std::string::npos) << out.str();
}

TEST(Progress, OffPrintsNothing) {
    double now = 0;
    std::ostringstream out;
    ProgressDisplay display(out, ProgressDisplay::Style::Off, "gpu render", [&now] { return now; });
    display.update(0, 10);
    now = 5;
    display.update(5, 10);
    display.finish();
    EXPECT_EQ(out.str(), "");
}

TEST(Progress, UpdatesFromWorkersOutOfOrderNeverGoBack) {
    double now = 0;
    std::ostringstream out;
    ProgressDisplay display(out, ProgressDisplay::Style::Lines, "cpu reference",
                            [&now] { return now; });
    display.update(0, 100);
    now = 1;
    display.update(50, 100);
    now = 3;
    display.update(40, 100);  // a worker that finished earlier reports late
    EXPECT_EQ(linesOf(out.str()).size(), 1u) << out.str();
}

}  // namespace
}  // namespace vkray
