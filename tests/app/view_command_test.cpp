// `vkray view` under a virtual X server (Xvfb), driven by --events scripts
// and --frames/--screenshot: its pictures are `vkray render`'s, byte for
// byte; its camera line renders its picture; it reloads, and keeps the
// last good image on an error. No test waits for time to pass: each waits
// for a line the view prints or for a pass (wait-pass, wait-reload).
#include "app/view_command.h"
#include "image/image_io.h"
#include "support/cli_fixture.h"
#include "support/virtual_display.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>

namespace vkray {
namespace {

using test::RunResult;
namespace fs = std::filesystem;

// A sphere on a floor, lit: edges for the samples to smooth, depths from
// near to the horizon.
const char* kScene =
    "camera eye 0 1.5 6 look 0 0.5 0 up 0 1 0 fov 40\n"
    "light 5 5 5 1 1 1\n"
    "ambient 0.2 0.05 0.05 diffuse 0.8 0.2 0.1 translate 0 1 0 sphere\n"
    "push rotate -90 1 0 0 ambient 0.2 0.2 0.2 diffuse 0.5 0.5 0.5 plane pop\n";
const char* kSize = " --size 64x48 --spp 4";  // 4 block passes + 4 samples

test::VirtualDisplay& virtualDisplay() {
    static test::VirtualDisplay display;
    return display;
}

// The line of `output` that starts with `start` (without its newline), or "".
std::string lineStarting(const std::string& output, const std::string& start) {
    const size_t at = output.rfind("\n" + start);
    if (at == std::string::npos)
        return output.rfind(start, 0) == 0 ? output.substr(0, output.find('\n')) : "";
    return output.substr(at + 1, output.find('\n', at + 1) - at - 1);
}

// The whole number that follows `before` in `text`, or -1.
long numberAfter(const std::string& text, const std::string& before) {
    const size_t at = text.find(before);
    return at == std::string::npos ? -1
                                   : std::strtol(text.c_str() + at + before.size(), nullptr, 10);
}

std::string bytesOf(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

class View : public test::CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        if (!virtualDisplay().ready()) GTEST_SKIP() << virtualDisplay().why();
        environment = "DISPLAY=" + virtualDisplay().display();
    }
    RunResult view(const std::string& args) { return test::vkray("view " + args, environment); }
    RunResult render(const std::string& args) { return test::vkray("render " + args + " --quiet"); }
    std::string events(const std::string& text) { return scene("events.txt", text); }
    // The view in the background, for what must happen while it is open.
    std::unique_ptr<test::BackgroundVkray> viewInBackground(const std::string& args) {
        return std::make_unique<test::BackgroundVkray>("view " + args, dir / "view.log",
                                                       std::vector<std::string>{environment});
    }
    // The exit status once the view has quit by itself (--frames, q).
    int exitStatus(test::BackgroundVkray& shown) {
        for (int i = 0; i < 600 && !shown.exited(); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        return shown.exited() ? shown.stop() : -2;
    }
    // Replaces the file at once, as an editor saves: written in the test's
    // folder under a name the view does not watch, then renamed over it. A
    // save is then one change, however slowly the test runs: a file written
    // beside a shader would be a change of the shader folder of its own.
    void save(const std::string& path, const std::string& text) {
        const fs::path written = dir / (fs::path(path).filename().string() + ".saving");
        std::ofstream(written) << text;
        fs::rename(written, path);
    }
    std::string environment;
};

TEST_F(View, FullProgressionIsTheRenderByteForByte) {
    const std::string s = scene("s.sdl", kScene);
    // With the validation layer: a Vulkan message of the window's swapchain,
    // copies or presents would fail the run.
    RunResult shown = view(s + kSize + " --validation --frames 8 --screenshot " + path("view.png"));
    ASSERT_EQ(shown.status, 0) << shown.output;
    EXPECT_EQ(shown.output.find("validation:"), std::string::npos) << shown.output;
    EXPECT_NE(shown.output.find("pass 8/8: block 1, sample 4 of 4"), std::string::npos)
        << shown.output;
    EXPECT_NE(shown.output.find("wrote " + path("view.png")), std::string::npos) << shown.output;
    ASSERT_EQ(render(s + kSize + " -o " + path("render.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("render.png")));
}

TEST_F(View, EachBlockPassIsRenderBlock) {
    // Pass 1 is `render --block 16`, pass 2 --block 8, 3 --block 4, 4 --block 2.
    const std::string s = scene("s.sdl", kScene);
    for (const int pass : {1, 2, 3, 4}) {
        const int block = 16 >> (pass - 1);
        RunResult shown = view(s + kSize + " --frames " + std::to_string(pass) + " --screenshot " +
                               path("view.png"));
        ASSERT_EQ(shown.status, 0) << shown.output;
        ASSERT_EQ(render(s + " --size 64x48 --block " + std::to_string(block) + " -o " +
                         path("render.png"))
                      .status,
                  0);
        EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("render.png"))) << "pass " << pass;
    }
    // With one sample, the fifth and last pass is the plain render.
    ASSERT_EQ(view(s + " --size 64x48 --spp 1 --frames 5 --screenshot " + path("view.png")).status,
              0);
    ASSERT_EQ(render(s + " --size 64x48 -o " + path("render.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("render.png")));
}

TEST_F(View, PrintedCameraRendersTheScreenshot) {
    const std::string s = scene("s.sdl", kScene);
    RunResult shown =
        view(s + kSize + " --frames 8 --screenshot " + path("view.png") + " --events " +
             events("drag left 60 -25\nwait-pass\ndrag right 7 4\nwheel 2\nkey p\n"));
    ASSERT_EQ(shown.status, 0) << shown.output;
    const std::string line = lineStarting(shown.output, "camera eye ");
    ASSERT_NE(line.find(" fov "), std::string::npos) << shown.output;
    // Pasted at the end of the scene, the line overrides its camera.
    const std::string moved = scene("moved.sdl", std::string(kScene) + line + "\n");
    ASSERT_EQ(render(moved + kSize + " -o " + path("moved.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("moved.png"))) << line;
    // ... and the camera did move: the scene's own camera gives another picture.
    ASSERT_EQ(render(s + kSize + " -o " + path("still.png")).status, 0);
    EXPECT_NE(bytesOf(path("view.png")), bytesOf(path("still.png")));
}

TEST_F(View, ResetKeyGoesBackToTheScenesCamera) {
    const std::string s = scene("s.sdl", kScene);
    ASSERT_EQ(view(s + kSize + " --frames 8 --screenshot " + path("view.png") + " --events " +
                   events("drag left 80 10\nwheel -3\nwait-pass\nkey r\n"))
                  .status,
              0);
    ASSERT_EQ(render(s + kSize + " -o " + path("render.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("render.png")));
}

TEST_F(View, SceneEditedWhileOpenShowsTheEdit) {
    const std::string s = scene("s.sdl", kScene);
    auto shown = viewInBackground(s + kSize + " --frames 8 --screenshot " + path("view.png") +
                                  " --events " + events("wait-reload\n"));
    ASSERT_TRUE(shown->waitFor("waiting for a reload")) << shown->output();
    std::string edited = kScene;
    edited.replace(edited.find("diffuse 0.8 0.2 0.1"), 19, "diffuse 0.1 0.3 0.9");
    save(s, edited);
    ASSERT_TRUE(shown->waitFor("wrote " + path("view.png"))) << shown->output();
    EXPECT_EQ(exitStatus(*shown), 0) << shown->output();
    EXPECT_NE(shown->output().find("reloaded " + s), std::string::npos) << shown->output();
    ASSERT_EQ(render(s + kSize + " -o " + path("edited.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("edited.png")));
}

TEST_F(View, BrokenEditKeepsTheLastGoodImageAndNamesThePlace) {
    const std::string s = scene("s.sdl", kScene);
    ASSERT_EQ(render(s + kSize + " -o " + path("good.png")).status, 0);
    auto shown = viewInBackground(s + kSize + " --frames 8 --screenshot " + path("view.png") +
                                  " --events " + events("wait-reload\n"));
    ASSERT_TRUE(shown->waitFor("waiting for a reload")) << shown->output();
    std::string broken = kScene;
    broken.replace(broken.find("diffuse 0.8"), 11, "diffuse frob");  // line 3, column 31
    save(s, broken);
    ASSERT_TRUE(shown->waitFor("wrote " + path("view.png"))) << shown->output();
    // The error stands at the end: exit 1, after the screenshot of the last good image.
    EXPECT_EQ(exitStatus(*shown), 1) << shown->output();
    EXPECT_NE(shown->output().find(s + ":3:31: error:"), std::string::npos) << shown->output();
    EXPECT_NE(shown->output().find("kept the last good image"), std::string::npos);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("good.png")));
}

TEST_F(View, ShaderEditReloadsAndABrokenShaderNamesItsLine) {
    // A copy of the shaders, edited while the view is open: the plane's
    // shader broken at a known line, then mended.
    const fs::path shaders = dir / "shaders";
    fs::copy(VKRAY_SHADER_DIR, shaders, fs::copy_options::recursive);
    const std::string s = scene("s.sdl", kScene);
    auto shown = viewInBackground(s + kSize + " --shader-dir " + shaders.string() +
                                  " --frames 8 --screenshot " + path("view.png") + " --events " +
                                  events("wait-reload\nwait-reload\n"));
    ASSERT_TRUE(shown->waitFor("waiting for a reload")) << shown->output();
    const fs::path plane = shaders / "shapes" / "plane.glsl";
    const std::string original = bytesOf(plane.string());
    save(plane.string(), "this is not GLSL\n" + original);
    ASSERT_TRUE(shown->waitFor("waiting for a reload", 2)) << shown->output();
    ASSERT_TRUE(shown->waitFor("plane.glsl:1")) << shown->output();
    EXPECT_NE(shown->output().find("kept the last good image"), std::string::npos)
        << shown->output();
    save(plane.string(), original);
    ASSERT_TRUE(shown->waitFor("wrote " + path("view.png"))) << shown->output();
    EXPECT_EQ(exitStatus(*shown), 0) << shown->output();
    ASSERT_EQ(render(s + kSize + " -o " + path("render.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("render.png")));
}

// The view's window on the X server: its title and its pixels as RGB bytes
// (both empty until it is there).
struct SeenWindow {
    std::string title;
    std::vector<unsigned char> rgb;
};

SeenWindow windowOnScreen(const std::string& display, int width, int height) {
    Display* x = XOpenDisplay(display.c_str());
    if (!x) return {};
    XSetErrorHandler(
        [](Display*, XErrorEvent*) { return 0; });  // a window not yet mapped: try again
    Window root = DefaultRootWindow(x), rootBack, parent, *children = nullptr, found = 0;
    unsigned count = 0;
    XQueryTree(x, root, &rootBack, &parent, &children, &count);
    SeenWindow seen;
    for (unsigned i = 0; i < count && !found; ++i) {
        char* name = nullptr;
        if (XFetchName(x, children[i], &name) && name) {
            if (std::string(name).rfind("vkray view", 0) == 0) {
                found = children[i];
                seen.title = name;
            }
            XFree(name);
        }
    }
    if (children) XFree(children);
    std::vector<unsigned char>& rgb = seen.rgb;
    XImage* image =
        found ? XGetImage(x, found, 0, 0, unsigned(width), unsigned(height), AllPlanes, ZPixmap)
              : nullptr;
    if (image) {
        const auto channel = [](unsigned long pixel, unsigned long mask) {
            int shift = 0;
            while (mask && !(mask & 1)) {
                mask >>= 1;
                ++shift;
            }
            return (unsigned char)((pixel >> shift) & mask);
        };
        for (int y = 0; y < height; ++y)
            for (int xx = 0; xx < width; ++xx) {
                const unsigned long p = XGetPixel(image, xx, y);
                rgb.push_back(channel(p, image->red_mask));
                rgb.push_back(channel(p, image->green_mask));
                rgb.push_back(channel(p, image->blue_mask));
            }
        XDestroyImage(image);
    }
    XCloseDisplay(x);
    return seen;
}

TEST_F(View, TheWindowShowsThePicture) {
    // Copied into the swapchain on the device: what the X server has in the
    // window is the render's PNG, byte for byte.
    const std::string s = scene("s.sdl", kScene);
    ASSERT_EQ(render(s + kSize + " -o " + path("render.png")).status, 0);
    const Image expected = readImage(path("render.png"));
    std::vector<unsigned char> want;
    for (const float v : expected.pixels) want.push_back((unsigned char)std::lround(v * 255));
    auto shown = viewInBackground(s + kSize + " --events " +
                                  events("wait-pass\nwait-pass\nwait-pass\nwait-pass\nwait-"
                                         "pass\nwait-pass\nwait-pass\nwait-pass\nwait-reload\n"));
    ASSERT_TRUE(shown->waitFor("waiting for a reload")) << shown->output();
    ASSERT_NE(shown->output().find("pass 8/8"), std::string::npos) << shown->output();
    // The X server draws what it was sent in its own time: look until it is there.
    SeenWindow seen;
    for (int attempt = 0; attempt < 600 && seen.rgb != want; ++attempt) {
        seen = windowOnScreen(virtualDisplay().display(), 64, 48);
        if (seen.rgb != want) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    EXPECT_TRUE(seen.rgb == want) << "the window does not show the picture";
    // The title: the scene, the pass, the speed and the device.
    for (const char* part :
         {"vkray view s.sdl", "pass 8/8 block 1, sample 4 of 4", "Mrays/s", "llvmpipe"})
        EXPECT_NE(seen.title.find(part), std::string::npos) << part << " in " << seen.title;
    EXPECT_EQ(shown->stop(SIGINT), 0) << shown->output();
}

// The view's window on `x`, or 0.
Window viewWindow(Display* x) {
    Window root = DefaultRootWindow(x), rootBack, parent, *children = nullptr, found = 0;
    unsigned count = 0;
    XQueryTree(x, root, &rootBack, &parent, &children, &count);
    for (unsigned i = 0; i < count && !found; ++i) {
        char* name = nullptr;
        if (XFetchName(x, children[i], &name) && name) {
            if (std::string(name).rfind("vkray view", 0) == 0) found = children[i];
            XFree(name);
        }
    }
    if (children) XFree(children);
    return found;
}

TEST_F(View, TheWindowsOwnMouseAndKeysMoveAndQuit) {
    // Input sent to the window as the X server would deliver a user's: a
    // drag with the left button, then `p` and `q`, handled in that order.
    const std::string s = scene("s.sdl", kScene);
    auto shown = viewInBackground(s + " --size 64x48 --spp 64");
    ASSERT_TRUE(shown->waitFor("pass 1/68")) << shown->output();
    Display* x = XOpenDisplay(virtualDisplay().display().c_str());
    ASSERT_NE(x, nullptr);
    const Window window = viewWindow(x);
    ASSERT_NE(window, 0u);
    const auto send = [&](int type, long mask, auto fill) {
        XEvent e{};
        e.type = type;
        e.xany.window = window;
        e.xany.display = x;
        fill(e);
        XSendEvent(x, window, True, mask, &e);
    };
    const auto mouse = [&](XEvent& e, int px, int py) {
        e.xbutton.root = DefaultRootWindow(x);
        e.xbutton.x = px;
        e.xbutton.y = py;
        e.xbutton.same_screen = True;
    };
    send(ButtonPress, ButtonPressMask, [&](XEvent& e) {
        mouse(e, 10, 20);
        e.xbutton.button = Button1;
    });
    send(MotionNotify, PointerMotionMask, [&](XEvent& e) {
        mouse(e, 40, 25);
        e.xmotion.state = Button1Mask;
    });
    send(ButtonRelease, ButtonReleaseMask, [&](XEvent& e) {
        mouse(e, 40, 25);
        e.xbutton.button = Button1;
        e.xbutton.state = Button1Mask;
    });
    for (const KeySym key : {XK_p, XK_q})
        send(KeyPress, KeyPressMask, [&](XEvent& e) {
            e.xkey.root = DefaultRootWindow(x);
            e.xkey.keycode = XKeysymToKeycode(x, key);
            e.xkey.same_screen = True;
        });
    XFlush(x);
    XCloseDisplay(x);
    ASSERT_TRUE(shown->waitFor("camera eye")) << shown->output();
    EXPECT_EQ(exitStatus(*shown), 0) << "q closes the view\n" << shown->output();
    // The drag moved the eye from the scene's (0, 1.5, 6).
    EXPECT_EQ(shown->output().find("camera eye 0 1.5 6 "), std::string::npos) << shown->output();
}

TEST_F(View, CpuReferenceViewIsRenderCpu) {
    const std::string s = scene("s.sdl", kScene);
    RunResult shown = view(s + kSize + " --frames 8 --screenshot " + path("view.png") +
                           " --events " + events("key c\nwait-cpu\n"));
    ASSERT_EQ(shown.status, 0) << shown.output;
    EXPECT_NE(shown.output.find("cpu reference ready"), std::string::npos) << shown.output;
    ASSERT_EQ(render(s + kSize + " --cpu -o " + path("cpu.png")).status, 0);
    EXPECT_EQ(bytesOf(path("view.png")), bytesOf(path("cpu.png")));
}

TEST_F(View, DifferenceCountsThePixelsCheckCounts) {
    // A threshold low enough that float against double shows: the count of
    // colours over it is `render --check`'s, for the same threshold, and so
    // is the margin rule's verdict on them.
    const std::string s = scene("s.sdl", kScene);
    RunResult shown = view(s + kSize + " --validation --fail 1e-7 --frames 8 --screenshot " +
                           path("diff.png") + " --events " + events("key d\nwait-cpu\n"));
    ASSERT_EQ(shown.status, 0) << shown.output;
    // The last count, the progression complete (no note after it).
    const std::string line = lineStarting(shown.output, "difference: ");
    ASSERT_NE(line.find(" of 3072 pixels with error > 1e-07"), std::string::npos) << shown.output;
    ASSERT_EQ(line.find("not complete"), std::string::npos) << shown.output;
    const long viewCount = numberAfter(line, "difference: ");
    RunResult check =
        render(s + kSize + " --check --fail 1e-7 --failpercent 100 -o " + path("gpu.png"));
    ASSERT_EQ(check.status, 0) << check.output;
    const long checkCount = numberAfter(check.output, "%): colour ");
    ASSERT_NE(check.output.find(" of 3072 pixels"), std::string::npos) << check.output;
    EXPECT_EQ(viewCount, checkCount);
    EXPECT_GT(viewCount, 0) << "the threshold is to make some pixels differ";
    EXPECT_NE(line.find("(the margin rule, robust)"), std::string::npos) << shown.output;
    // The heat map, by the margin rule's verdicts: set-aside pixels blue (as
    // `render --diff` draws them), unexplained ones red to yellow by their
    // error, grey where the colours agree.
    const Image heat = readImage(path("diff.png"));
    long hot = 0, blue = 0;
    for (size_t i = 0; i < heat.pixels.size(); i += 3) {
        const float r = heat.pixels[i], g = heat.pixels[i + 1], b = heat.pixels[i + 2];
        const bool red = r == 1.0f && b == 0.0f;
        const bool setAside = r == 0.2f && g == 0.4f && b == 1.0f;
        const bool grey = r == g && g == b;
        EXPECT_TRUE(red || setAside || grey) << "pixel " << i / 3;
        hot += red && !grey;
        blue += setAside;
    }
    EXPECT_EQ(hot + blue, viewCount);
    EXPECT_EQ(hot, numberAfter(line, " set aside, "));
    EXPECT_EQ(blue, numberAfter(line, "; "));
    EXPECT_GT(blue, 0) << line;  // float against double at 1e-7: within the bound
}

TEST_F(View, AovViewsShowTheRendersAovs) {
    const std::string s = scene("s.sdl", kScene);
    ASSERT_EQ(render(s + kSize + " --aov " + path("aov") + " -o " + path("render.png")).status, 0);
    const Image depth = readImage(path("aov.depth.pfm")),
                normal = readImage(path("aov.normal.pfm")), ids = readImage(path("aov.id.pfm"));
    std::map<std::string, Image> shown;
    for (const char* key : {"2", "3", "4"}) {
        RunResult run = view(s + kSize + " --frames 8 --screenshot " +
                             path(std::string("view") + key + ".png") + " --events " +
                             events(std::string("key ") + key + "\n"));
        ASSERT_EQ(run.status, 0) << run.output;
        shown[key] = readImage(path(std::string("view") + key + ".png"));
    }
    const size_t pixels = size_t(depth.width) * size_t(depth.height);
    // Depth: red near to blue far, even in 1/depth over the finite depths' range.
    float nearest = INFINITY, farthest = 0;
    for (const float d : depth.pixels)
        if (std::isfinite(d)) nearest = std::min(nearest, d), farthest = std::max(farthest, d);
    // Normals: 0.5 + 0.5 n. Ids: one colour per object, black for the background.
    std::map<float, std::vector<float>> colourOfId;
    for (size_t i = 0; i < pixels; ++i) {
        const float d = depth.pixels[i];
        const float t =
            std::isfinite(d) ? (1 / d - 1 / farthest) / (1 / nearest - 1 / farthest) : -1;
        const float expectedDepth[3] = {std::clamp(2 * t - 1, 0.0f, 1.0f),
                                        std::clamp(1 - std::abs(2 * t - 1), 0.0f, 1.0f),
                                        std::clamp(1 - 2 * t, 0.0f, 1.0f)};
        for (int c = 0; c < 3; ++c) {
            const float want = std::isfinite(d) ? expectedDepth[c] : 0.0f;
            ASSERT_NEAR(shown["2"].pixels[3 * i + size_t(c)], want, 1.5 / 255)
                << "depth view, pixel " << i;
            const float n =
                ids.pixels[i] < 0 ? 0.0f : 0.5f + 0.5f * normal.pixels[3 * i + size_t(c)];
            ASSERT_NEAR(shown["3"].pixels[3 * i + size_t(c)], n, 1.0 / 255)
                << "normal view, pixel " << i;
        }
        const std::vector<float> colour(shown["4"].pixels.begin() + long(3 * i),
                                        shown["4"].pixels.begin() + long(3 * i + 3));
        if (ids.pixels[i] < 0)
            EXPECT_EQ(colour, std::vector<float>(3, 0.0f)) << "background, pixel " << i;
        else if (!colourOfId.count(ids.pixels[i]))
            colourOfId[ids.pixels[i]] = colour;
        else
            EXPECT_EQ(colour, colourOfId[ids.pixels[i]])
                << "id " << ids.pixels[i] << ", pixel " << i;
    }
    ASSERT_EQ(colourOfId.size(), 2u);  // the sphere and the floor
    EXPECT_NE(colourOfId.begin()->second, colourOfId.rbegin()->second);
}

TEST_F(View, SaveKeyWritesAWholePngAndSaysWhere) {
    const std::string s = scene("s.sdl", kScene);
    RunResult shown = test::runShell("cd " + dir.string() + " && env " + environment + " " +
                                     VKRAY_BINARY + " view s.sdl" + kSize +
                                     " --frames 8 --events " + events("key s\nwait-pass\nkey s\n"));
    ASSERT_EQ(shown.status, 0) << shown.output;
    EXPECT_NE(shown.output.find("wrote s-1.png"), std::string::npos) << shown.output;
    EXPECT_NE(shown.output.find("wrote s-2.png"), std::string::npos) << shown.output;
    EXPECT_EQ(readImage(path("s-2.png")).width, 64);
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

// No display needed for these.
using ViewWithoutDisplay = test::CliTest;

TEST_F(ViewWithoutDisplay, NoDisplayExitsOneNamingThemAndRenderWatch) {
    const std::string s = scene("s.sdl", kScene);
    RunResult run = test::runShell("env -u DISPLAY -u WAYLAND_DISPLAY " +
                                   std::string(VKRAY_BINARY) + " view " + s + " --frames 1");
    EXPECT_EQ(run.status, 1) << run.output;
    for (const char* word : {"DISPLAY", "WAYLAND_DISPLAY", "vkray render --watch"})
        EXPECT_NE(run.output.find(word), std::string::npos) << word << " in " << run.output;
}

TEST_F(ViewWithoutDisplay, BadEventScriptNamesItsLine) {
    const std::string s = scene("s.sdl", kScene);
    const std::string events = scene("events.txt", "key p\n\ndrag middle 1 2\n");
    RunResult run = test::vkray("view " + s + " --events " + events);
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find(events + ":3:6: error:"), std::string::npos) << run.output;
}

TEST(ViewProgression, BlocksThenOneSampleAPass) {
    const std::vector<ViewPass> passes = viewProgression(64, 48, 3, 9);
    ASSERT_EQ(passes.size(), 7u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(passes[size_t(i)].settings.block, 16 >> i);
        EXPECT_EQ(passes[size_t(i)].settings.spp, 1);  // the block's centre, as render --block
        EXPECT_TRUE(passes[size_t(i)].fresh);
    }
    for (int k = 0; k < 3; ++k) {
        const RenderSettings& s = passes[size_t(4 + k)].settings;
        EXPECT_EQ(s.block, 1);
        EXPECT_EQ(s.spp, 3);
        EXPECT_EQ(s.seed, 9u);
        EXPECT_EQ(s.firstSample, k);
        EXPECT_EQ(s.sampleCount, 1);
        EXPECT_EQ(passes[size_t(4 + k)].fresh, k == 0);
    }
    EXPECT_EQ(passes[5].name, "block 1, sample 2 of 3");
}

}  // namespace
}  // namespace vkray
