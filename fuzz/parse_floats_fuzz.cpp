// libFuzzer target: the command line's "x,y,z" list parser (cli::parse_floats), used by every option
// that takes a list or a range. The first byte picks the accepted count range; the rest is the text.
// It must either return between min and max finite numbers, one per comma-separated item, or throw
// InvalidParam naming the option.
#include "cli/command.h"
#include "kernel/error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size == 0) return 0;
    const size_t lo = data[0] & 3, hi = lo + ((data[0] >> 2) & 3);
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        const std::vector<float> v = groom::cli::parse_floats("--fuzz", text, lo, hi);
        const size_t items = static_cast<size_t>(std::count(text.begin(), text.end(), ',')) + 1;
        if (v.size() != items || v.size() < lo || v.size() > hi) __builtin_trap();
        for (float f : v)
            if (!std::isfinite(f)) __builtin_trap();
    }
    catch (const groom::InvalidParam& e) {
        if (std::string(e.what()).find("--fuzz") == std::string::npos) __builtin_trap();  // must name the option
    }
    return 0;
}
