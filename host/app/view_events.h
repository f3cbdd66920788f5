// What `vkray view` reacts to: keys, drags and the wheel, whether from the
// window or replayed from an --events script, and the script's waits.
#pragma once

#include <string>
#include <vector>

namespace vkray {

struct ViewEvent {
    enum class Kind {
        Key,    // `key C`: a key the window knows (r p 1 2 3 4 c d s q, esc)
        Drag,   // `drag left|right DX DY`: the mouse moved by DX, DY pixels (y down) with a button
                // held
        Wheel,  // `wheel N`: N steps of the wheel (positive: away from the user, zooms in)
        WaitPass,    // `wait-pass`: until the next pass of the progression is finished
        WaitCpu,     // `wait-cpu`: until the CPU reference running is finished
        WaitReload,  // `wait-reload`: until a watched file changes and the view has reloaded
    };
    Kind kind = Kind::Key;
    std::string key;           // Key: "r", "p", "1".."4", "c", "d", "s", "q" or "esc"
    bool rightButton = false;  // Drag: the right button (pan), else the left (orbit)
    double dx = 0, dy = 0;     // Drag
    double steps = 0;          // Wheel
};

// Parses one event a line; blank lines and lines starting with '#' are
// skipped. Throws Error at `path:line:col` for anything else.
std::vector<ViewEvent> parseViewEvents(const std::string& text, const std::string& path);

// Reads and parses the --events file (Error naming it when unreadable).
std::vector<ViewEvent> readViewEvents(const std::string& path);

}  // namespace vkray
