// libFuzzer target: a scene's XML text to validated parameters, the way the driver reads
// it (drivers/tribos.cpp): core::parameterListFromXml (strict reading: nesting, duplicate
// names, values of their type) then validation against the scene's valid list. It must
// give a list or throw core::InputError; anything else (another exception, a crash, a
// sanitizer report, a timeout) is a finding. Seeds: test/fuzz/corpus/scene; dictionary:
// test/fuzz/scene.dict.
#include <Teuchos_ParameterList.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/stack/SceneParameters.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto list = tribos::core::parameterListFromXml(text, "fuzz.xml");
    tribos::core::validateAndSetDefaults(*list, *tribos::stack::sceneValidParameters(), "fuzz.xml");
  } catch (const tribos::core::InputError&) {
  }
  return 0;
}
