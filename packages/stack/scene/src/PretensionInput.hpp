#pragma once
// Internal to stack/scene/: the Pretension/<name> sublists read into the scene (the sections
// themselves: Scene.hpp, PretensionSection; how a history solves them: stack/Pretension.hpp).
#include <string>

#include "tribos/stack/Scene.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// Reads the Pretension/<name> sublists into scene.pretensions (after the contact interfaces):
/// an Interface of the scene with Friction Model Bonded, one section per interface, Force or
/// Shortening (one of them, > 0), Steps at most Load Steps/Number Of Steps; a scene with a
/// section is solved as a load history. Throws core::InputError naming the parameter.
void readPretensions(const Teuchos::ParameterList& list, const std::string& source, Scene& scene);

}  // namespace tribos::stack
