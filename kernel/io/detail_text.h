// Detail values as one line of text, for the formats that have comments but no detail values of
// their own: PLY (`comment groom detail NAME TYPE VALUE`) and OBJ (`# groom detail NAME TYPE VALUE`).
// With them a `--shard` part keeps its tag in every format that can (merge checks the set), and a
// closed curve its mark in PLY.
#pragma once

#include "kernel/curve_set.h"

#include <optional>
#include <string>
#include <string_view>

namespace groom::io {

/// The most detail comments a file may carry: groom writes a few (a --shard part's tag, units, up
/// axis, `closed`); each is looked up among those before it.
inline constexpr size_t kMaxDetailComments = 4096;

/// Whether a detail column's name can be one word of a comment (printable ASCII, no spaces).
bool plain_detail_name(std::string_view name);

/// The attribute type with this name (type_name's), if any.
std::optional<AttrType> attr_type_named(std::string_view s);

/// "TYPE VALUE" for detail column `a` (a string escaped to one line: \\, \n, \r). Throws
/// InvalidParam naming `format` when the column's name has spaces or non-ASCII characters.
std::string detail_value_text(const Attribute& a, const std::string& format);

/// Sets detail `name` of `cs` from text of detail_value_text's form; throws ParseError(`bad`) when
/// the text is malformed.
void set_detail_from_text(CurveSet& cs, const std::string& name, std::string_view text, const std::string& bad);

}  // namespace groom::io
