// libFuzzer target: a scene's XML text to validated parameters, the way the driver reads
// it (drivers/tribos.cpp: the Teuchos XML parser, whose errors become input errors, then
// validation against every component's valid list). It must give a list or throw
// core::InputError; anything else is a finding. Seeds: test/fuzz/corpus/scene; dictionary:
// test/fuzz/scene.dict.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/stack/SceneParameters.hpp"

namespace {
void readScene(const std::string& text) {
  Teuchos::RCP<Teuchos::ParameterList> list;
  try {
    list = Teuchos::getParametersFromXmlString(text);
  } catch (const std::exception& e) {
    throw tribos::core::InputError(std::string("fuzz.xml: not a valid Teuchos XML parameter list: ") + e.what());
  }
  tribos::core::validateAndSetDefaults(*list, *tribos::stack::sceneValidParameters(), "fuzz.xml");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    readScene(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const tribos::core::InputError&) {
  }
  return 0;
}
