// The message of the vkray::Error an action throws, for tests that check
// what a user is told; "(no error)" when it throws none.
#pragma once

#include "util/error.h"

#include <functional>
#include <string>

namespace vkray {

inline std::string errorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace vkray
