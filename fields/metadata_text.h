// MetadataText: reads the printable numbers groom keeps in a .vdb's grid metadata (the source mesh,
// fields/source_mesh.h; the texture coordinates, fields/uv_map.h): whitespace-separated tokens, each
// checked, every failure a ParseError naming the file and the metadata. Text rather than bytes
// because vdb_print shows and pyopenvdb decodes metadata strings.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace groom::detail {

class MetadataText {
public:
    /// `context` names the file and the metadata, e.g. "head.vdb: source mesh (grid metadata 'groom_source_mesh')".
    MetadataText(std::string_view text, std::string context) : text_(text), context_(std::move(context)) {}

    /// Throws ParseError: the context, `why`, and a hint that the file may be corrupt.
    [[noreturn]] void fail(const std::string& why) const;
    /// The next token (empty at the end).
    std::string_view token();
    /// The next token as a decimal integer in [lo, hi]; `name` says what it is in the message.
    int64_t integer(int64_t lo, int64_t hi, const char* name);
    /// The next token as a finite float.
    float real();
    size_t size() const { return text_.size(); }
    /// The first two tokens: `name` and version 1 (the only one written so far).
    void header(std::string_view name);
    /// A count of numbers still to come, read as an integer in [lo, the most the text could hold]:
    /// a flipped digit must not allocate gigabytes.
    int64_t count(int64_t lo, const char* name);
    /// Fails unless the whole text could hold `numbers` numbers (the counts read, multiplied out).
    void expect_numbers(int64_t numbers) const;

private:
    int64_t most_numbers() const;
    std::string_view text_;
    std::string context_;
    size_t pos_ = 0;
};

}  // namespace groom::detail
