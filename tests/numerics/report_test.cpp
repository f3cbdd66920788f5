// The report files (CSV, JSON, HTML with SVG plots), `vkray report`'s sweep
// over the knobs, and both commands as a user runs them.
#include "image/image_io.h"
#include "image/pictures.h"
#include "numerics/document_check.h"
#include "numerics/report_sweep.h"
#include "numerics/report_writer.h"
#include "scene/scene_geometry.h"
#include "support/cli_fixture.h"
#include "support/gpu_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

namespace vkray::numerics {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

Report sampleReport() {
    Report r;
    r.title = "a <title> & more";
    r.paragraphs = {"line with \"quotes\", commas\nand a newline"};
    r.table.columns = {"name", "value", "count"};
    using V = ReportValue;
    r.table.rows = {{V::str("plain"), V::num(1.25e-7), V::whole(3)},
                    {V::str("needs, \"quoting\""), V{}, V::whole(-1)},
                    {V::str("zero"), V::num(0), V::whole(0)}};
    Plot plot;
    plot.title = "t & time";
    plot.xLabel = "s";
    plot.yLabel = "error";
    plot.points = {{"slow exact", 2.0, 0.0, false},
                   {"fast <rough>", 0.01, 3e-3, true},
                   {"middle", 0.1, 1e-6, false},
                   {"dominated", 3.0, 1e-2, false}};
    r.plots = {plot};
    return r;
}

TEST(ReportWriter, CsvQuotesAndKeepsFullPrecision) {
    const auto rows = test::parseCsv(toCsv(sampleReport().table));
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[0], (std::vector<std::string>{"name", "value", "count"}));
    EXPECT_EQ(rows[1], (std::vector<std::string>{"plain", "1.25e-07", "3"}));
    EXPECT_EQ(rows[2], (std::vector<std::string>{"needs, \"quoting\"", "", "-1"}));
}

TEST(ReportWriter, JsonParsesWithNullsAndEscapes) {
    const nlohmann::json json = nlohmann::json::parse(toJson(sampleReport()));
    EXPECT_EQ(json.at("title"), "a <title> & more");
    EXPECT_EQ(json.at("notes").at(0), "line with \"quotes\", commas\nand a newline");
    ASSERT_EQ(json.at("rows").size(), 3u);
    EXPECT_EQ(json.at("rows")[0].at("value").get<double>(), 1.25e-7);
    EXPECT_TRUE(json.at("rows")[1].at("value").is_null());
    EXPECT_EQ(json.at("rows")[1].at("name"), "needs, \"quoting\"");
}

// Read back by a library, not by a reader written with the writer: every
// control character, quote, backslash and UTF-8 text survives; bytes that are
// not UTF-8 become U+FFFD instead of an invalid file.
TEST(ReportWriter, JsonKeepsEveryCharacter) {
    Report report;
    std::string every;
    for (int c = 1; c < 0x20; ++c) every += char(c);
    every += "\"\\/ caf\xc3\xa9 \xe2\x88\x9e";
    report.title = every;
    report.paragraphs = {"latin-1 \xe9 byte"};
    report.table.columns = {"name", "n"};
    report.table.rows = {{ReportValue::str(every), ReportValue::whole(-3)}};
    const nlohmann::json json = nlohmann::json::parse(toJson(report));
    EXPECT_EQ(json.at("title"), every);
    EXPECT_EQ(json.at("rows")[0].at("name"), every);
    EXPECT_EQ(json.at("rows")[0].at("n"), -3);
    EXPECT_EQ(json.at("notes")[0], "latin-1 \xef\xbf\xbd byte");
}

TEST(ReportWriter, TableAlignsAndShortensNumbers) {
    const std::string text = formatTable(sampleReport().table);
    EXPECT_NE(text.find("1.25e-07"), std::string::npos) << text;
    EXPECT_NE(text.find("plain"), std::string::npos);
    std::istringstream lines(text);
    std::string first, second;
    std::getline(lines, first);
    std::getline(lines, second);
    EXPECT_EQ(first.size(), second.size()) << text;
}

