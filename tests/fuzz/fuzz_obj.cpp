// libFuzzer target: the Wavefront OBJ loader of the test scenes (examples/scene/mesh.hpp,
// tinyobjloader underneath) on arbitrary bytes. Property: it returns a mesh whose faces index
// its vertices, or throws std::runtime_error / hush::invalid_argument; no crash, hang or
// sanitizer report.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/hush_fuzz_obj_" + std::to_string(getpid()) + ".obj";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    const hush_tools::scene::mesh m = hush_tools::scene::load_obj(path);
    for (std::uint32_t i : m.indices)
      if (i >= m.positions.size()) {
        std::fprintf(stderr, "load_obj: index %u of %zu positions\n", i, m.positions.size());
        std::abort();
      }
    if (m.normals.size() != m.positions.size() || m.uvs.size() != m.positions.size()) {
      std::fprintf(stderr, "load_obj: %zu normals, %zu uvs for %zu positions\n", m.normals.size(),
                   m.uvs.size(), m.positions.size());
      std::abort();
    }
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  std::remove(path.c_str());
  return 0;
}
