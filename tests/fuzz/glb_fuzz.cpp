// A scene's glTF binary mesh (runtime/src/scene_mesh.cpp): any bytes, as the .glb's contents.
#include "fuzz_target.h"
#include "scene_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return meadow::fuzz::readOrRefuse([&] {
        (void)meadow::runtime::glbTriangles(meadow::fuzz::text(data, size), "fuzz/ground.glb");
    });
}
