// Every case of scenes/stress/ at a reduced size (80x60; docs/numerics.md
// has the full-size figures): robust mode, fp64 and the double CPU reference
// meet the stated bounds (stress_suite.h: no flips outside the set-aside, no
// wrong ids, no acne, shadow flips or exit errors, t and normal errors
// within 8 u times each pixel's condition), naive mode fails exactly the
// cases built to break it; and every bound fails on deliberately broken
// input.
#include "numerics/stress_suite.h"
#include "gpu/shader_variant.h"
#include "numerics/document_check.h"
#include "numerics/secondary_check.h"
#include "numerics/stress_report.h"
#include "support/gpu_fixture.h"
#include "support/temp_folder.h"
#include "util/error.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

namespace vkray::numerics {
namespace {

namespace fs = std::filesystem;

const std::string kCasesDir = test::kSourceDir + "/scenes/stress";

std::string describe(const ModeMetrics& m) {
    char text[360];
    std::snprintf(text, sizeof text,
                  "%s %s: set aside %zu of %zu beside edges, flips %zu wrong id %zu t err %.2e "
                  "(%.2f u cond) normal err %.2e (%.2f u cond) acne %zu/%zu shadow flips %zu "
                  "exit errors %zu/%zu oracle bound %.1e shipped variant differs on %zu",
                  m.caseName.c_str(), m.mode.c_str(), m.setAside, m.besideEdges, m.flips, m.wrongId,
                  m.tErrMax, m.tRatioMax, m.normalErrMax, m.normalRatioMax, m.acne, m.feelers,
                  m.shadowFlips, m.exitErrors, m.refracted, m.oracleBound, m.shippedDiffer);
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
    const std::vector<ModeMetrics> rows =
        runStressCase(stressCase, &test::gpuContext(), options, nullptr);
    const bool castsShadows = gpu::featuresOf(loadScene(stressCase.path, {}, nullptr), {}, false)
                                  .has(gpu::Shading::Shadows);
    ASSERT_EQ(rows.size(), 4u);
    for (const ModeMetrics& m : rows) {
        std::cout << describe(m) << "\n";
        ASSERT_TRUE(m.ran) << m.note;
        EXPECT_EQ(m.pixels, 80u * 60u);
        // The numbers speak for what `render` ships: its own variant draws
        // the same pixels as the stress-output variant they come from.
        if (m.mode != "double") EXPECT_EQ(m.shippedDiffer, 0u) << describe(m);
        // Only pixels beside an edge are ever set aside.
        EXPECT_LE(m.setAside, m.besideEdges) << describe(m);
        if (m.mode == "naive")
            EXPECT_EQ(withinBounds(m), !stressCase.naiveFails)
                << (stressCase.naiveFails ? "not stiff enough for naive: " : "naive fails: ")
                << describe(m);
        else
            EXPECT_TRUE(withinBounds(m)) << describe(m);
        // The variant traces feelers wherever one can meet an object (not on a lone plane).
        if ((m.mode == "robust" || m.mode == "fp64") && castsShadows) {
            EXPECT_GT(m.feelers, 0u) << "no shadow feeler was compared";
        }
        // The oracle's own certified bound is far below any renderer's error.
        if (m.compared > 0) {
            EXPECT_LT(m.oracleBound, 1e-20) << describe(m);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, StressCaseTest, ::testing::ValuesIn(caseNames()),
                         [](const auto& info) { return info.param; });

// One case's oracle and the stress output of a mode, at 40x30, for the
// broken-input tests below.
struct CaseRun {
    Scene scene;
    CameraBasis camera;
    RenderSettings settings{40, 30, 1};
    std::vector<OraclePixel> oracle;

    explicit CaseRun(const std::string& name)
        : scene(loadScene(kCasesDir + "/" + name + ".sdl", {}, nullptr)),
          camera(makeCameraBasis(*scene.camera, 40, 30)),
          oracle(renderOracle(scene, camera, settings, 2)) {}

    std::vector<StressSample> samples(Precision precision) const {
        if (precision == Precision::Naive) throw Error("naive: not broken on purpose");
        gpu::GpuTracer tracer(test::gpuContext(),
                              {.shaderDirectory = test::kShaderDir, .precision = precision});
        std::vector<StressSample> out;
        tracer.renderStressOutput(scene, camera, settings, out);
        return out;
    }
    ModeMetrics metrics(const std::vector<StressSample>& samples, Arithmetic a) const {
        ModeMetrics m = compareWithOracle(oracle, samples, a);
        // Robust's origin footprint for float, fp64's for double (the CPU
        // reference records no secondary rays).
        const OriginFootprint footprint =
            originFootprintOf(a == kFloat ? Precision::Robust : Precision::Fp64);
        const SecondaryStats s =
            checkSecondaryRays(scene, camera, oracle, samples, a, footprint, 2);
        m.feelers = s.feelerPixels;
        m.acne = s.acne;
        m.shadowFlips = s.shadowFlips;
        m.exitErrors = s.exitErrors;
        m.refracted = s.refracted;
        return m;
    }
};

// Robust and fp64 on the GPU, and the double CPU reference, each with its arithmetic.
struct Renderer {
    const char* name;
    Arithmetic arithmetic;
    std::vector<StressSample> (*samples)(const CaseRun&);
};
const Renderer kRenderers[] = {
    {"robust", kFloat, [](const CaseRun& c) { return c.samples(Precision::Robust); }},
    {"fp64", kDouble, [](const CaseRun& c) { return c.samples(Precision::Fp64); }},
    {"double", kDoubleAsWritten,
     [](const CaseRun& c) { return referenceSamples(c.scene, c.camera, c.settings, 2); }},
};

// A pixel both hit, away from every edge (and, with `feeler`, whose feeler
// toward light 0 was traced).
size_t comparedPixel(const CaseRun& run, const std::vector<StressSample>& samples, Arithmetic a,
                     bool feeler) {
    for (size_t i = 0; i < samples.size(); ++i)
        if (!run.oracle[i].setAside[a] && !run.oracle[i].besideEdge && run.oracle[i].hit.id >= 0 &&
            samples[i].object == run.oracle[i].hit.id && (!feeler || samples[i].feelerTraced(0)))
            return i;
    throw Error("no pixel to break");
}

TEST(StressBounds, ATOffByAThousandUlpsFails) {
    // The same render with every t moved by 1000 ulps of its arithmetic:
    // beyond 8 u times the condition wherever that is below 125. Near the
    // origin for the CPU reference, which is allowed the rounding of far
    // world coordinates; anywhere for the rebased modes.
    const std::pair<const char*, std::vector<const char*>> cases[] = {
        {"robust", {"eye_inside", "thin_torus", "far_cluster", "huge_sphere"}},
        {"fp64", {"eye_inside", "thin_torus", "far_cluster", "huge_sphere"}},
        {"double", {"thin_torus", "anisotropy", "grazing_silhouette"}},
    };
    for (const auto& [renderer, names] : cases) {
        const Renderer& r =
            *std::find_if(std::begin(kRenderers), std::end(kRenderers),
                          [&](const Renderer& x) { return std::string(x.name) == renderer; });
        for (const char* name : names) {
            SCOPED_TRACE(std::string(name) + " " + r.name);
            const CaseRun run(name);
            std::vector<StressSample> samples = r.samples(run);
            EXPECT_TRUE(withinBounds(run.metrics(samples, r.arithmetic))) << "unbroken";
            for (StressSample& s : samples) s.t *= 1 + 1000 * kUnitRoundoff[r.arithmetic];
            const ModeMetrics broken = run.metrics(samples, r.arithmetic);
            EXPECT_GT(broken.tRatioMax, kTAllowanceMultiple) << describe(broken);
            EXPECT_FALSE(withinBounds(broken));
        }
    }
}

TEST(StressBounds, ANormalTurnedByAThousandUlpsFailsOnAPlane) {
    // A plane's normal is exact in generic space (its condition is J = sqrt 3
    // for a rotated plane): a normal 1000 u off is 577 times that.
    const CaseRun run("grazing_plane");
    for (const Renderer& r : kRenderers) {
        SCOPED_TRACE(r.name);
        std::vector<StressSample> samples = r.samples(run);
        for (StressSample& s : samples) {
            const glm::dvec3 side = glm::normalize(glm::cross(s.normal, glm::dvec3(0.6, 0, 0.8)));
            s.normal = glm::normalize(s.normal + 1000 * kUnitRoundoff[r.arithmetic] * side);
        }
        const ModeMetrics broken = run.metrics(samples, r.arithmetic);
        EXPECT_GT(broken.normalRatioMax, kNormalAllowanceMultiple) << describe(broken);
        EXPECT_FALSE(withinBounds(broken));
    }
}

TEST(StressBounds, OneFlipOrWrongIdAwayFromAnEdgeFails) {
    const CaseRun run("far_cluster");
    for (const Renderer& r : kRenderers) {
        SCOPED_TRACE(r.name);
        const std::vector<StressSample> samples = r.samples(run);
        ASSERT_TRUE(withinBounds(run.metrics(samples, r.arithmetic)));
        const size_t i = comparedPixel(run, samples, r.arithmetic, false);
        std::vector<StressSample> flipped = samples;
        flipped[i].object = -1;
        flipped[i].t = std::numeric_limits<double>::infinity();
        EXPECT_EQ(run.metrics(flipped, r.arithmetic).flips, 1u);
        EXPECT_FALSE(withinBounds(run.metrics(flipped, r.arithmetic)));
        std::vector<StressSample> other = samples;
        other[i].object = (other[i].object + 1) % int(run.scene.objects.size());
        EXPECT_EQ(run.metrics(other, r.arithmetic).wrongId, 1u);
        EXPECT_FALSE(withinBounds(run.metrics(other, r.arithmetic)));
    }
}

TEST(StressBounds, AFeelerVerdictTurnedFails) {
    // A clear feeler reported blocked, or a blocked one clear: a shadow flip.
    const CaseRun run("far_cluster");
    const std::vector<StressSample> samples = run.samples(Precision::Robust);
    std::vector<StressSample> broken = samples;
    const size_t i = comparedPixel(run, samples, kFloat, true);
    broken[i].feelersMet ^= 1u;
    const ModeMetrics m = run.metrics(broken, kFloat);
    EXPECT_EQ(m.shadowFlips, 1u);
    EXPECT_FALSE(withinBounds(m));
    // Reported met by the object it left, where the exact feeler is clear: acne.
    broken = samples;
    for (size_t k = 0; k < samples.size(); ++k) {
        if (!samples[k].feelerTraced(0) || samples[k].feelerMet(0)) continue;
        broken[k].feelersMet |= 1u;
        broken[k].feelersMetLeft |= 1u;
        break;
    }
    EXPECT_GE(run.metrics(broken, kFloat).acne, 1u);
}

TEST(StressBounds, WithoutTheOffsetAcneAndExitErrorsAreCounted) {
    // VKRAY_FAULT=no-offset: the shader's secondary rays start on their surface.
    for (const char* name : {"acne_large_sphere", "refraction_exit"}) {
        const CaseRun run(name);
        for (Precision precision : {Precision::Robust, Precision::Fp64}) {
            SCOPED_TRACE(std::string(name) + " " + precisionName(precision));
            const Arithmetic a = precision == Precision::Fp64 ? kDouble : kFloat;
            const ModeMetrics good = run.metrics(run.samples(precision), a);
            EXPECT_TRUE(withinBounds(good)) << describe(good);
            setenv("VKRAY_FAULT", "no-offset", 1);
            const ModeMetrics broken = run.metrics(run.samples(precision), a);
            unsetenv("VKRAY_FAULT");
            EXPECT_FALSE(withinBounds(broken)) << describe(broken);
            const size_t failures =
                std::string(name) == "acne_large_sphere" ? broken.acne : broken.exitErrors;
            EXPECT_GT(failures, 0u) << describe(broken);
        }
    }
}

TEST(StressSuite, HasTheCasesTheIssueAsksFor) {
    const std::vector<StressCase> cases = findStressCases(kCasesDir, "");
    EXPECT_GE(cases.size(), 22u);
    for (const StressCase& c : cases) {
        EXPECT_FALSE(c.stiff.empty()) << c.name;
        EXPECT_FALSE(c.correct.empty()) << c.name;
    }
    // The stiff cases a shared blind spot of shader and oracle would hide.
    for (const char* name :
         {"torus_tangent", "torus_hole", "sphere_tangent_1e5", "cube_edge_on_1e5"})
        EXPECT_EQ(findStressCases(kCasesDir, name).size(), 1u) << name;
    EXPECT_EQ(findStressCases(kCasesDir, "torus").size(), 3u);
    EXPECT_THROW(findStressCases(kCasesDir, "no-such-case"), Error);
    EXPECT_THROW(findStressCases(kCasesDir + "/missing", ""), Error);
}

// --cases takes globs as ctest and gtest do, and plain parts of names as before.
TEST(StressSuite, CasesAreSelectedByGlobOrByPartOfTheName) {
    EXPECT_TRUE(caseNameMatches("tiny_sphere", ""));
    EXPECT_TRUE(caseNameMatches("tiny_sphere", "*"));
    EXPECT_TRUE(caseNameMatches("tiny_sphere", "tiny*"));
    EXPECT_TRUE(caseNameMatches("tiny_sphere", "*_sphere"));
    EXPECT_TRUE(caseNameMatches("tiny_sphere", "tiny_spher?"));
    EXPECT_TRUE(caseNameMatches("tiny_sphere", "[st]iny*"));
    EXPECT_TRUE(caseNameMatches("tiny_sphere", "sphere"));    // a part of the name
    EXPECT_FALSE(caseNameMatches("tiny_sphere", "sphere*"));  // a glob matches the whole name
    EXPECT_FALSE(caseNameMatches("tiny_sphere", "huge"));
    EXPECT_EQ(findStressCases(kCasesDir, "tiny*").size(), 1u);
    EXPECT_EQ(findStressCases(kCasesDir, "torus_*").size(), 2u);  // not thin_torus
    EXPECT_EQ(findStressCases(kCasesDir, "*_1e5").size(), 2u);
    EXPECT_EQ(findStressCases(kCasesDir, "tiny").size(), 1u);
    EXPECT_THROW(findStressCases(kCasesDir, "tiny?"), Error);
}

class StressHeader : public ::testing::Test {
protected:
    std::string write(const std::string& text) {
        const fs::path p = scratch_.path() / "header.sdl";
        std::ofstream(p) << text;
        return p.string();
    }
    test::TempFolder scratch_{"vkray-stress-header"};
};

TEST_F(StressHeader, ReadsKeysAndContinuations) {
    const StressCase c = readStressCase(
        write("! stress: title\n! stiff: first\n!   second\n! correct: t = 1\n! naive: fails\n"
              "sphere\n! stress: not part of the header\n"));
    EXPECT_EQ(c.title, "title");
    EXPECT_EQ(c.stiff, "first second");
    EXPECT_EQ(c.correct, "t = 1");
    EXPECT_TRUE(c.naiveFails);
}

TEST_F(StressHeader, RejectsMissingKeysAndBadValues) {
    EXPECT_THROW(readStressCase(write("! stress: t\nsphere\n")), Error);
    try {
        readStressCase(write("! stress: t\n! stiff: s\n! correct: c\n! naive: maybe\n"));
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(".sdl:4: 'naive:' takes fails or passes"),
                  std::string::npos)
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

    const nlohmann::json json = nlohmann::json::parse(toJson(report));
    ASSERT_EQ(json.at("rows").size(), rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
        const nlohmann::json& row = json.at("rows").at(i);
        EXPECT_EQ(row.at("case"), rows[i].caseName);
        EXPECT_EQ(row.at("mode"), rows[i].mode);
        if (rows[i].ran) {
            EXPECT_TRUE(row.at("flips").is_number());
            EXPECT_EQ(row.at("flips").get<double>(), double(rows[i].flips));
        } else {
            EXPECT_TRUE(row.at("flips").is_null());
            EXPECT_EQ(row.at("note"), "the device has no shaderFloat64");
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
    for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
        ++svgs;
    EXPECT_EQ(svgs, cases.size());
    EXPECT_NE(html.find("far_sphere_silhouette"), std::string::npos);
}

}  // namespace
}  // namespace vkray::numerics
