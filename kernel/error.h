// Typed errors for the whole library. Every message states what went wrong, where (file:line,
// parameter name) and what was expected versus what was found. Only cli/ catches them.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace groom {

/// Base of every error groom throws on purpose.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A parameter (op params struct or command-line value) outside its valid range.
/// The CLI reports these as usage errors (exit code 2).
class InvalidParam : public Error {
public:
    using Error::Error;
};

/// A file that cannot be parsed: the message names the file and line or byte offset.
class ParseError : public Error {
public:
    using Error::Error;
};

/// A file that cannot be opened, written or renamed.
class IoError : public Error {
public:
    using Error::Error;
};

/// Geometry that breaks an invariant (offsets not monotonic, NaN positions, column size mismatch).
class InvalidGeometry : public Error {
public:
    using Error::Error;
};

/// Input that would exceed a resource budget (memory, counts) and is refused before allocating.
class LimitExceeded : public Error {
public:
    using Error::Error;
};

/// A number as error messages show it: "%g", so 1.5 reads "1.5" and 1e-7 stays "1e-07" (a fixed
/// six-decimal format would print a tiny bad value as "0").
inline std::string format_number(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

/// A point as the options take one, "x,y,z" (each format_number), so a message's point can be
/// pasted back as --center and the like.
template <class Vec3> std::string format_xyz(const Vec3& v)
{
    return format_number(v.x) + "," + format_number(v.y) + "," + format_number(v.z);
}

}  // namespace groom
