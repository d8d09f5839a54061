// libFuzzer target: PLY curve reader (kernel/io/ply_parse.cpp, ply_curves.cpp), ASCII and binary. See fuzz_reader.h.
// The round trip alternates the writer's encoding by input size so both writers are exercised.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    const PlyEncoding enc = size % 2 ? PlyEncoding::Ascii : PlyEncoding::Binary;
    fuzz::check_curve_reader(data, size, "fuzz.ply", io::read_ply_curves,
                             [enc](const CurveSet& cs) { return io::write_ply_curves(cs, enc); });
    return 0;
}
