// Layer 1 (Primitives): the SPIR-V binaries compiled at build time (cmake/FeShaders.cmake),
// found by their path under shaders/, e.g. fe::shaders::find("conformance/triangle.vert").
#pragma once
#include <string_view>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::shaders {

void registerBinary(const gdi::ShaderBinary& binary);
// Throws gdi::Error naming the shader when it is not compiled into this program.
const gdi::ShaderBinary& find(std::string_view name);
std::vector<std::string_view> names();

}  // namespace fe::shaders
