// Layer 2 (GDI abstraction): what a SPIR-V module declares and uses, read with SPIRV-Cross, so
// a pipeline is checked against its shaders before any native call (the same gdi::Error on
// every backend) and its binding slots can be derived from them.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

// The scalar type of a stage input or output (vertex attributes, colour outputs).
enum class ScalarKind : uint8_t { Float, Int, Uint, Other };
const char* scalarKindName(ScalarKind k);
const char* shaderStageName(ShaderStage s);  // "vertex", "fragment", "compute"
const char* bindingTypeName(BindingType t);  // "uniform buffer", ...

// Locations a stage's inputs or outputs may use: 0 to 15 (64 components, the least both APIs
// guarantee for vertex attributes, varyings and fragment inputs).
inline constexpr uint32_t kMaxInterfaceLocations = 16;

// One member of a uniform or storage block as the shader lays it out (std140, std430 or
// explicit offsets): a port from OpenGL sets uniforms by name, so it needs these rather than
// padding a C++ struct by hand. Members of nested structs are listed by path ("light.colour"),
// and each element of an array of structs by index ("lights[2].colour") up to 64 elements.
struct BlockMember {
    std::string name;
    uint32_t offset = 0;                  // bytes from the block's start
    uint32_t size = 0;                    // bytes the member takes (all of an array's elements)
    ScalarKind kind = ScalarKind::Float;  // Other: bool (4 bytes in a block)
    uint32_t vectorSize = 1;              // components of a vector (of a matrix's column)
    uint32_t columns = 1;                 // a matrix's columns, else 1
    bool rowMajor = false;                // layout(row_major): each row contiguous instead
    uint32_t matrixStride = 0;            // bytes between a matrix's columns (rows if rowMajor)
    uint32_t arrayCount = 1;              // elements; 0: runtime-sized (a storage block's last)
    uint32_t arrayStride = 0;             // bytes between elements (0: not an array)
};

struct ShaderInterface {
    struct Binding {
        uint32_t slot = 0;  // layout(binding = slot), descriptor set 0
        BindingType type = BindingType::UniformBuffer;
        std::string name;  // the block or variable name, for messages
        // Textures: 1 + the TextureDimension the shader declares (sampler2DArray: Texture2DArray),
        // kTexture2DMultisampleKind for sampler2DMS; 0 for buffers.
        uint8_t dimension = 0;
        // Buffers: the block's declared size in bytes (a runtime-sized array counted as empty)
        // and its members (BlockMember); empty for textures.
        uint32_t blockBytes = 0;
        std::vector<BlockMember> members;
    };
    struct Variable {
        uint32_t location = 0;
        ScalarKind kind = ScalarKind::Float;
        uint32_t components = 1;
        std::string name;
        uint32_t locations = 1;  // consecutive locations taken (arrays, matrices)
        bool patch = false;      // a tessellation stage's per-patch variable (`patch out`)
    };
    ShaderStage stage = ShaderStage::None;
    std::vector<Binding> bindings;  // the ones the entry point uses, by slot
    std::vector<Variable> inputs;   // user inputs (built-ins excluded), by location
    std::vector<Variable> outputs;
    struct SpecConstant {
        uint32_t id = 0;                      // layout(constant_id = id)
        ScalarKind kind = ScalarKind::Float;  // Other: a bool
        bool isBool = false;
        std::string name;
    };
    // The per-draw constants block (FE_CONSTANTS): a push-constant block in Vulkan SPIR-V, the
    // uniform block at kConstantsGlBinding in GL SPIR-V. 0: none.
    uint32_t pushConstantBytes = 0;
    std::vector<SpecConstant> specConstants;  // by id
    std::array<uint32_t, 3> workgroupSize{};  // compute
    bool writesSampleMask = false;            // fragment: declares the SampleMask output
};

// The GL binding of the constants block (fe_common.glsl's FE_CONSTANTS), past the 0..63 slots.
inline constexpr uint32_t kConstantsGlBinding = 64;

// The rules a module is validated against before it is read: SPIR-V's own, OpenGL 4.5's (the GL
// backend) or a Vulkan version's (block layouts, capabilities, built-ins: what the validation
// layer would refuse on that device).
enum class SpirvRules : uint8_t { Universal, OpenGL45, Vulkan12, Vulkan13 };

// Throws Error naming the shader and the encoding when the module is not valid under `rules`.
void validateSpirv(std::span<const uint32_t> spirv, SpirvRules rules, const std::string& name);

// Both encodings a ShaderBinary carries (an empty one is skipped), the Vulkan one first under
// `vulkanRules`: the magic number, validateSpirv, the capabilities it declares (those every
// device offers, cube arrays where `features` say so), and the entry point of desc's stage.
// Every backend calls it before reading its own half, so a damaged binary is the same Error on
// every backend, not only on the one that happens to read the damaged half.
void validateShaderBinary(const ShaderDesc& desc, SpirvRules vulkanRules,
                          const DeviceFeatures& features);

// Throws Error naming the shader when the module is not valid under `rules`, cannot be parsed,
// uses a descriptor set other than 0, or a resource kind the device has no slot type for.
ShaderInterface reflectShader(std::span<const uint32_t> spirv, ShaderStage stage,
                              const char* entryPoint, const std::string& name,
                              SpirvRules rules = SpirvRules::Universal);

// The module with `prefix` before every OpName. NVIDIA's GL matches a program's uniforms across
// stages by name even in SPIR-V programs, so two stages' blocks of one name and different members
// fail to link there ("struct fields mismatch") where Vulkan and Mesa take them. Dropping the
// names does not help: it names them by result id, and ids repeat across stages ("type mismatch
// between variables of same name __defaultname_103"). A prefix per stage keeps every name apart.
std::vector<uint32_t> withNamesPrefixed(std::span<const uint32_t> spirv, const std::string& prefix);

// The module with every storage texture's binding `slot` changed to newSlot[slot] (0xff: kept).
// The GL backend numbers a pipeline's storage textures 0, 1, ... as image units, because GL has
// as few as 8 image units (NVIDIA) where the device's slots go to 63. `spirv` must be valid.
std::vector<uint32_t> withStorageTextureSlots(std::span<const uint32_t> spirv,
                                              const std::array<uint8_t, 64>& newSlot);

// The fragment module with its SampleMask output turned into a private variable and a discard,
// before each return of the entry point, of a fragment whose mask has bit 0 clear: what Vulkan
// does on a single-sample target, where GL ignores gl_SampleMask (no sample buffers). The module
// unchanged when it declares no SampleMask. `spirv` must be valid.
std::vector<uint32_t> withSampleMaskAsDiscard(std::span<const uint32_t> spirv);

}  // namespace fe::gdi
