// The one exception type of vkray's library code. Library code throws; only
// host/app prints and chooses the exit code (pbrt-v4 / Mitsuba style).
#pragma once

#include <stdexcept>
#include <string>

namespace vkray {

// An error the user can act on: bad input, a missing file, no device. The
// message is complete (place, what went wrong, what to do).
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vkray