TEST(ReportWriter, HtmlIsWellFormedWithOneSvgPerPlotAndAParetoFront) {
    const std::string html = toHtml(sampleReport());
    EXPECT_EQ(test::xmlProblem(html), "");
    EXPECT_EQ(test::xmlProblem("<p><b>x</p></b>"), "</p> closes <b> at 7");  // the checker checks
    EXPECT_NE(html.find("a &lt;title&gt; &amp; more"), std::string::npos);
    const std::string svg = toSvg(sampleReport().plots[0]);
    EXPECT_EQ(test::xmlProblem(svg), "");
    // Four points, the zero drawn on its own "0" line, and a front through the
    // three undominated ones (fast, middle, slow exact), not "dominated".
    size_t circles = 0;
    for (size_t at = svg.find("<circle class=\"point\""); at != std::string::npos;
         at = svg.find("<circle class=\"point\"", at + 1))
        ++circles;
    EXPECT_EQ(circles, 4u);
    EXPECT_NE(svg.find(">0</text>"), std::string::npos);
    const size_t front = svg.find("<polyline points=\"");
    ASSERT_NE(front, std::string::npos);
    const std::string points = svg.substr(front, svg.find('"', front + 18) - front);
    EXPECT_EQ(std::count(points.begin(), points.end(), ','), 3) << points;
    EXPECT_NE(svg.find("stroke=\"#d62728\""), std::string::npos);  // the flagged point
}

// The PNG an <img> embeds, decoded; fails the test unless it is a PNG data:
// URI shown at a whole multiple of its size.
Image embeddedImage(const test::XmlElement& img) {
    const std::string src = img.attribute("src"), prefix = "data:image/png;base64,";
    EXPECT_EQ(src.rfind(prefix, 0), 0u) << src.substr(0, 40);
    const Image image = decodeImage(test::fromBase64(src.substr(prefix.size())), "embedded.png");
    const int width = std::stoi(img.attribute("width")),
              height = std::stoi(img.attribute("height"));
    EXPECT_EQ(width % image.width, 0) << width << " for " << image.width;
    EXPECT_EQ(width / image.width * image.height, height);
    return image;
}

// The texts of an element's <text> children (an SVG's labels), each whole.
std::vector<std::string> svgTexts(const test::XmlElement& element) {
    std::vector<std::string> texts;
    for (const test::XmlElement* t : element.all("text")) texts.push_back(t->allText());
    return texts;
}

bool contains(const std::vector<std::string>& texts, const std::string& text) {
    return std::find(texts.begin(), texts.end(), text) != texts.end();
}

TEST(ReportWriter, Base64MatchesTheRfcVectors) {
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
    const std::string bytes("\x00\xff\x10\x80", 4);
    EXPECT_EQ(test::fromBase64(base64(bytes)), bytes);
}

