// Small checkers for the report files (their JSON is read with nlohmann-json):
// a CSV splitter, and an XML well-formedness check for the HTML page (it is
// written as XHTML-style markup: every element closed, every attribute quoted).
#pragma once

#include <cctype>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vkray::test {

// Splits CSV text into rows of fields (quoted fields with "" escapes).
inline std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string field;
    bool quoted = false, any = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
                field += '"', ++i;
            else if (c == '"')
                quoted = false;
            else
                field += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            row.push_back(field);
            field.clear();
        } else if (c == '\n') {
            row.push_back(field);
            rows.push_back(row);
            row.clear();
            field.clear();
            any = false;
            continue;
        } else {
            field += c;
        }
        any = true;
    }
    if (any) {
        row.push_back(field);
        rows.push_back(row);
    }
    return rows;
}

// "" when the markup is well formed (after an optional <!DOCTYPE ...>):
// elements nest and close, attributes are quoted, '&' starts an entity and
// text holds no raw '<'. Otherwise what is wrong and where.
inline std::string xmlProblem(const std::string& s) {
    std::vector<std::string> open;
    size_t i = 0;
    if (s.compare(0, 9, "<!DOCTYPE") == 0) i = s.find('>') + 1;
    while (i < s.size()) {
        if (s[i] == '&') {
            const size_t semi = s.find(';', i);
            if (semi == std::string::npos || semi - i > 8) return "bare & at " + std::to_string(i);
            i = semi + 1;
            continue;
        }
        if (s[i] != '<') {
            ++i;
            continue;
        }
        const size_t end = s.find('>', i);
        if (end == std::string::npos) return "unclosed tag at " + std::to_string(i);
        std::string tag = s.substr(i + 1, end - i - 1);
        if (tag.find('<') != std::string::npos) return "'<' inside a tag at " + std::to_string(i);
        size_t quotes = 0;
        for (char c : tag) quotes += c == '"';
        if (quotes % 2) return "unbalanced quotes in <" + tag + ">";
        const bool closing = !tag.empty() && tag[0] == '/';
        const bool selfClosing = !tag.empty() && tag.back() == '/';
        const std::string name =
            tag.substr(closing ? 1 : 0, tag.find_first_of(" /\t\n", 1) - (closing ? 1 : 0));
        if (name.empty()) return "empty tag name at " + std::to_string(i);
        if (closing) {
            if (open.empty() || open.back() != name)
                return "</" + name + "> closes <" + (open.empty() ? "" : open.back()) + "> at " +
                       std::to_string(i);
            open.pop_back();
        } else if (!selfClosing) {
            open.push_back(name);
        }
        i = end + 1;
    }
    return open.empty() ? "" : "<" + open.back() + "> is never closed";
}

// The page as a tree, for tests that look inside it: elements with their
// attributes (entities decoded) and text. Assumes xmlProblem() found nothing.
struct XmlElement {
    std::string name;
    std::map<std::string, std::string> attributes;
    std::string text;  // the text directly inside it, entities decoded
    std::vector<XmlElement> children;

    std::string attribute(const std::string& key) const {
        const auto it = attributes.find(key);
        return it == attributes.end() ? "" : it->second;
    }
    // Every element below this one (not itself) named `tag` with, when
    // `cls` is given, that word in its class attribute.
    std::vector<const XmlElement*> all(const std::string& tag, const std::string& cls = "") const {
        std::vector<const XmlElement*> found;
        for (const XmlElement& child : children) {
            const std::string classes = " " + child.attribute("class") + " ";
            if (child.name == tag &&
                (cls.empty() || classes.find(" " + cls + " ") != std::string::npos))
                found.push_back(&child);
            for (const XmlElement* below : child.all(tag, cls)) found.push_back(below);
        }
        return found;
    }
    // All text inside, children's included, in document order (no separators).
    std::string allText() const {
        std::string out = text;
        for (const XmlElement& child : children) out += child.allText();
        return out;
    }
};

inline std::string decodeEntities(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '&') {
            out += s[i];
            continue;
        }
        const size_t semi = s.find(';', i);
        const std::string name = s.substr(i + 1, semi - i - 1);
        out += name == "amp"    ? "&"
               : name == "lt"   ? "<"
               : name == "gt"   ? ">"
               : name == "quot" ? "\""
                                : "?";
        i = semi;
    }
    return out;
}

// A document root (name "") holding the page's elements.
inline XmlElement parseXml(const std::string& s) {
    XmlElement root;
    std::vector<XmlElement*> open{&root};
    size_t i = 0;
    if (s.compare(0, 9, "<!DOCTYPE") == 0) i = s.find('>') + 1;
    while (i < s.size()) {
        const size_t lt = s.find('<', i);
        open.back()->text += decodeEntities(s.substr(i, lt - i));
        if (lt == std::string::npos) break;
        const size_t gt = s.find('>', lt);
        std::string tag = s.substr(lt + 1, gt - lt - 1);
        i = gt + 1;
        if (tag[0] == '/') {
            if (open.size() > 1) open.pop_back();
            continue;
        }
        const bool selfClosing = tag.back() == '/';
        if (selfClosing) tag.pop_back();
        XmlElement element;
        size_t at = tag.find_first_of(" \t\n");
        element.name = tag.substr(0, at);
        while (at != std::string::npos && at < tag.size()) {
            const size_t nameStart = tag.find_first_not_of(" \t\n", at);
            if (nameStart == std::string::npos) break;
            const size_t eq = tag.find('=', nameStart);
            const size_t open1 = tag.find('"', eq), close1 = tag.find('"', open1 + 1);
            if (eq == std::string::npos || open1 == std::string::npos) break;
            element.attributes[tag.substr(nameStart, eq - nameStart)] =
                decodeEntities(tag.substr(open1 + 1, close1 - open1 - 1));
            at = close1 + 1;
        }
        open.back()->children.push_back(std::move(element));
        if (!selfClosing) open.push_back(&open.back()->children.back());
    }
    return root;
}

// RFC 4648 base64 back to bytes; throws std::runtime_error on a bad digit or length.
inline std::string fromBase64(const std::string& text) {
    static const std::string digits =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    if (text.size() % 4) throw std::runtime_error("base64: length not a multiple of 4");
    std::string out;
    for (size_t i = 0; i < text.size(); i += 4) {
        unsigned v = 0;
        int pad = 0;
        for (size_t k = 0; k < 4; ++k) {
            const char c = text[i + k];
            const size_t d = digits.find(c);
            if (c == '=' && i + 4 == text.size() && k >= 2)
                ++pad;
            else if (d == std::string::npos || pad)
                throw std::runtime_error("base64: bad digit");
            v = v << 6 | (c == '=' ? 0u : unsigned(d));
        }
        out += char(v >> 16);
        if (pad < 2) out += char(v >> 8 & 0xff);
        if (pad < 1) out += char(v & 0xff);
    }
    return out;
}

}  // namespace vkray::test
