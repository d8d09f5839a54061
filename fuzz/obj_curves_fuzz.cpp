// libFuzzer target: OBJ `l` polyline reader (kernel/io/obj.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_curve_reader(data, size, "fuzz.obj", io::read_obj_curves, io::write_obj_curves);
    return 0;
}
