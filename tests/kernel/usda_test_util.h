// Shared by the USD reader tests (tests/kernel/usda_*_test.cpp): read a .usda text through the real
// reader (a file on disk, as a user would) and keep the warnings it gives.
#pragma once

#include "kernel/io/curve_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace groom::test {

struct UsdaRead {
    CurveSet curves;
    std::vector<std::string> warnings;
    /// Whether some warning contains `text`.
    bool warned(const std::string& text) const
    {
        for (const std::string& w : warnings)
            if (w.find(text) != std::string::npos) return true;
        return false;
    }
};

inline UsdaRead read_usda_text(const std::string& text, CurveReadOptions options = {}, const std::string& name = "t.usda")
{
    TempDir dir;
    write_text(dir.file(name), text);
    UsdaRead r;
    options.warn = [&r](const std::string& w) { r.warnings.push_back(w); };
    r.curves = read_curves(dir.file(name), options);
    return r;
}

/// The ParseError text of reading `text`, or "" when it reads.
inline std::string usda_error(const std::string& text, CurveReadOptions options = {}, const std::string& name = "bad.usda")
{
    TempDir dir;
    write_text(dir.file(name), text);
    try {
        read_curves(dir.file(name), options);
    }
    catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace groom::test