// Pictures embedded as PNG data URIs that decode to what was given, heat
// maps with their colour scale, and a legend on every plot and gallery.
TEST(ReportWriter, HtmlEmbedsPicturesWithScalesAndLegends) {
    Report report = sampleReport();
    report.plots[0].points[2].series = report.plots[0].points[3].series = "same series";
    const Image picture{4, 3, 3, [] {
                            std::vector<float> v;
                            for (int i = 0; i < 36; ++i) v.push_back(float(i * 7 % 256) / 255);
                            return v;
                        }()};
    const Image heat = heatMap(Image{2, 1, 1, {0, 1}}, HeatScale{1e-4, 1});
    Gallery gallery;
    gallery.title = "Pictures & more";
    gallery.legend = {{"#ff00ff", "flip"}, {"#00ffff", "acne"}};
    gallery.groups = {{"first",
                       "a note",
                       {{"image", pngBytes(picture), std::nullopt, ""},
                        {"error", pngBytes(heat), HeatScale{1e-4, 1}, "colour error"}}},
                      {"second", "", {{"image", pngBytes(picture), std::nullopt, ""}}}};
    report.galleries = {gallery};
    const std::string html = toHtml(report);
    ASSERT_EQ(test::xmlProblem(html), "");
    const test::XmlElement page = test::parseXml(html);

    // Each plot: a legend naming each series once, the hollow red points and the front.
    const auto svgs = page.all("svg");
    ASSERT_EQ(svgs.size(), 2u);  // the plot and one colour scale
    const auto legends = svgs[0]->all("g", "legend");
    ASSERT_EQ(legends.size(), 1u);
    const std::vector<std::string> legendTexts = svgTexts(*legends[0]);
    EXPECT_EQ(legendTexts, (std::vector<std::string>{"legend", "slow exact", "fast <rough>",
                                                     "same series", "flagged", "Pareto front"}));
    EXPECT_EQ(legends[0]->all("circle").size(), 4u);  // three series and the flagged mark
    EXPECT_EQ(legends[0]->all("line").size(), 1u);    // the front's dashes

    // The gallery: its legend, its groups, each picture as it was given.
    const auto galleries = page.all("section", "gallery");
    ASSERT_EQ(galleries.size(), 1u);
    EXPECT_EQ(galleries[0]->all("h2").at(0)->allText(), "Pictures & more");
    const auto swatches = galleries[0]->all("span", "swatch");
    ASSERT_EQ(swatches.size(), 2u);
    EXPECT_EQ(swatches[0]->attribute("style"), "background: #ff00ff");
    EXPECT_NE(galleries[0]->all("div", "legend").at(0)->allText().find("acne"), std::string::npos);
    const auto groups = galleries[0]->all("div", "group");
    ASSERT_EQ(groups.size(), 2u);
    EXPECT_EQ(groups[0]->all("h3").at(0)->allText(), "first");
    const auto images = page.all("img");
    ASSERT_EQ(images.size(), 3u);
    EXPECT_EQ(embeddedImage(*images[0]).pixels, picture.pixels);
    EXPECT_EQ(std::stoi(images[0]->attribute("width")), 160);  // small pictures are enlarged
    const Image heatBack = embeddedImage(*images[1]);
    ASSERT_EQ(heatBack.width, 2);
    EXPECT_EQ(heatBack.pixels[0], std::round(heatColour(0).r * 255) / 255);
    // The heat map's figure holds its colour scale: a tick per decade, the label.
    const auto figures = groups[0]->all("figure");
    ASSERT_EQ(figures.size(), 2u);
    EXPECT_TRUE(figures[0]->all("svg").empty());
    const auto scale = figures[1]->all("svg", "scale");
    ASSERT_EQ(scale.size(), 1u);
    EXPECT_EQ(svgTexts(*scale[0]), (std::vector<std::string>{"\u22641e-4", "1e-3", "1e-2", "1e-1",
                                                             "1", "colour error"}));
    EXPECT_EQ(scale[0]->all("rect").size(), 61u);  // 60 steps and the frame
}

TEST(ReportSweep, KnobsCoverPrecisionSppBlockAndSize) {
    const std::vector<Knob> knobs = reportKnobs();
    ASSERT_EQ(knobs.size(), 4u);
    EXPECT_EQ(knobs[0].name, "precision");
    EXPECT_EQ(knobs[0].values, (std::vector<std::string>{"naive", "robust", "fp64"}));
    ReportConfig c;
    c.settings = {100, 50, 1};
    knobs[0].apply(c, "fp64");
    knobs[1].apply(c, "4");
    knobs[2].apply(c, "2");
    knobs[3].apply(c, "half");
    EXPECT_EQ(c.precision, Precision::Fp64);
    EXPECT_EQ(c.settings.spp, 4);
    EXPECT_EQ(c.settings.block, 2);
    EXPECT_EQ(c.settings.width, 50);
    EXPECT_EQ(c.settings.height, 25);
}

