// The --events script: one event a line, and every mistake at its place.
#include "app/view_events.h"

#include "util/error.h"

#include <gtest/gtest.h>

namespace vkray {
namespace {

TEST(ViewEvents, ReadsEveryKind) {
    const std::vector<ViewEvent> e = parseViewEvents(
        "# a comment\nkey p\n\ndrag left 100 0\ndrag right -3.5 2\nwheel -2\nwait-pass\n"
        "wait-cpu\nwait-reload\nkey esc\n",
        "e.txt");
    ASSERT_EQ(e.size(), 8u);
    EXPECT_EQ(e[0].kind, ViewEvent::Kind::Key);
    EXPECT_EQ(e[0].key, "p");
    EXPECT_EQ(e[1].kind, ViewEvent::Kind::Drag);
    EXPECT_FALSE(e[1].rightButton);
    EXPECT_EQ(e[1].dx, 100);
    EXPECT_EQ(e[1].dy, 0);
    EXPECT_TRUE(e[2].rightButton);
    EXPECT_EQ(e[2].dx, -3.5);
    EXPECT_EQ(e[3].kind, ViewEvent::Kind::Wheel);
    EXPECT_EQ(e[3].steps, -2);
    EXPECT_EQ(e[4].kind, ViewEvent::Kind::WaitPass);
    EXPECT_EQ(e[5].kind, ViewEvent::Kind::WaitCpu);
    EXPECT_EQ(e[6].kind, ViewEvent::Kind::WaitReload);
    EXPECT_EQ(e[7].key, "esc");
}

std::string errorOf(const std::string& text) {
    try {
        parseViewEvents(text, "e.txt");
    } catch (const Error& e) {
        return e.what();
    }
    return "(accepted)";
}

TEST(ViewEvents, MistakesNameTheirPlace) {
    EXPECT_EQ(errorOf("key p\nkey x\n").rfind("e.txt:2:5: error: 'x' is not a key", 0), 0u)
        << errorOf("key p\nkey x\n");
    EXPECT_EQ(errorOf("  drag up 1 2\n").rfind("e.txt:1:8: error: the button is", 0), 0u);
    EXPECT_EQ(errorOf("drag left 1 y\n").rfind("e.txt:1:13: error: 'y' is not a number", 0), 0u);
    EXPECT_EQ(errorOf("drag left 1\n").rfind("e.txt:1:11: error: too little", 0), 0u);
    EXPECT_EQ(errorOf("wheel 1 2\n").rfind("e.txt:1:9: error: too much", 0), 0u);
    EXPECT_EQ(errorOf("wait-pass now\n").rfind("e.txt:1:11: error: too much", 0), 0u);
    EXPECT_EQ(errorOf("press q\n").rfind("e.txt:1:1: error: unknown event 'press'", 0), 0u);
    EXPECT_EQ(errorOf("wheel inf\n").rfind("e.txt:1:7: error: 'inf' is not a number", 0), 0u);
}

}  // namespace
}  // namespace vkray
