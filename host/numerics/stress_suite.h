// The stress suite: every scene of scenes/stress/ rendered in each
// precision mode and compared pixel by pixel with the long-double oracle.
//
// Metrics, per case and mode (docs/numerics.md says how to read them):
//   silhouette   pixels whose oracle id changes within the mode's rounding
//                band (oracle.h); left out of every other metric
//   flips        other pixels where the mode and the oracle disagree on hit
//                against miss
//   wrong id     other pixels where both hit, but different objects
//   t err        over the pixels where both hit the same object: relative
//                distance error beyond what the band explains,
//                max(0, |t - t*| - spread) / t*  (spread: how far t* itself
//                moves within the band); max and RMS
//   normal err   the same for the normal's angle, radians
//   acne         shadow feelers (or refraction exit rays) that hit the
//                surface they start on, replayed on the CPU (numerics/feelers.h)
#pragma once

#include "numerics/oracle.h"
#include "numerics/precision.h"
#include "scene/camera.h"
#include "scene/scene.h"

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace vkray::gpu { class Context; }

namespace vkray::numerics {

// A scene of scenes/stress/ with its header (SDL comments):
//   ! stress: TITLE
//   ! stiff: what makes it hard         (a key's text may go on over
//   ! correct: the right answer          following "!   ..." lines)
//   ! naive: fails | passes             (fails: built to break naive mode)
//   ! secondary: shadow | refraction    (which secondary rays to replay; default shadow)
struct StressCase {
    std::string name;  // file stem
    std::string path;
    std::string title, stiff, correct;
    bool naiveFails = false;
    bool refraction = false;
};

StressCase readStressCase(const std::string& path);

// The cases of `directory` whose name contains `pattern` ("" or "*": all),
// sorted by name. Throws Error when none matches.
std::vector<StressCase> findStressCases(const std::string& directory, const std::string& pattern);

// The modes a row can be: the three GPU precisions and the CPU reference.
inline constexpr const char* kCpuDoubleMode = "double";

struct ModeMetrics {
    std::string caseName;
    std::string mode;  // naive, robust, fp64, double
    bool ran = false;
    std::string note;  // why it did not run
    double seconds = 0;  // render time (GPU dispatches; CPU tracing)
    std::size_t pixels = 0, silhouette = 0, compared = 0;
    std::size_t flips = 0, wrongId = 0;
    double tErrMax = 0, tErrRms = 0;
    double normalErrMax = 0, normalErrRms = 0;
    std::size_t feelers = 0, acne = 0;  // feelers: how many were traced
};

// The bounds a mode must meet on a case to pass it: no flips, no wrong ids,
// no acne, and t and normal errors (beyond the band) within these.
inline constexpr double kFloatTErrorBound = 1e-5;       // relative, float modes
inline constexpr double kFloatNormalErrorBound = 1e-5;  // radians
// The double CPU reference works in world coordinates as written (no
// rebasing): its error grows like u_double |eye| / object size, 2e-9 for a unit
// object 1e7 away, times the conditioning at grazing incidence.
inline constexpr double kDoubleTErrorBound = 1e-7;
inline constexpr double kDoubleNormalErrorBound = 1e-6;
// fp64 works in double on the GPU but returns t and the normal as float:
// their rounding (2^-24 relative) and the float normal transform of shading
// bound its error.
inline constexpr double kFp64TErrorBound = 1e-7;
inline constexpr double kFp64NormalErrorBound = 1e-6;
bool withinBounds(const ModeMetrics& metrics);

// What a renderer gave for one pixel.
struct ModeSample {
    double t;  // +inf on a miss
    glm::dvec3 normal;
    int id;
};

// What one pixel of a mode is, against the oracle, in the rounding band of
// float (band 0) or double (band 1): the metrics' categories.
enum class PixelVerdict { Silhouette, Flip, WrongId, BothMiss, Compared };
PixelVerdict classifyPixel(const OraclePixel& oracle, const ModeSample& sample, int band);

// The metrics of one mode's samples against the oracle, with the rounding
// band of float (band 0) or double (band 1).
ModeMetrics compareWithOracle(const std::vector<OraclePixel>& oracle,
                              const std::vector<ModeSample>& samples, int band);

struct StressOptions {
    int width = 320, height = 240;
    std::string shaderDirectory;
    int threads = 0;  // CPU reference and oracle threads (0: all cores)
    std::vector<Precision> gpuModes{Precision::Naive, Precision::Robust, Precision::Fp64};
    bool cpuDouble = true;
};

// A case's rows as bytes and back, bit for bit: how they travel from the MPI
// rank that ran the case to rank 0 (dist/job_hand_out.h).
std::string encodeRows(const std::vector<ModeMetrics>& rows);
std::vector<ModeMetrics> decodeRows(const std::string& bytes);

struct StressPicture;  // numerics/stress_pictures.h

// Runs one case in every mode; `log` (may be null) gets a line per mode,
// `picture` (may be null) the case's pictures for the report.
std::vector<ModeMetrics> runStressCase(const StressCase& stressCase, gpu::Context* context,
                                       const StressOptions& options, std::ostream* log,
                                       StressPicture* picture = nullptr);

}  // namespace vkray::numerics