TEST(ReportSweep, ErrorFallsWithSamplesGrowsWithBlockEveryPrecisionRuns) {
    const Scene scene = loadScene(test::kSourceDir + "/scenes/shapes.sdl", {}, nullptr);
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    SweepOptions options;
    options.width = 48;
    options.height = 36;
    options.shaderDirectory = test::kShaderDir;
    options.threads = 2;
    const std::vector<SweepPoint> points =
        runSweep(scene, camera, test::gpuContext(), options, nullptr);
    ASSERT_EQ(points.size(),
              3u * 2u * 3u * 2u + 2u);  // every combination, then a reference per size
    const auto find = [&](const std::string& precision, const std::string& spp,
                          const std::string& block) {
        const std::vector<std::string> values{"precision " + precision, "spp " + spp,
                                              "block " + block, "size full"};
        for (const SweepPoint& p : points)
            if (p.values == values) return p;
        ADD_FAILURE() << precision << " " << spp << " " << block;
        return SweepPoint{};
    };
    // Against the 16-spp reference: the error is mostly aliasing; 4 samples
    // per pixel lower it, one ray per 4x4 block raises it.
    const SweepPoint robust = find("robust", "1", "1"), robust4spp = find("robust", "4", "1"),
                     robust4block = find("robust", "1", "4");
    ASSERT_TRUE(robust.ran && robust4spp.ran && robust4block.ran);
    EXPECT_GT(robust.rmse, 0);
    EXPECT_LT(robust4spp.rmse, 0.8 * robust.rmse);
    EXPECT_GT(robust4block.rmse, 2 * robust.rmse);
    EXPECT_GT(robust.seconds, 0);
    // An easy scene: the precision modes trace the same samples to about the same colours.
    const SweepPoint fp64 = find("fp64", "1", "1"), naive = find("naive", "1", "1");
    ASSERT_TRUE(fp64.ran && naive.ran);
    EXPECT_NEAR(fp64.rmse, robust.rmse, 1e-4);
    EXPECT_NEAR(naive.rmse, robust.rmse, 1e-2);
    EXPECT_EQ(points.back().note, "the reference");

    const Report report = sweepReport("scenes/shapes.sdl", points, "test device");
    EXPECT_EQ(report.table.rows.size(), points.size());
    EXPECT_EQ(report.plots.size(), 4u);  // RMSE and max error, for each of two sizes
    EXPECT_EQ(test::xmlProblem(toHtml(report)), "");
}

using NumericsCli = test::CliTest;

