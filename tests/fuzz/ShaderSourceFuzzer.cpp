// libFuzzer harness: shader sources compiled at run time (ShaderCompiler.h). Any text, as GLSL
// or HLSL, for any stage, with includes, either compiles or is refused with a gdi::Error, never a
// crash or a hang; what compiles is SPIR-V the reflection reads (or refuses with an Error) in
// both encodings. The first byte picks the stage (bits 0-2) and the language (bit 3); an
// `#include "x"` gets the text after the first NUL of the input, so includes are reached too.
#include <cstdint>
#include <string>

#include "FuzzSupport.h"
#include "fe/gdi/ShaderCompiler.h"
#include "fe/gdi/ShaderReflection.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fe::gdi;
    if (size == 0 || size > 64 * 1024) return 0;
    static const ShaderStage kStages[] = {ShaderStage::Vertex,      ShaderStage::Fragment,
                                          ShaderStage::Compute,     ShaderStage::Geometry,
                                          ShaderStage::TessControl, ShaderStage::TessEvaluation};
    const ShaderStage stage = kStages[(data[0] & 7) % 6];
    const ShaderLanguage language = data[0] & 8 ? ShaderLanguage::HLSL : ShaderLanguage::GLSL;
    const std::string all(reinterpret_cast<const char*>(data + 1), size - 1);
    const size_t nul = all.find('\0');
    const std::string text = all.substr(0, nul);
    const std::string included = nul == std::string::npos ? "" : all.substr(nul + 1);
    try {
        const ShaderBinary b =
            compileShader({.stage = stage,
                           .text = text,
                           .language = language,
                           .name = "fuzz",
                           .include = [&](const std::string&, const std::string&) {
                               return std::optional<std::string>(included);
                           }});
        FUZZ_CHECK(!b.vulkan.empty() && !b.opengl.empty(), "a compiled source has no binary",
                   std::string());
        (void)reflectShader(b.vulkan, stage, "main", "fuzz", SpirvRules::Vulkan12);
        (void)reflectShader(b.opengl, stage, "main", "fuzz", SpirvRules::OpenGL45);
    } catch (const Error&) {
        // refused: the expected outcome for most inputs
    }
    return 0;
}
