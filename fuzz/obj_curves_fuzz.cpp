// libFuzzer target: OBJ `l` polyline reader (kernel/io/obj.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    // Odd sizes also take closed loops of edges (as a hairline is read), so that path is fuzzed too.
    const bool loops = size % 2;
    fuzz::check_curve_reader(
        data, size, "fuzz.obj", [loops](const io::FileBytes& f) { return io::read_obj_curves(f, loops); },
        [](const CurveSet& cs) { return io::write_obj_curves(cs); });
    return 0;
}
