#include "fields/metadata_text.h"

#include "kernel/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace groom::detail {

void MetadataText::fail(const std::string& why) const { throw ParseError(context_ + ": " + why + " (is the file corrupt?)"); }

std::string_view MetadataText::token()
{
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n')) ++pos_;
    const size_t b = pos_;
    while (pos_ < text_.size() && text_[pos_] != ' ' && text_[pos_] != '\n') ++pos_;
    return text_.substr(b, pos_ - b);
}

int64_t MetadataText::integer(int64_t lo, int64_t hi, const char* name)
{
    const std::string_view t = token();
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || v < lo || v > hi) {
        fail(std::string("expected ") + name + " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], found '" +
             std::string(t.substr(0, 32)) + "'");
    }
    return v;
}

float MetadataText::real()
{
    const std::string_view t = token();
    float v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v)) {
        fail("expected a finite number, found '" + std::string(t.substr(0, 32)) + "'");
    }
    return v;
}

void MetadataText::header(std::string_view name)
{
    if (token() != name) fail("expected the header '" + std::string(name) + "'");
    if (integer(0, 1000000, "a version") != 1) fail("unknown version (this groom reads version 1)");
}

int64_t MetadataText::most_numbers() const
{
    // Every number takes at least two characters (a digit and a separator).
    return int64_t(text_.size() / 2 + 1);
}

int64_t MetadataText::count(int64_t lo, const char* name)
{
    return integer(lo, std::min<int64_t>(most_numbers(), std::numeric_limits<int32_t>::max()), name);
}

void MetadataText::expect_numbers(int64_t numbers) const
{
    if (numbers > most_numbers()) fail("the counts need more numbers than the text holds");
}

}  // namespace groom::detail
