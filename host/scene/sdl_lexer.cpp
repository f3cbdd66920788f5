#include "scene/sdl_lexer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

#include "util/error.h"

namespace vkray {

namespace {

// The bytes C's isspace() accepts in the "C" locale; a lone CR counts as
// space, so CRLF files read like LF files.
bool isSdlSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

bool isBrace(char c) {
    return c == '{' || c == '}';
}

bool endsWord(char c) {
    return isSdlSpace(c) || isBrace(c) || c == '!';
}

bool isBraceToken(const Token& token) {
    return token.text == "{" || token.text == "}";
}

}  // namespace

std::vector<Token> tokenizeSdl(std::string_view text, std::shared_ptr<const std::string> fileName) {
    std::vector<Token> tokens;
    int line = 1;
    std::size_t lineStart = 0;  // byte offset of the current line's first byte
    std::size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            lineStart = ++i;
            continue;
        }
        if (isSdlSpace(c)) {
            ++i;
            continue;
        }
        if (c == '!') {  // comment: any bytes up to the end of the line
            while (i < text.size() && text[i] != '\n') ++i;
            continue;
        }
        const FileLoc loc{fileName, line, static_cast<int>(i - lineStart) + 1};
        const std::size_t start = i;
        if (isBrace(c)) {
            ++i;
        } else {
            while (i < text.size() && !endsWord(text[i])) ++i;
        }
        tokens.push_back(Token{std::string(text.substr(start, i - start)), loc, nullptr});
    }
    return tokens;
}

std::vector<Token> tokenizeSdl(std::string_view text, const std::string& fileName) {
    return tokenizeSdl(text, std::make_shared<const std::string>(fileName));
}

NumberStatus parseSdlNumber(std::string_view text, double& value) {
    // from_chars follows strtod's syntax but refuses a leading '+'; Hill's
    // files may have one. A '+' before a sign or letter stays malformed.
    std::string_view digits = text;
    if (digits.size() >= 2 && digits[0] == '+' &&
        ((digits[1] >= '0' && digits[1] <= '9') || digits[1] == '.'))
        digits.remove_prefix(1);
    double parsed = 0;
    const char* const end = digits.data() + digits.size();
    const auto [stop, error] = std::from_chars(digits.data(), end, parsed);
    if (error == std::errc::invalid_argument || stop != end) return NumberStatus::Malformed;
    if (error == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
    if (!std::isfinite(parsed)) return NumberStatus::NotFinite;
    value = parsed;
    return NumberStatus::Ok;
}

std::string inQuotes(const std::string& text) {
    std::string quoted = "'";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f) {
            quoted += c;
        } else {
            static const char kHex[] = "0123456789abcdef";
            quoted += {'\\', 'x', kHex[byte >> 4], kHex[byte & 15]};
        }
    }
    return quoted + "'";
}

std::string diagnosticAt(const Token& token, const char* severity, const std::string& message) {
    return formatDiagnostic(token.loc, token.expansion.get(), severity, message);
}

void throwAt(const Token& token, const std::string& message) {
    throw Error(diagnosticAt(token, "error", message));
}

// ---- def / use substitution -----------------------------------------------

SdlTokenStream::SdlTokenStream(std::vector<Token> tokens, const SdlOptions& options)
    : maxExpandedTokens_(options.maxExpandedTokens), maxUseDepth_(options.maxUseDepth) {
    sources_.push_back(Source{std::make_shared<const TokenList>(std::move(tokens)), 0, nullptr});
}

std::optional<Token> SdlTokenStream::next() {
    if (peeked_) return std::exchange(peeked_, std::nullopt);
    return fetch();
}

const Token* SdlTokenStream::peek() {
    if (!peeked_) peeked_ = fetch();
    return peeked_ ? &*peeked_ : nullptr;
}

std::optional<Token> SdlTokenStream::fetch() {
    for (;;) {
        std::optional<Token> token = nextRaw();
        if (!token) return std::nullopt;
        if (token->text == "def") {
            readDef(*token);
        } else if (token->text == "use") {
            pasteUse(*token);
        } else {
            return token;
        }
    }
}

