// The Vulkan params block layouts hush computes (hush/glsl/vulkan_params.hpp) of the shader
// files named on the command line, for glslang_matrix.py to compare with glslang's reflection
// of the same files. One line per file and per member:
//   FILE block NAME SIZE            (NAME - and SIZE 0 for a shader without loose uniforms)
//   FILE member NAME TYPE COUNT OFFSET STRIDE
// FILE as given. Exits 1, with the reason on stderr, when a file cannot be read or laid out.
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "hush/glsl/vulkan_params.hpp"

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    if (!in) {
      std::cerr << "vulkan_params_layout: cannot read " << argv[i] << '\n';
      return 1;
    }
    std::ostringstream text;
    text << in.rdbuf();
    try {
      const hush::glsl::vulkan_params_layout l = hush::glsl::vulkan_params_layout_of(text.str());
      std::cout << argv[i] << " block " << (l.block.empty() ? "-" : l.block) << ' ' << l.size
                << '\n';
      for (const hush::glsl::vulkan_param& m : l.members)
        std::cout << argv[i] << " member " << m.name << ' ' << m.type << ' ' << m.count << ' '
                  << m.offset << ' ' << m.stride << '\n';
    } catch (const std::exception& e) {
      std::cerr << "vulkan_params_layout: " << argv[i] << ": " << e.what() << '\n';
      return 1;
    }
  }
  return 0;
}
