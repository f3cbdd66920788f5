// Every case of scenes/stress/ at a reduced size (80x60; docs/numerics.md
// has the full-size figures): robust mode, fp64 and the double CPU reference
// meet the stated bounds (stress_suite.h: no flips outside the silhouette
// band, no wrong ids, no acne, t and normal errors within 1e-5 in float;
// within 1e-7 (t) and 1e-6 (normal) for fp64 and for the double reference),
// and naive mode fails exactly the cases built to break it.
#include "numerics/stress_report.h"
#include "numerics/stress_suite.h"
#include "scene/error.h"
#include "support/gpu_fixture.h"
#include "numerics/document_check.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

namespace vkray::numerics {
namespace {

namespace fs = std::filesystem;

const std::string kCasesDir = test::kSourceDir + "/scenes/stress";

std::string describe(const ModeMetrics& m) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "%s %s: silhouette %zu flips %zu wrong id %zu t err %.2e normal err %.2e acne %zu/%zu",
                  m.caseName.c_str(), m.mode.c_str(), m.silhouette, m.flips, m.wrongId, m.tErrMax,
                  m.normalErrMax, m.acne, m.feelers);
    return text;
}

std::vector<std::string> caseNames() {
    std::vector<std::string> names;
    for (const StressCase& c : findStressCases(kCasesDir, "")) names.push_back(c.name);
    return names;
}

class StressCaseTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StressCaseTest, RobustFp64AndDoublePassNaiveFailsWhereBuiltTo) {
    const StressCase stressCase = readStressCase(kCasesDir + "/" + GetParam() + ".sdl");
    StressOptions options;
    options.width = 80;
    options.height = 60;
    options.shaderDirectory = test::kShaderDir;
    options.threads = 2;
    options.gpuModes = {Precision::Naive, Precision::Robust, Precision::Fp64};
    const std::vector<ModeMetrics> rows = runStressCase(stressCase, &test::gpuContext(), options, nullptr);
    ASSERT_EQ(rows.size(), 4u);
    for (const ModeMetrics& m : rows) {
        std::cout << describe(m) << "\n";
        ASSERT_TRUE(m.ran) << m.note;
        EXPECT_EQ(m.pixels, 80u * 60u);
        // The band must leave most of the image to compare.
        EXPECT_LT(m.silhouette, m.pixels / 4) << describe(m);
        if (m.mode == "naive")
            EXPECT_EQ(withinBounds(m), !stressCase.naiveFails)
                << (stressCase.naiveFails ? "not stiff enough for naive: " : "naive fails: ") << describe(m);
        else
            EXPECT_TRUE(withinBounds(m)) << describe(m);
        if (m.mode == "robust" || m.mode == "fp64") {
            EXPECT_GT(m.feelers, 0u) << "no secondary ray was replayed";
            EXPECT_LE(m.tErrMax, m.mode == "fp64" ? kFp64TErrorBound : kFloatTErrorBound);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, StressCaseTest, ::testing::ValuesIn(caseNames()),
                         [](const auto& info) { return info.param; });

TEST(StressSuite, HasTheCasesTheIssueAsksFor) {
    const std::vector<StressCase> cases = findStressCases(kCasesDir, "");
    EXPECT_GE(cases.size(), 14u);
    for (const StressCase& c : cases) {
        EXPECT_FALSE(c.stiff.empty()) << c.name;
        EXPECT_FALSE(c.correct.empty()) << c.name;
    }
    EXPECT_EQ(findStressCases(kCasesDir, "torus").size(), 1u);
    EXPECT_THROW(findStressCases(kCasesDir, "no-such-case"), Error);
    EXPECT_THROW(findStressCases(kCasesDir + "/missing", ""), Error);
}

class StressHeader : public ::testing::Test {
protected:
    std::string write(const std::string& text) {
        const fs::path p = fs::path(::testing::TempDir()) / "vkray-stress-header.sdl";
        std::ofstream(p) << text;
        return p.string();
    }
};

TEST_F(StressHeader, ReadsKeysAndContinuations) {
    const StressCase c = readStressCase(write(
        "! stress: title\n! stiff: first\n!   second\n! correct: t = 1\n! naive: fails\n"
        "! secondary: refraction\nsphere\n! stress: not part of the header\n"));
    EXPECT_EQ(c.title, "title");
    EXPECT_EQ(c.stiff, "first second");
    EXPECT_EQ(c.correct, "t = 1");
    EXPECT_TRUE(c.naiveFails);
    EXPECT_TRUE(c.refraction);
}

TEST_F(StressHeader, RejectsMissingKeysAndBadValues) {
    EXPECT_THROW(readStressCase(write("! stress: t\nsphere\n")), Error);
    try {
        readStressCase(write("! stress: t\n! stiff: s\n! correct: c\n! naive: maybe\n"));
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(".sdl:4: 'naive:' takes fails or passes"), std::string::npos)
            << e.what();
    }
}

TEST(StressReport, OneRowPerCaseAndModeInCsvJsonAndHtml) {
    const std::vector<StressCase> cases = findStressCases(kCasesDir, "sphere");
    ASSERT_GE(cases.size(), 2u);
    StressOptions options;
    options.width = 24;
    options.height = 18;
    options.shaderDirectory = test::kShaderDir;
    std::vector<ModeMetrics> rows;
    for (const StressCase& c : cases) {
        const auto caseRows = runStressCase(c, &test::gpuContext(), options, nullptr);
        rows.insert(rows.end(), caseRows.begin(), caseRows.end());
    }
    ASSERT_EQ(rows.size(), cases.size() * 4);  // naive, robust, fp64, double
    // A row that could not run (fp64 on a device without doubles) is a row too.
    ModeMetrics notRun;
    notRun.caseName = cases[0].name;
    notRun.mode = "fp64";
    notRun.note = "the device has no shaderFloat64";
    rows.push_back(notRun);
    const Report report = stressReport(rows, cases, "vkray stress --size 24x18", "test device");

    const auto csv = test::parseCsv(toCsv(report.table));
    ASSERT_EQ(csv.size(), rows.size() + 1);
    EXPECT_EQ(csv[0][0], "case");
    EXPECT_EQ(csv[0][1], "mode");
    for (size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(csv[i + 1].size(), csv[0].size());
        EXPECT_EQ(csv[i + 1][0], rows[i].caseName);
        EXPECT_EQ(csv[i + 1][1], rows[i].mode);
    }

    const test::Json json = test::JsonReader(toJson(report)).document();
    ASSERT_EQ(json["rows"].items.size(), rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
        const test::Json& row = json["rows"].items[i];
        EXPECT_EQ(row["case"].text, rows[i].caseName);
        EXPECT_EQ(row["mode"].text, rows[i].mode);
        if (rows[i].ran) {
            EXPECT_EQ(row["flips"].kind, test::Json::Number);
            EXPECT_EQ(row["flips"].number, double(rows[i].flips));
        } else {
            EXPECT_EQ(row["flips"].kind, test::Json::Null);
            EXPECT_EQ(row["note"].text, "the device has no shaderFloat64");
        }
    }

    const std::string html = toHtml(report);
    EXPECT_EQ(test::xmlProblem(html), "");
    // Self-contained: no scripts, nothing fetched from another file or the network.
    for (const char* outside : {"<script", "src=", "<link", "url("})
        EXPECT_EQ(html.find(outside), std::string::npos) << outside;
    std::string withoutNamespaces = html;
    const std::string svgNamespace = "xmlns=\"http://www.w3.org/2000/svg\"";
    for (size_t at; (at = withoutNamespaces.find(svgNamespace)) != std::string::npos;)
        withoutNamespaces.erase(at, svgNamespace.size());
    EXPECT_EQ(withoutNamespaces.find("http"), std::string::npos);
    size_t svgs = 0;
    for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++svgs;
    EXPECT_EQ(svgs, cases.size());
    EXPECT_NE(html.find("far_sphere_silhouette"), std::string::npos);
}

}  // namespace
}  // namespace vkray::numerics