std::optional<Token> SdlTokenStream::nextRaw() {
    while (!sources_.empty()) {
        Source& source = sources_.back();
        if (source.position < source.tokens->size()) {
            const Token& written = (*source.tokens)[source.position++];
            // Tokens of the file itself carry no expansion; pasted ones carry
            // the paste that brought them here.
            return Token{written.text, written.loc, source.expansion};
        }
        sources_.pop_back();
    }
    return std::nullopt;
}

void SdlTokenStream::readDef(const Token& defKeyword) {
    const std::optional<Token> name = nextRaw();
    if (!name) throwAt(defKeyword, "'def' is missing its name (end of file)");
    if (isBraceToken(*name))
        throwAt(*name, "expected a name after 'def', found '" + name->text + "'");
    const std::optional<Token> open = nextRaw();
    if (!open)
        throwAt(defKeyword, "'def " + name->text + "' is missing its body { ... } (end of file)");
    if (open->text != "{")
        throwAt(*open, "expected '{' after 'def " + name->text + "', found '" + open->text + "'");

    // The body is stored as written, braces inside it balanced; it is parsed
    // only where it is pasted.
    TokenList body;
    std::vector<Token> openBraces{*open};
    for (;;) {
        std::optional<Token> token = nextRaw();
        if (!token)
            throwAt(openBraces.back(),
                    "'{' is never closed by a matching '}' (in 'def " + name->text + "')");
        if (token->text == "{") {
            openBraces.push_back(*token);
        } else if (token->text == "}") {
            openBraces.pop_back();
            if (openBraces.empty()) break;
        }
        token->expansion = nullptr;  // a paste gives it the expansion of that use
        body.push_back(std::move(*token));
    }
    // A later def of the same name replaces this one (text semantics).
    defs_[name->text] = std::make_shared<const TokenList>(std::move(body));
}

void SdlTokenStream::pasteUse(const Token& useKeyword) {
    const std::optional<Token> name = nextRaw();
    if (!name) throwAt(useKeyword, "'use' is missing the name of a def (end of file)");
    if (isBraceToken(*name))
        throwAt(*name, "expected the name of a def after 'use', found '" + name->text + "'");
    const auto def = defs_.find(name->text);
    if (def == defs_.end())
        throwAt(useKeyword,
                "'use " + name->text + "': no def named '" + name->text + "' before this point");

    // The uses that pasted this one: a def among them that is pasted again
    // would paste itself forever.
    int depth = 1;
    bool recursive = false;
    for (const Expansion* e = useKeyword.expansion.get(); e; e = e->parent.get()) {
        ++depth;
        recursive = recursive || e->name == name->text;
    }
    if (recursive) {
        std::string path = name->text;  // built outermost first
        for (const Expansion* e = useKeyword.expansion.get(); e; e = e->parent.get())
            path = e->name + " -> " + path;
        throwAt(useKeyword, "recursive 'use " + name->text + "' (" + path + ")");
    }
    if (depth > maxUseDepth_)
        throwAt(useKeyword, "'use " + name->text + "' is nested more than " +
                                std::to_string(maxUseDepth_) + " uses deep");
    const std::size_t bodySize = def->second->size();
    if (bodySize > maxExpandedTokens_ - std::min(expandedTokens_, maxExpandedTokens_))
        throwAt(useKeyword, "'use " + name->text + "' would paste more than " +
                                std::to_string(maxExpandedTokens_) +
                                " tokens in all (def/use expansion limit)");
    expandedTokens_ += bodySize;

    // Finished pastes below the new one need not stay on the stack.
    while (sources_.size() > 1 && sources_.back().position == sources_.back().tokens->size())
        sources_.pop_back();
    auto expansion = std::make_shared<const Expansion>(
        Expansion{name->text, useKeyword.loc, useKeyword.expansion});
    sources_.push_back(Source{def->second, 0, std::move(expansion)});
}

}  // namespace vkray
