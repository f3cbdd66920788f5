#include "app/view_events.h"

#include "util/error.h"
#include "util/files.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace vkray {

namespace {

struct Word {
    std::string text;
    int column = 0;  // 1-based
};

std::vector<Word> wordsOf(const std::string& line) {
    std::vector<Word> words;
    for (size_t i = 0; i < line.size();) {
        if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
            ++i;
            continue;
        }
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        words.push_back({line.substr(start, i - start), int(start) + 1});
    }
    return words;
}

}  // namespace

std::vector<ViewEvent> parseViewEvents(const std::string& text, const std::string& path) {
    static const std::set<std::string> keys{"r", "p", "1", "2", "3",  "4",
                                            "c", "d", "s", "q", "esc"};
    std::vector<ViewEvent> events;
    std::istringstream in(text);
    int lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        const std::vector<Word> words = wordsOf(line);
        if (words.empty() || words[0].text[0] == '#') continue;
        const auto fail = [&](const Word& at, const std::string& message) {
            throw Error(path + ":" + std::to_string(lineNumber) + ":" + std::to_string(at.column) +
                        ": error: " + message);
        };
        const auto number = [&](size_t i) {
            if (i >= words.size())
                fail(words.back(), "'" + words[0].text + "' expects more numbers");
            double value = 0;
            const std::string& w = words[i].text;
            const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
            if (ec != std::errc() || end != w.data() + w.size() || !std::isfinite(value))
                fail(words[i], "'" + w + "' is not a number");
            return value;
        };
        const auto expectWords = [&](size_t count, const char* usage) {
            if (words.size() > count)
                fail(words[count], std::string("too much on the line; expected `") + usage + "`");
            if (words.size() < count)
                fail(words.back(), std::string("too little on the line; expected `") + usage + "`");
        };
        ViewEvent e;
        const std::string& verb = words[0].text;
        if (verb == "key") {
            expectWords(2, "key r|p|1|2|3|4|c|d|s|q|esc");
            e.kind = ViewEvent::Kind::Key;
            e.key = words[1].text;
            if (!keys.count(e.key))
                fail(words[1],
                     "'" + e.key + "' is not a key the view knows (r p 1 2 3 4 c d s q esc)");
        } else if (verb == "drag") {
            expectWords(4, "drag left|right DX DY");
            e.kind = ViewEvent::Kind::Drag;
            if (words[1].text != "left" && words[1].text != "right")
                fail(words[1],
                     "the button is 'left' (orbit) or 'right' (pan), not '" + words[1].text + "'");
            e.rightButton = words[1].text == "right";
            e.dx = number(2);
            e.dy = number(3);
        } else if (verb == "wheel") {
            expectWords(2, "wheel N");
            e.kind = ViewEvent::Kind::Wheel;
            e.steps = number(1);
        } else if (verb == "wait-pass" || verb == "wait-cpu" || verb == "wait-reload") {
            expectWords(1, verb.c_str());
            e.kind = verb == "wait-pass"  ? ViewEvent::Kind::WaitPass
                     : verb == "wait-cpu" ? ViewEvent::Kind::WaitCpu
                                          : ViewEvent::Kind::WaitReload;
        } else {
            fail(words[0], "unknown event '" + verb +
                               "' (key, drag, wheel, wait-pass, wait-cpu, wait-reload)");
        }
        events.push_back(e);
    }
    return events;
}

std::vector<ViewEvent> readViewEvents(const std::string& path) {
    const std::optional<std::string> text = readFileIfPresent(path);
    if (!text) throw Error("--events " + path + ": cannot read the file");
    return parseViewEvents(*text, path);
}

}  // namespace vkray