TEST_F(NumericsCli, StressWritesTableCsvJsonHtml) {
    test::RunResult run = test::vkray("stress --cases tiny --size 24x18 --cases-dir " +
                                      test::kSourceDir + "/scenes/stress --out " + path("out"));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("tiny_sphere  robust"), std::string::npos) << run.output;
    const auto csv = test::parseCsv(readFile(dir / "out/stress.csv"));
    EXPECT_EQ(csv.size(), 5u);  // header + naive, robust, fp64, double
    EXPECT_TRUE(nlohmann::json::parse(readFile(dir / "out/stress.json")).is_object());
    const std::string html = readFile(dir / "out/stress.html");
    EXPECT_EQ(test::xmlProblem(html), "");
    const test::XmlElement page = test::parseXml(html);
    // The case's plot has a legend naming the four modes.
    const auto legends = page.all("g", "legend");
    ASSERT_EQ(legends.size(), 1u);
    for (const char* mode : {"naive", "robust", "fp64", "double", "Pareto front"})
        EXPECT_TRUE(contains(svgTexts(*legends[0]), mode)) << mode;
    // Its pictures: the oracle's, then each GPU mode's, at the render's size.
    const auto groups = page.all("div", "group");
    ASSERT_EQ(groups.size(), 1u);
    EXPECT_EQ(groups[0]->all("h3").at(0)->allText(), "tiny_sphere");
    const auto images = groups[0]->all("img");
    ASSERT_EQ(images.size(), 4u);
    const auto captions = groups[0]->all("figcaption");
    ASSERT_EQ(captions.size(), 4u);
    EXPECT_EQ(captions[0]->allText(), "oracle (long double)");
    for (size_t i = 0; i < images.size(); ++i) {
        const Image image = embeddedImage(*images[i]);
        EXPECT_EQ(image.width, 24);
        EXPECT_EQ(image.height, 18);
        if (i == 0) continue;
        const char* mode = std::array{"naive", "robust", "fp64"}[i - 1];
        EXPECT_EQ(captions[i]->allText().find(mode), 0u) << mode;
    }
    const auto marks = page.all("span", "swatch");
    ASSERT_EQ(marks.size(), 3u);  // flips, wrong ids, acne
    const std::string legendText = page.all("div", "legend").at(0)->allText();
    for (const char* mark : {"flip", "wrong id", "acne"})
        EXPECT_NE(legendText.find(mark), std::string::npos) << mark;

    EXPECT_NE(run.output.find("result: 4 of 4 rows as expected (PASS)"), std::string::npos)
        << run.output;

    // A case that claims to break naive but does not: exit 2, named.
    fs::create_directories(dir / "cases");
    std::ofstream(dir / "cases/easy.sdl")
        << "! stress: a unit sphere at the origin\n! stiff: nothing\n! correct: t = 4 at the "
           "centre\n"
           "! naive: fails\ncamera eye 0 0 5 look 0 0 0 fov 40\nlight 5 5 5 1 1 1\nsphere\n";
    test::RunResult easy =
        test::vkray("stress --size 24x18 --cases-dir " + path("cases") + " --out " + path("easy"));
    EXPECT_EQ(easy.status, 2) << easy.output;
    EXPECT_NE(easy.output.find("unexpected: easy naive passes a case built to break it"),
              std::string::npos)
        << easy.output;

    test::RunResult none = test::vkray("stress --cases nothing-matches --cases-dir " +
                                       test::kSourceDir + "/scenes/stress --out " + path("none"));
    EXPECT_EQ(none.status, 1);
    EXPECT_NE(none.output.find("no scene in"), std::string::npos) << none.output;
    EXPECT_EQ(test::vkray("stress extra").status, 1);
}

// "verdict: note" for each row of a stress.csv whose mode is `mode`.
std::vector<std::string> verdictsOf(const fs::path& csvPath, const std::string& mode) {
    const auto csv = test::parseCsv(readFile(csvPath));
    std::vector<std::string> verdicts;
    if (csv.empty()) return verdicts;
    const auto column = [&](const std::string& name) {
        return size_t(std::find(csv[0].begin(), csv[0].end(), name) - csv[0].begin());
    };
    const size_t modeColumn = column("mode"), verdictColumn = column("verdict"),
                 noteColumn = column("note");
    for (size_t i = 1; i < csv.size(); ++i)
        if (csv[i].size() > noteColumn && csv[i][modeColumn] == mode)
            verdicts.push_back(csv[i][verdictColumn] + ": " + csv[i][noteColumn]);
    return verdicts;
}

