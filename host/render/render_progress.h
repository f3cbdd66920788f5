// How a renderer reports progress and learns that it should stop: both
// renderers (GPU tiles, CPU reference rows) call a RenderProgress, and the
// command line turns it into the progress display and Ctrl-C.
#pragma once

#include <cstddef>
#include <exception>
#include <functional>

namespace vkray {

// Called once before the first ray and after each piece of work (a GPU tile,
// a CPU row of blocks) with the primary rays traced so far and in all. The
// CPU reference calls it from its worker threads, so it must be thread-safe.
// Returning false stops the render between pieces: the renderer throws
// Interrupted.
using RenderProgress = std::function<bool(std::size_t raysDone, std::size_t raysTotal)>;

// A render stopped on request (Ctrl-C, SIGTERM). Not an Error: nothing is
// wrong with the input; vkray writes nothing, prints "interrupted", exits 130.
class Interrupted : public std::exception {
public:
    const char* what() const noexcept override { return "interrupted"; }
};

}  // namespace vkray
