// libFuzzer target: Cem Yuksel .hair reader (kernel/io/hair.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_curve_reader(data, size, "fuzz.hair", io::read_hair, [](const CurveSet& c) { return io::write_hair(c); });
    return 0;
}
