// libFuzzer target: STL mesh reader, ASCII and binary (kernel/io/off_stl.cpp). Read-only format,
// no round trip. See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_mesh_reader(data, size, "fuzz.stl", io::read_stl, nullptr);
    return 0;
}
