#include "numerics/stress_report.h"

#include <algorithm>

namespace vkray::numerics {

std::vector<std::string> notRunSummary(const std::vector<ModeMetrics>& rows,
                                       std::size_t caseCount) {
    // Each mode that did not run, with its reasons, in the rows' order.
    std::vector<std::pair<std::string, std::vector<std::string>>> modes;
    std::vector<std::size_t> counts;
    for (const ModeMetrics& m : rows) {
        if (m.ran) continue;
        auto it = std::find_if(modes.begin(), modes.end(),
                               [&](const auto& e) { return e.first == m.mode; });
        if (it == modes.end()) {
            modes.push_back({m.mode, {}});
            counts.push_back(0);
            it = modes.end() - 1;
        }
        ++counts[std::size_t(it - modes.begin())];
        const std::string reason = m.note.empty() ? "no reason given" : m.note;
        if (std::find(it->second.begin(), it->second.end(), reason) == it->second.end())
            it->second.push_back(reason);
    }
    std::vector<std::string> lines;
    for (std::size_t i = 0; i < modes.size(); ++i) {
        std::string reasons;
        for (const std::string& r : modes[i].second) reasons += (reasons.empty() ? "" : "; ") + r;
        lines.push_back("not run: " + modes[i].first + " on " + std::to_string(counts[i]) + " of " +
                        std::to_string(caseCount) + (caseCount == 1 ? " case" : " cases") + ": " +
                        reasons);
    }
    return lines;
}

Report stressReport(const std::vector<ModeMetrics>& rows, const std::vector<StressCase>& cases,
                    const std::string& command, const std::string& device) {
    Report report;
    report.title = "vkray stress";
    report.paragraphs = {
        "`" + command + "` on " + device + ". " + std::to_string(cases.size()) +
            (cases.size() == 1 ? " stress case" : " stress cases") +
            " in each precision "
            "mode (naive, robust, fp64 on the GPU; the double CPU reference) against a float128 "
            "oracle with certified error bounds, pixel by pixel.",
        "set aside: pixels whose footprint (8 times the angle the mode's rounding can turn its "
        "ray by) straddles an edge, of those beside an id change; left out of the other "
        "columns. flips: hit against miss. wrong id: both hit, different objects. compared: "
        "pixels where both hit the same object; over these, t err is the raw relative error "
        "|t - t*| / t* (max and RMS), t cond the largest condition number of t from the "
        "pixel's geometry, t world the largest of the term for rounding the world's "
        "coordinates as written in double (allowed the CPU reference only), t err / allowance "
        "the largest ratio of the error to u t cond + u_double t world at its pixel, u the "
        "mode's unit roundoff (2^-24, or 2^-53 for fp64 and double); normal err, normal cond, "
        "normal world, normal err / allowance: the same for the normal's angle, radians. From "
        "the mode's own shader (its stress "
        "output): acne: pixels whose shadow feelers met the object they left where the exact "
        "feeler from the exact point does not; of: pixels with a feeler compared; shadow "
        "flips: feelers whose verdict differs from the exact one, shadow edges: those the "
        "primary hit's own error or the secondary rays' offset explains (set aside); exit errors: "
        "refracted rays that met "
        "their entry surface again or left off the exact exit point, of refracted. The double "
        "CPU reference's secondary rays are not recorded. oracle bound: the largest certified "
        "bound of the oracle's own t, relative. time: the fastest of three GPU renders, or the "
        "CPU tracing. verdict: pass when there are no flips, wrong ids, acne, shadow flips or "
        "exit errors and both ratios are at most " +
            std::to_string(int(kTAllowanceMultiple)) +
            "; not run when the mode could not run (the note says why), which is never a pass.",
        "Plots: one per case, a point per mode, x the render time and y the largest relative t "
        "error (0 is drawn below the lowest decade). Lower left is better; the dashed line is the "
        "Pareto front. Hollow red points are modes with flips, wrong ids or acne."};
    report.table.columns = {"case",
                            "mode",
                            "time s",
                            "set aside",
                            "beside edges",
                            "flips",
                            "wrong id",
                            "compared",
                            "t err max",
                            "t err rms",
                            "t cond max",
                            "t world max",
                            "t err / allowance",
                            "normal err max",
                            "normal err rms",
                            "normal cond max",
                            "normal world max",
                            "normal err / allowance",
                            "acne",
                            "of",
                            "shadow flips",
                            "shadow edges",
                            "exit errors",
                            "refracted",
                            "oracle bound",
                            "verdict",
                            "naive built to fail",
                            "note"};
    using V = ReportValue;
    for (const ModeMetrics& m : rows) {
        const auto c = std::find_if(cases.begin(), cases.end(),
                                    [&](const StressCase& sc) { return sc.name == m.caseName; });
        const bool naiveFails = c != cases.end() && c->naiveFails;
        const bool feelers = m.ran && m.mode != kCpuDoubleMode;
        const bool compared =
            m.ran && m.compared > 0;  // errors exist only where both hit one object
        const auto count = [&](bool shown, std::size_t n) {
            return shown ? V::whole((long long)n) : V{};
        };
        const auto number = [&](double x) { return compared ? V::num(x) : V{}; };
        report.table.rows.push_back({V::str(m.caseName),
                                     V::str(m.mode),
                                     m.ran ? V::num(m.seconds) : V{},
                                     count(m.ran, m.setAside),
                                     count(m.ran, m.besideEdges),
                                     count(m.ran, m.flips),
                                     count(m.ran, m.wrongId),
                                     count(m.ran, m.compared),
                                     number(m.tErrMax),
                                     number(m.tErrRms),
                                     number(m.tConditionMax),
                                     number(m.tWorldMax),
                                     number(m.tRatioMax),
                                     number(m.normalErrMax),
                                     number(m.normalErrRms),
                                     number(m.normalConditionMax),
                                     number(m.normalWorldMax),
                                     number(m.normalRatioMax),
                                     count(feelers, m.acne),
                                     count(feelers, m.feelers),
                                     count(feelers, m.shadowFlips),
                                     count(feelers, m.shadowEdges),
                                     count(feelers, m.exitErrors),
                                     count(feelers, m.refracted),
                                     number(m.oracleBound),
                                     V::str(!m.ran            ? "not run"
                                            : withinBounds(m) ? "pass"
                                                              : "FAIL"),
                                     V::str(naiveFails ? "yes" : "no"),
                                     V::str(m.note)});
    }
    for (const std::string& line : notRunSummary(rows, cases.size()))
        report.paragraphs.push_back(line);
    for (const StressCase& c : cases)
        report.paragraphs.push_back(c.name + ": " + c.title + ". Stiff: " + c.stiff +
                                    " Correct: " + c.correct);
    for (const StressCase& c : cases) {
        Plot plot;
        plot.title = c.name;
        plot.xLabel = "render time (s)";
        plot.yLabel = "max relative t error";
        plot.flaggedMeaning = "flips, wrong ids or acne";
        for (const ModeMetrics& m : rows) {
            if (m.caseName != c.name || !m.ran) continue;
            plot.points.push_back(
                {m.mode, m.seconds, m.tErrMax,
                 m.flips + m.wrongId + m.acne + m.shadowFlips + m.exitErrors > 0});
        }
        report.plots.push_back(plot);
    }
    return report;
}

}  // namespace vkray::numerics
