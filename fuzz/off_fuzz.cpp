// libFuzzer target: OFF mesh reader (kernel/io/off_stl.cpp). OFF is read-only in groom, so there is
// no round trip. See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_mesh_reader(data, size, "fuzz.off", io::read_off, nullptr);
    return 0;
}
