// libFuzzer target: OBJ `f` mesh reader (kernel/io/obj.cpp). See fuzz_reader.h.
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace groom;
    // The whole file, round-tripped through the writer; then the faces of group or object "a" (with
    // their texture coordinates; the writer keeps no groups, so no round trip).
    fuzz::check_mesh_reader(data, size, "fuzz.obj", [](const io::FileBytes& f) { return io::read_obj_mesh(f); }, io::write_obj_mesh);
    fuzz::check_mesh_reader(data, size, "fuzz.obj", [](const io::FileBytes& f) { return io::read_obj_mesh(f, "a"); }, nullptr);
    return 0;
}
