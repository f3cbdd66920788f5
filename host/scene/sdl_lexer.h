// The lexical layer of the SDL reader: splitting text into located tokens,
// reading numbers, and the `def`/`use` text substitution, which works on
// tokens before the parser sees them (Hill's `use` pastes text, so a `def`
// body is stored unparsed and checked only where it is pasted).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "scene/sdl_reader.h"
#include "util/file_loc.h"

namespace vkray {

struct Token {
    std::string text;
    FileLoc loc;                                 // where the text was written
    std::shared_ptr<const Expansion> expansion;  // the `use` that pasted it; null if none
};

// Splits SDL text into tokens: white space separates them, `{` and `}` are
// tokens of their own even when glued to a word, `!` starts a comment to the
// end of the line. Any other byte (Latin-1, UTF-8) belongs to a word.
std::vector<Token> tokenizeSdl(std::string_view text, std::shared_ptr<const std::string> fileName);
std::vector<Token> tokenizeSdl(std::string_view text, const std::string& fileName);

enum class NumberStatus { Ok, Malformed, NotFinite, OutOfRange };

// One SDL number: what std::from_chars reads as a double, plus a leading '+'.
// The whole text must be the number; NaN, infinities and values beyond double
// range are refused. `value` is set only when the result is Ok.
NumberStatus parseSdlNumber(std::string_view text, double& value);

// "file:line:col: severity: message" at the token, plus one note per `use`
// that pasted it.
// A word as a message quotes it: bytes that are not printable ASCII (a NUL
// would end the message in a terminal; binary junk garbles it) as \xNN.
std::string inQuotes(const std::string& text);
std::string diagnosticAt(const Token& token, const char* severity, const std::string& message);
[[noreturn]] void throwAt(const Token& token, const std::string& message);

// Tokens of one file with `def NAME { ... }` taken out (stored) and every
// `use NAME` replaced by the stored tokens, recursively. Pasted tokens keep
// the place they were written and carry the chain of uses that pasted them.
class SdlTokenStream {
public:
    SdlTokenStream(std::vector<Token> tokens, const SdlOptions& options);

    // The next token after substitution; nullopt at the end of the text.
    std::optional<Token> next();
    // The token next() would return, without consuming it; null at the end.
    const Token* peek();

    std::size_t expandedTokenCount() const { return expandedTokens_; }

private:
    using TokenList = std::vector<Token>;
    struct Source {
        std::shared_ptr<const TokenList> tokens;
        std::size_t position = 0;
        std::shared_ptr<const Expansion> expansion;  // null for the file itself
    };

    std::optional<Token> fetch();    // next token after substitution
    std::optional<Token> nextRaw();  // next token as written (def bodies, names)
    void readDef(const Token& defKeyword);
    void pasteUse(const Token& useKeyword);

    std::vector<Source> sources_;  // the file at the bottom, innermost paste on top
    std::unordered_map<std::string, std::shared_ptr<const TokenList>> defs_;
    std::optional<Token> peeked_;
    std::size_t expandedTokens_ = 0;
    std::size_t maxExpandedTokens_;
    int maxUseDepth_;
};

}  // namespace vkray
