// libFuzzer target: USD ASCII BasisCurves reader (kernel/io/usda_*.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_curve_reader(
        data, size, "fuzz.usda", [](const io::FileBytes& f) { return io::read_usda(f, CurveReadOptions{}); },
        [](const CurveSet& cs) { return io::write_usda(cs); });
    return 0;
}
