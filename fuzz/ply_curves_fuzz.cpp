// libFuzzer target: PLY curve reader (kernel/io/ply_parse.cpp, ply_curves.cpp), ASCII and binary. See fuzz_reader.h.
// The round trip alternates the writer's encoding by input size so both writers are exercised.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    const PlyEncoding enc = size % 2 ? PlyEncoding::Ascii : PlyEncoding::Binary;
    // Sizes 2 and 3 mod 4 also take closed loops of edges (as a hairline is read).
    const bool loops = size % 4 >= 2;
    fuzz::check_curve_reader(data, size, "fuzz.ply", [loops](const io::FileBytes& f) { return io::read_ply_curves(f, loops); },
                             [enc](const CurveSet& cs) { return io::write_ply_curves(cs, enc); });
    return 0;
}
