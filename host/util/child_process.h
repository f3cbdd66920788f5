// Work done in a child process under a time limit: for third-party code
// that may loop or crash on hostile input (Assimp reading a mesh file), so
// that vkray refuses the input instead of hanging or dying with it.
#pragma once

#include <functional>
#include <string>

namespace vkray {

// Runs `work` in a forked child and returns the bytes it returned. The child
// shares nothing with the caller afterwards: what it computes comes back
// only as those bytes. Throws Error with `what` in front ("PATH: error:
// reading it took ...") when the child does not finish within `seconds`
// (it is killed), when it dies by a signal, or when `work` throws: then the
// error's message is the child's.
std::string runInChild(const std::function<std::string()>& work, double seconds,
                       const std::string& what);

}  // namespace vkray
