#include "kernel/io/io_util.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

namespace groom::io {

FileBytes read_all(const std::string& path)
{
    FileBytes fb;
    if (path == "-") {
        fb.name = "<stdin>";
        std::ostringstream s;
        s << std::cin.rdbuf();
        fb.data = std::move(s).str();
        return fb;
    }
    fb.name = path;
    std::ifstream f(path, std::ios::binary);
    if (!f) throw IoError(path + ": cannot open for reading (" + std::strerror(errno) + ")");
    f.seekg(0, std::ios::end);
    const std::streamoff size = f.tellg();
    if (size < 0) throw IoError(path + ": cannot determine the file size (is it a directory?)");
    f.seekg(0, std::ios::beg);
    fb.data.resize(static_cast<size_t>(size));
    if (size > 0 && !f.read(fb.data.data(), size)) throw IoError(path + ": read failed (" + std::strerror(errno) + ")");
    return fb;
}

std::string extension_of(const std::string& path)
{
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void fail_at_line(const std::string& name, size_t line, const std::string& message)
{
    throw ParseError(name + ":" + std::to_string(line) + ": " + message);
}

void fail_at_byte(const std::string& name, size_t offset, const std::string& message)
{
    throw ParseError(name + ": byte " + std::to_string(offset) + ": " + message);
}

void check_claimed_count(const std::string& name, std::string_view what, uint64_t count, uint64_t min_bytes_each,
                         uint64_t available, size_t offset)
{
    // Compare by division so an absurd count cannot overflow the product.
    if (min_bytes_each > 0 && count > available / min_bytes_each) {
        throw LimitExceeded(name + ": byte " + std::to_string(offset) + ": header claims " + std::to_string(count) + " " + std::string(what) + " (at least " +
                            std::to_string(min_bytes_each) + " bytes each) but only " + std::to_string(available) +
                            " bytes follow; the file is truncated or corrupt");
    }
}

std::string describe_found(std::string_view token)
{
    if (token.empty()) return "end of line";
    std::string s(token.substr(0, 40));
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return "'" + s + (token.size() > 40 ? "...'" : "'");
}

bool parse_float(std::string_view t, float& out)
{
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    if (t.empty()) return false;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
    if (res.ec == std::errc::result_out_of_range) {
        // Denormal-range or huge text: fall back to double, then narrow (gives 0 or inf like strtof).
        double d = 0;
        const auto r2 = std::from_chars(t.data(), t.data() + t.size(), d);
        if (r2.ec != std::errc() || r2.ptr != t.data() + t.size()) return false;
        out = static_cast<float>(d);
        return true;
    }
    return res.ec == std::errc() && res.ptr == t.data() + t.size();
}

bool parse_double(std::string_view t, double& out)
{
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    if (t.empty()) return false;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
    return res.ec == std::errc() && res.ptr == t.data() + t.size();
}

bool parse_int(std::string_view t, int64_t& out)
{
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    if (t.empty()) return false;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
    return res.ec == std::errc() && res.ptr == t.data() + t.size();
}

namespace {
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
}  // namespace

std::string_view TextCursor::token()
{
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    return text_.substr(start, pos_ - start);
}

std::string_view TextCursor::token_any_line()
{
    for (;;) {
        std::string_view t = token();
        if (!t.empty()) return t;
        if (!next_line()) return {};
    }
}

bool TextCursor::next_line()
{
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ >= text_.size()) return false;
    ++pos_;
    ++line_;
    return pos_ < text_.size();
}

bool TextCursor::at_line_end(bool hash_comments)
{
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    return pos_ >= text_.size() || text_[pos_] == '\n' || (hash_comments && text_[pos_] == '#');
}

std::string_view TextCursor::rest_of_line()
{
    const size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::string_view r = text_.substr(start, pos_ - start);
    if (!r.empty() && r.back() == '\r') r.remove_suffix(1);
    return r;
}

}  // namespace groom::io