// --precision fp64 on a device without doubles: the one mode asked for did
// not run, so the run fails, whatever the CPU rows say.
TEST_F(NumericsCli, StressFailsWhenTheModeAskedForDidNotRun) {
    test::RunResult run =
        test::vkray("stress --cases tiny --size 24x18 --precision fp64 --cases-dir " +
                        test::kSourceDir + "/scenes/stress --out " + path("nd"),
                    "VKRAY_FAULT=no-float64");
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_EQ(run.output.find("(PASS)"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("not run: fp64 on 1 of 1 case: the device has no shaderFloat64"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("result: 1 of 2 rows as expected (1 not run) (FAIL)"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("not run"), std::string::npos) << run.output;  // the table's verdict
    EXPECT_EQ(verdictsOf(dir / "nd/stress.csv", "fp64"),
              std::vector<std::string>{"not run: the device has no shaderFloat64"});
    EXPECT_EQ(verdictsOf(dir / "nd/stress.csv", "double"), std::vector<std::string>{"pass: "});
    const std::string json = readFile(dir / "nd/stress.json");
    EXPECT_TRUE(nlohmann::json::parse(json).is_object());
    EXPECT_NE(json.find("\"not run\""), std::string::npos);
    EXPECT_NE(json.find("not run: fp64 on 1 of 1 case: the device has no shaderFloat64"),
              std::string::npos);
    const std::string html = readFile(dir / "nd/stress.html");
    EXPECT_EQ(test::xmlProblem(html), "");
    EXPECT_NE(html.find("not run: fp64 on 1 of 1 case: the device has no shaderFloat64"),
              std::string::npos);
}

// Every mode (no --precision): fp64 not running fails the run too, and says so.
TEST_F(NumericsCli, StressOfEveryModeFailsWhenFp64DidNotRun) {
    test::RunResult run = test::vkray("stress --cases tiny --size 24x18 --cases-dir " +
                                          test::kSourceDir + "/scenes/stress --out " + path("all"),
                                      "VKRAY_FAULT=no-float64");
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("not run: fp64 on 1 of 1 case: the device has no shaderFloat64"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("result: 3 of 4 rows as expected (1 not run) (FAIL)"),
              std::string::npos)
        << run.output;
    EXPECT_EQ(verdictsOf(dir / "all/stress.csv", "fp64"),
              std::vector<std::string>{"not run: the device has no shaderFloat64"});
    EXPECT_EQ(verdictsOf(dir / "all/stress.csv", "robust"), std::vector<std::string>{"pass: "});
}

// The build copies scenes/stress next to the binary, as it does shaders/, and
// the binary looks for its cases there, wherever it is run from: here a copy
// of the build's binary with what lies next to it, in a folder far from the
// checkout, run from yet another folder.
TEST_F(NumericsCli, StressFindsItsCasesNextToTheBinaryFromAnyFolder) {
    const fs::path binary = VKRAY_BINARY, built = binary.parent_path();
    ASSERT_TRUE(fs::exists(built / "scenes/stress/tiny_sphere.sdl")) << built;
    const fs::path bin = dir / "install/bin";
    fs::create_directories(bin / "scenes");
    fs::copy_file(binary, bin / "vkray");
    fs::copy(built / "shaders", bin / "shaders", fs::copy_options::recursive);
    fs::copy(built / "scenes/stress", bin / "scenes/stress", fs::copy_options::recursive);
    fs::create_directories(dir / "elsewhere");
    test::RunResult run =
        test::runShell("cd " + path("elsewhere") + " && " + (bin / "vkray").string() +
                       " stress --cases tiny_sphere --size 32x24 --precision robust");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("stress: 1 cases"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("result: 2 of 2 rows as expected (PASS)"), std::string::npos)
        << run.output;
    EXPECT_TRUE(fs::exists(dir / "elsewhere/stress-report/stress.csv"));

    // Without them next to it, the error says where it looked and what to pass.
    fs::remove_all(bin / "scenes");
    test::RunResult lost =
        test::runShell("cd " + path("elsewhere") + " && " + (bin / "vkray").string() +
                       " stress --cases tiny_sphere --size 32x24");
    EXPECT_EQ(lost.status, 1) << lost.output;
    EXPECT_NE(
        lost.output.find("cannot find the stress cases next to the binary (" +
                         (bin / "scenes/stress").string() + ") nor in the installed place (" +
                         (dir / "install/share/vkray/stress").string() + "); pass --cases-dir DIR"),
        std::string::npos)
        << lost.output;
}

// The installed layout of `cmake --install` and the .deb: P/bin/vkray with
// nothing beside it, its shaders and stress cases in P/share/vkray.
TEST_F(NumericsCli, StressFindsItsInstalledCasesAndShadersFromAnyFolder) {
    const fs::path binary = VKRAY_BINARY, built = binary.parent_path();
    const fs::path prefix = dir / "prefix";
    fs::create_directories(prefix / "bin");
    fs::create_directories(prefix / "share/vkray");
    fs::copy_file(binary, prefix / "bin/vkray");
    fs::copy(built / "shaders", prefix / "share/vkray/shaders", fs::copy_options::recursive);
    fs::copy(built / "scenes/stress", prefix / "share/vkray/stress", fs::copy_options::recursive);
    fs::create_directories(dir / "elsewhere");
    test::RunResult run =
        test::runShell("cd " + path("elsewhere") + " && " + (prefix / "bin/vkray").string() +
                       " stress --cases tiny_sphere --size 32x24 --precision robust");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("result: 2 of 2 rows as expected (PASS)"), std::string::npos)
        << run.output;
    EXPECT_TRUE(fs::exists(dir / "elsewhere/stress-report/stress.csv"));
}

TEST_F(NumericsCli, ReportWritesItsFilesAndNamesBadInput) {
    const std::string s = scene("s.sdl", "camera eye 0 0 5\nlight 5 5 5 1 1 1\nsphere\n");
    test::RunResult run = test::vkray("report " + s + " --size 24x18 --out " + path("rep"));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("precision robust spp 1 block 1"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("precision fp64 spp 4 block 2"), std::string::npos) << run.output;
    const auto csv = test::parseCsv(readFile(dir / "rep/report.csv"));
    EXPECT_EQ(csv.size(), 1u + 36u + 2u);  // header, every configuration, a reference per size
    const std::string html = readFile(dir / "rep/report.html");
    EXPECT_EQ(test::xmlProblem(html), "");
    // Per size: two plots, each with a legend of the precision modes; a
    // gallery with each configuration's image and error heat map (on its
    // colour scale), the reference's image alone.
    const test::XmlElement page = test::parseXml(html);
    const auto legends = page.all("g", "legend");
    ASSERT_EQ(legends.size(), 4u);
    for (const auto* legend : legends)
        for (const char* series : {"naive", "robust", "fp64", "cpu double"})
            EXPECT_TRUE(contains(svgTexts(*legend), series)) << series;
    const auto galleries = page.all("section", "gallery");
    ASSERT_EQ(galleries.size(), 2u);
    for (const auto* gallery : galleries) {
        const auto groups = gallery->all("div", "group");
        ASSERT_EQ(groups.size(), 19u);
        for (const auto* group : groups) {
            const bool reference = group->all("h3").at(0)->allText().rfind("cpu double", 0) == 0;
            const auto images = group->all("img");
            ASSERT_EQ(images.size(), reference ? 1u : 2u);
            for (const auto* img : images) EXPECT_GT(embeddedImage(*img).width, 0);
            EXPECT_EQ(group->all("svg", "scale").size(), reference ? 0u : 1u);
        }
    }
    test::RunResult robust =
        test::vkray("report " + s + " --size 24x18 --precision robust --out " + path("rob"));
    ASSERT_EQ(robust.status, 0) << robust.output;
    EXPECT_EQ(test::parseCsv(readFile(dir / "rob/report.csv")).size(), 1u + 12u + 2u);
    EXPECT_EQ(robust.output.find("precision naive"), std::string::npos) << robust.output;
    test::RunResult bad =
        test::vkray("report " + scene("bad.sdl", "sphere frobnicate\n") + " --out " + path("x"));
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("bad.sdl:1:8"), std::string::npos) << bad.output;
    EXPECT_EQ(test::vkray("report").status, 1);
}

}  // namespace
}  // namespace vkray::numerics
