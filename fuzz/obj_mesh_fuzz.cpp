// libFuzzer target: OBJ `f` mesh reader (kernel/io/obj.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_mesh_reader(data, size, "fuzz.obj", io::read_obj_mesh, io::write_obj_mesh);
    return 0;
}
