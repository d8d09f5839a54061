// libFuzzer target: PLY mesh reader (kernel/io/ply_parse.cpp, ply_mesh.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    fuzz::check_mesh_reader(data, size, "fuzz.ply", io::read_ply_mesh, io::write_ply_mesh);
    return 0;
}
