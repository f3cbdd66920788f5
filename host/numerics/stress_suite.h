// The stress suite: every scene of scenes/stress/ rendered in each precision
// mode and compared pixel by pixel with the float128 oracle (oracle.h).
//
// Metrics, per case and mode (docs/numerics.md says how to read them):
//   set aside    pixels whose footprint straddles an edge (oracle.h), of the
//                pixels beside an id change; left out of every other metric
//   flips        other pixels where the mode and the oracle disagree on hit
//                against miss
//   wrong id     other pixels where both hit, but different objects
//   t err        over the pixels where both hit the same object: the raw
//                relative error |t - t*| / t*, max and RMS; t cond, t
//                world: the largest conditions there (oracle.h,
//                Conditioning); t err / allowance: the largest ratio of the
//                error to the mode's allowance at the pixel, u t + u_double
//                tWorld (tWorld only as written), which the verdict holds to
//                kTAllowanceMultiple
//   normal err   the same for the normal's angle, radians
//   acne, shadow flips, exit errors
//                the shader's own secondary rays (its stress output) against
//                the oracle's exact ones (numerics/secondary_check.h)
//   oracle bound the largest certified bound of the oracle's t, relative
#pragma once

#include "gpu/precision.h"
#include "image/stress_sample.h"
#include "numerics/oracle.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace vkray::gpu {
class Context;
}

namespace vkray::numerics {

// A scene of scenes/stress/ with its header (SDL comments):
//   ! stress: TITLE
//   ! stiff: what makes it hard         (a key's text may go on over
//   ! correct: the right answer          following "!   ..." lines)
//   ! naive: fails | passes             (fails: built to break naive mode)
struct StressCase {
    std::string name;  // file stem
    std::string path;
    std::string title, stiff, correct;
    bool naiveFails = false;
};

StressCase readStressCase(const std::string& path);

// Whether a case's name (its file's stem) is selected by `pattern`: a glob
// (fnmatch: *, ?, [...]) when it holds one of those, as in ctest and gtest,
// else a substring of the name. "" selects every case.
bool caseNameMatches(const std::string& name, const std::string& pattern);

// The cases of `directory` that `pattern` selects (caseNameMatches), sorted
// by name. Throws Error when none matches.
std::vector<StressCase> findStressCases(const std::string& directory, const std::string& pattern);

// The modes a row can be: the three GPU precisions and the CPU reference.
inline constexpr const char* kCpuDoubleMode = "double";

struct ModeMetrics {
    std::string caseName;
    std::string mode;  // naive, robust, fp64, double
    bool ran = false;
    std::string note;    // why it did not run
    double seconds = 0;  // render time (GPU dispatches; CPU tracing)
    std::size_t pixels = 0, setAside = 0, besideEdges = 0, compared = 0;
    std::size_t flips = 0, wrongId = 0;
    double tErrMax = 0, tErrRms = 0, tConditionMax = 0, tWorldMax = 0, tRatioMax = 0;
    double normalErrMax = 0, normalErrRms = 0, normalConditionMax = 0, normalWorldMax = 0,
           normalRatioMax = 0;
    double oracleBound = 0;
    std::size_t feelers = 0, acne = 0;  // feelers: pixels with a feeler compared
    std::size_t shadowFlips = 0, shadowEdges = 0;
    std::size_t refracted = 0, exitErrors = 0;
    // Pixels where `render`'s own variant (primary cover, feeler hints and
    // world-space triangles on) shows another object, depth (beyond 1e-5 of
    // it), normal (1e-4) or colour (1e-4) than the stress-output variant the
    // numbers come from: 0, or the numbers do not speak for what ships.
    std::size_t shippedDiffer = 0;
};

// The bounds a mode must meet on a case to pass it: no flips, no wrong ids,
// no acne, no shadow flips, no exit errors, render's own variant drawing the
// same pixels (shippedDiffer 0), and at every compared pixel
//   |t - t*| / t* <= kTAllowanceMultiple (u t + u_double tWorld),
//   angle(n, n*) <= kNormalAllowanceMultiple (u normal + u_double normalWorld),
// with u the mode's unit roundoff (2^-24 for naive and robust, 2^-53 for
// fp64 and the CPU reference), the conditions of oracle.h, and the world
// terms only for the CPU reference, which works in the world's coordinates
// as written (naive does too, but in float: it is held to robust's bound,
// not forgiven its choice). The multiple stands for the roundings a
// renderer makes on the way, beyond the few per quantity the conditions
// count: 8, which the worst pixel of any robust, fp64 or double row leaves
// at least 4 times over (docs/numerics.md), and which a t off by a
// thousand ulps exceeds wherever a pixel's condition is below 125.
inline constexpr double kTAllowanceMultiple = 8;
inline constexpr double kNormalAllowanceMultiple = 8;
bool withinBounds(const ModeMetrics& metrics);

// The arithmetic a mode works in (oracle.h): float (naive, robust), double
// (fp64), double as written (the CPU reference).
Arithmetic arithmeticOf(const std::string& mode);

// What one pixel of a mode is, against the oracle, in arithmetic `a`: the
// metrics' categories.
enum class PixelVerdict { SetAside, Flip, WrongId, BothMiss, Compared };
PixelVerdict classifyPixel(const OraclePixel& oracle, const StressSample& sample, Arithmetic a);

// The metrics of one mode's primary hits against the oracle, in arithmetic `a`.
ModeMetrics compareWithOracle(const std::vector<OraclePixel>& oracle,
                              const std::vector<StressSample>& samples, Arithmetic a);

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

// The double CPU reference's primary hits (t in double), one per pixel.
std::vector<StressSample> referenceSamples(const Scene& scene, const CameraBasis& camera,
                                           const RenderSettings& settings, int threads);

struct StressPicture;  // numerics/stress_pictures.h

// Runs one case in every mode; `log` (may be null) gets a line per mode,
// `picture` (may be null) the case's pictures for the report.
std::vector<ModeMetrics> runStressCase(const StressCase& stressCase, gpu::Context* context,
                                       const StressOptions& options, std::ostream* log,
                                       StressPicture* picture = nullptr);

}  // namespace vkray::numerics
