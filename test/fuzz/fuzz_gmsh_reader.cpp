// libFuzzer target: the gmsh reader on arbitrary bytes. It must return a mesh or throw
// core::InputError; anything else (another exception, a crash, a sanitizer report, a
// timeout) is a finding. Seeds: test/fuzz/corpus/gmsh.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/GmshReader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const bool splitBodies : {false, true}) {
    try {
      tribos::mesh::parseGmsh(text, "fuzz.msh", splitBodies);
    } catch (const tribos::core::InputError&) {
    }
  }
  return 0;
}
