// The stress suite's outputs: rows of ModeMetrics as a Report (table, CSV,
// JSON, HTML with one error-against-time plot per case, a point per mode).
#pragma once

#include "numerics/report_writer.h"
#include "numerics/stress_suite.h"

#include <string>
#include <vector>

namespace vkray::numerics {

// One line per mode with rows that did not run: "not run: fp64 on 3 of 18
// cases: the device has no shaderFloat64" (empty when every row ran).
std::vector<std::string> notRunSummary(const std::vector<ModeMetrics>& rows, std::size_t caseCount);

// `command` is the command line that produced the rows (shown in the page).
Report stressReport(const std::vector<ModeMetrics>& rows, const std::vector<StressCase>& cases,
                    const std::string& command, const std::string& device);

}  // namespace vkray::numerics
