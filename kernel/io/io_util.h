// Shared plumbing for the file-format readers and writers in kernel/io: whole-file input (with "-"
// for stdin), error messages that name the file and line or byte offset, and exact text formatting
// of numbers. Internal to kernel/io: nothing outside this folder includes it.
#pragma once

#include "kernel/error.h"
#include "kernel/math/vec.h"

#include <charconv>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>

namespace groom::io {

/// A file's whole contents plus the name used in messages ("<stdin>" for "-").
struct FileBytes {
    std::string name;
    std::string data;
};

/// Reads `path` ("-" = standard input) into memory. Throws IoError naming the path.
FileBytes read_all(const std::string& path);

/// Lower-case extension without the dot ("usda"), or "" when there is none.
std::string extension_of(const std::string& path);

/// "name:line: message" as a ParseError.
[[noreturn]] void fail_at_line(const std::string& name, size_t line, const std::string& message);
/// "name: byte N: message" as a ParseError.
[[noreturn]] void fail_at_byte(const std::string& name, size_t offset, const std::string& message);

/// Throws LimitExceeded when a header claims `count` items of at least `min_bytes_each` bytes but
/// only `available` bytes follow from byte `offset`: refused before anything is allocated.
void check_claimed_count(const std::string& name, std::string_view what, uint64_t count, uint64_t min_bytes_each,
                         uint64_t available, size_t offset);

/// Where a text writer's output goes as it is made: with a stream, the text so far is handed to it
/// once it passes a few MiB, so a large file is never held whole beside the curves (a trial's
/// 21 M-segment groom.write to .usda grew to 23.8 GB and was killed); without one, it all stays in
/// `out` for the caller. Call it between items; write what is left in `out` at the end.
struct TextSpill {
    std::string& out;
    std::ostream* to = nullptr;
    void operator()() const
    {
        if (to && out.size() >= (size_t(4) << 20)) {
            to->write(out.data(), static_cast<std::streamsize>(out.size()));
            out.clear();
        }
    }
};

/// Shortest text that parses back to exactly `v` (std::to_chars), appended to `out`.
inline void append_number(std::string& out, float v)
{
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, res.ptr);
}
inline void append_number(std::string& out, int64_t v)
{
    char buf[24];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, res.ptr);
}
inline void append_number(std::string& out, int32_t v) { append_number(out, static_cast<int64_t>(v)); }

/// Text shown for a found token in messages: quoted, shortened, "end of file" when empty.
std::string describe_found(std::string_view token);

/// Parses a whole token as a float / integer; false when it is not one. Accepts a leading '+'.
bool parse_float(std::string_view token, float& out);
bool parse_double(std::string_view token, double& out);
bool parse_int(std::string_view token, int64_t& out);

/// Splits text into lines and whitespace-separated tokens, tracking the 1-based line number.
/// Used by the line-oriented formats (OBJ, OFF, ASCII STL, ASCII PLY).
class TextCursor {
public:
    TextCursor(std::string_view text, size_t first_line = 1) : text_(text), line_(first_line) {}

    /// Next token on the current line, or "" at the end of the line (does not advance lines).
    std::string_view token();
    /// Next token, crossing line ends; "" at the end of the text.
    std::string_view token_any_line();
    /// Skips to the start of the next line; false at the end of the text.
    bool next_line();
    /// True when only spaces (or a '#' comment, when `hash_comments`) remain on the current line.
    bool at_line_end(bool hash_comments = true);
    /// The rest of the current line (without the newline), consuming it.
    std::string_view rest_of_line();
    bool at_end() const { return pos_ >= text_.size(); }
    size_t line() const { return line_; }
    size_t offset() const { return pos_; }

private:
    std::string_view text_;
    size_t pos_ = 0;
    size_t line_;
};

}  // namespace groom::io
