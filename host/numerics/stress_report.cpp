#include "numerics/stress_report.h"

#include <algorithm>

namespace vkray::numerics {

std::vector<std::string> notRunSummary(const std::vector<ModeMetrics>& rows, std::size_t caseCount) {
    // Each mode that did not run, with its reasons, in the rows' order.
    std::vector<std::pair<std::string, std::vector<std::string>>> modes;
    std::vector<std::size_t> counts;
    for (const ModeMetrics& m : rows) {
        if (m.ran) continue;
        auto it = std::find_if(modes.begin(), modes.end(), [&](const auto& e) { return e.first == m.mode; });
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
            (cases.size() == 1 ? " stress case" : " stress cases") + " in each precision "
        "mode (naive, robust, fp64 on the GPU; the double CPU reference) against a long-double "
        "oracle, pixel by pixel.",
        "silhouette: pixels whose oracle object changes when the ray turns by 8 units in the last "
        "place of the mode's arithmetic (float for naive and robust, double for fp64 and the "
        "CPU); left out of "
        "the other columns. flips: hit against miss. wrong id: both hit, different objects. "
        "compared: pixels where both hit the same object; over these, t err is the relative "
        "distance error beyond what that turn explains (max and RMS) and normal err: the same for the normal, radians. acne: "
        "pixels whose shadow feelers (or, for refraction cases, refracted exit rays), replayed "
        "on the CPU as the mode's shader makes them (in float, or double for fp64) from the "
        "mode's hit points, hit the surface they start on where the exact ray does not; of: "
        "pixels with a "
        "feeler. time: the fastest of three GPU renders, or the CPU tracing. verdict: pass when "
        "there are no flips, wrong ids or acne and the t and normal errors are at most 1e-5 "
        "(naive, robust), 1e-7 and 1e-6 (fp64, whose t and normal reach the host as float) or "
        "1e-7 and 1e-6 (double); not run when the mode could not run (the note says why), "
        "which is never a pass.",
        "Plots: one per case, a point per mode, x the render time and y the largest relative t "
        "error (0 is drawn below the lowest decade). Lower left is better; the dashed line is the "
        "Pareto front. Hollow red points are modes with flips, wrong ids or acne."};
    report.table.columns = {"case",         "mode",          "time s",      "silhouette",
                            "flips",        "wrong id",      "compared",    "t err max",   "t err rms",
                            "normal err max", "normal err rms", "acne",     "of",
                            "verdict", "naive built to fail", "note"};
    using V = ReportValue;
    for (const ModeMetrics& m : rows) {
        const auto c = std::find_if(cases.begin(), cases.end(),
                                    [&](const StressCase& sc) { return sc.name == m.caseName; });
        const bool naiveFails = c != cases.end() && c->naiveFails;
        const bool feelers = m.ran && m.mode != kCpuDoubleMode;
        const bool compared = m.ran && m.compared > 0;  // errors exist only where both hit one object
        report.table.rows.push_back({
            V::str(m.caseName), V::str(m.mode), m.ran ? V::num(m.seconds) : V{},
            m.ran ? V::whole((long long)m.silhouette) : V{}, m.ran ? V::whole((long long)m.flips) : V{},
            m.ran ? V::whole((long long)m.wrongId) : V{}, m.ran ? V::whole((long long)m.compared) : V{},
            compared ? V::num(m.tErrMax) : V{}, compared ? V::num(m.tErrRms) : V{},
            compared ? V::num(m.normalErrMax) : V{}, compared ? V::num(m.normalErrRms) : V{},
            feelers ? V::whole((long long)m.acne) : V{},
            feelers ? V::whole((long long)m.feelers) : V{},
            V::str(!m.ran ? "not run" : withinBounds(m) ? "pass" : "FAIL"), V::str(naiveFails ? "yes" : "no"),
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
            plot.points.push_back({m.mode, m.seconds, m.tErrMax, m.flips + m.wrongId + m.acne > 0});
        }
        report.plots.push_back(plot);
    }
    return report;
}

}  // namespace vkray::numerics
