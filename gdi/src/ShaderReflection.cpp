// SPIR-V reflection through SPIRV-Cross's C API (Debian's libspirv-cross-c-shared): only the
// variables the entry point statically uses count, as Vulkan's validation counts them, so an
// include that declares more blocks than a shader reads does not ask for more bindings.
#include <cstring>
#include <string_view>
#include "fe/gdi/ShaderReflection.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>
#include <spirv-tools/libspirv.h>
#include <spirv_cross/spirv_cross_c.h>

namespace fe::gdi {

const char* scalarKindName(ScalarKind k) {
    switch (k) {
        case ScalarKind::Float:
            return "float";
        case ScalarKind::Int:
            return "int";
        case ScalarKind::Uint:
            return "uint";
        default:
            return "other";
    }
}

const char* shaderStageName(ShaderStage s) {
    switch (s) {
        case ShaderStage::Vertex:
            return "vertex";
        case ShaderStage::Fragment:
            return "fragment";
        case ShaderStage::Compute:
            return "compute";
        case ShaderStage::Geometry:
            return "geometry";
        case ShaderStage::TessControl:
            return "tessellation control";
        case ShaderStage::TessEvaluation:
            return "tessellation evaluation";
        default:
            return "unknown-stage";
    }
}

const char* bindingTypeName(BindingType t) {
    switch (t) {
        case BindingType::UniformBuffer:
            return "uniform buffer";
        case BindingType::StorageBuffer:
            return "storage buffer";
        case BindingType::SampledTexture:
            return "sampled texture";
        default:
            return "storage texture";
    }
}

namespace {

struct Context {
    spvc_context ctx = nullptr;
    Context() { spvc_context_create(&ctx); }
    ~Context() { spvc_context_destroy(ctx); }
};

ScalarKind kindOf(spvc_basetype t) {
    switch (t) {
        case SPVC_BASETYPE_FP16:
        case SPVC_BASETYPE_FP32:
        case SPVC_BASETYPE_FP64:
            return ScalarKind::Float;
        case SPVC_BASETYPE_INT8:
        case SPVC_BASETYPE_INT16:
        case SPVC_BASETYPE_INT32:
        case SPVC_BASETYPE_INT64:
            return ScalarKind::Int;
        case SPVC_BASETYPE_UINT8:
        case SPVC_BASETYPE_UINT16:
        case SPVC_BASETYPE_UINT32:
        case SPVC_BASETYPE_UINT64:
            return ScalarKind::Uint;
        default:
            return ScalarKind::Other;
    }
}

// SPIRV-Cross trusts the module it parses: a malformed one can crash it (the capture-file fuzzer
// found one), so SPIRV-Tools' validator (Debian's spirv-tools) checks every module first. Vulkan
// modules under the device's Vulkan rules, as the validation layer would: a uniform block whose
// member straddles a 16-byte boundary is valid SPIR-V but not valid Vulkan (the fuzzer again).
// Relaxed block layout is core from Vulkan 1.1; the device enables no scalar or standard layout.
spv_context spirvContext(SpirvRules rules) {
    static const spv_context universal = spvContextCreate(SPV_ENV_UNIVERSAL_1_5);
    static const spv_context opengl45 = spvContextCreate(SPV_ENV_OPENGL_4_5);
    static const spv_context vulkan12 = spvContextCreate(SPV_ENV_VULKAN_1_2);
    static const spv_context vulkan13 = spvContextCreate(SPV_ENV_VULKAN_1_3);
    switch (rules) {
        case SpirvRules::OpenGL45:
            return opengl45;
        case SpirvRules::Vulkan12:
            return vulkan12;
        case SpirvRules::Vulkan13:
            return vulkan13;
        case SpirvRules::Universal:
            break;
    }
    return universal;
}

// Location decorations anywhere (block members included, which reflection does not list) stay
// below kMaxInterfaceLocations. The module is valid here, so the instruction stream is sound.
void checkLocationLiterals(std::span<const uint32_t> spirv, const std::string& name) {
    constexpr uint32_t kOpDecorate = 71, kOpMemberDecorate = 72, kLocation = 30;
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size()) break;
        const size_t decoration = op == kOpDecorate ? 2 : op == kOpMemberDecorate ? 3 : 0;
        if (decoration && words > decoration + 1 && spirv[i + decoration] == kLocation &&
            spirv[i + decoration + 1] >= kMaxInterfaceLocations)
            throw Error("shader '" + name + "': location " +
                        std::to_string(spirv[i + decoration + 1]) + "; every device has " +
                        std::to_string(kMaxInterfaceLocations) + " (0 to " +
                        std::to_string(kMaxInterfaceLocations - 1) + ")");
        i += words;
    }
}

// gl_ClipDistance and gl_CullDistance arrays hold at most 8 distances together (the least both
// APIs guarantee); a longer one is the driver's error otherwise (the capture-file fuzzer made a
// module with 14337). Found by walking the module's types, as reflection does not list built-ins.
void checkDistanceArrays(std::span<const uint32_t> spirv, const std::string& name) {
    constexpr uint32_t kOpConstant = 43, kOpTypeArray = 28, kOpTypeStruct = 30, kOpTypePointer = 32,
                       kOpVariable = 59;
    constexpr uint32_t kOpDecorate = 71, kOpMemberDecorate = 72, kBuiltIn = 11, kClip = 3,
                       kCull = 4;
    constexpr uint32_t kMaxDistances = 8;
    std::unordered_map<uint32_t, uint32_t> constants, arrayLength, pointee, variableType;
    std::unordered_map<uint32_t, std::vector<uint32_t>> structMembers;
    std::vector<uint32_t> distanceTypes;  // the types of the distance built-ins, resolved below
    std::vector<std::pair<uint32_t, uint32_t>> memberDistances;  // (struct, member)
    std::vector<uint32_t> variableDistances;
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size()) break;
        const uint32_t* w = &spirv[i];
        if (op == kOpConstant && words == 4)
            constants[w[2]] = w[3];
        else if (op == kOpTypeArray && words == 4)
            arrayLength[w[1]] = w[3];
        else if (op == kOpTypeStruct)
            structMembers[w[1]].assign(w + 2, w + words);
        else if (op == kOpTypePointer && words == 4)
            pointee[w[1]] = w[3];
        else if (op == kOpVariable && words >= 4)
            variableType[w[2]] = w[1];
        else if (op == kOpMemberDecorate && words == 5 && w[3] == kBuiltIn &&
                 (w[4] == kClip || w[4] == kCull))
            memberDistances.push_back({w[1], w[2]});
        else if (op == kOpDecorate && words == 4 && w[2] == kBuiltIn &&
                 (w[3] == kClip || w[3] == kCull))
            variableDistances.push_back(w[1]);
        i += words;
    }
    for (const auto& [s, m] : memberDistances)
        if (const auto it = structMembers.find(s);
            it != structMembers.end() && m < it->second.size())
            distanceTypes.push_back(it->second[m]);
    for (uint32_t v : variableDistances)
        if (const auto t = variableType.find(v); t != variableType.end())
            if (const auto p = pointee.find(t->second); p != pointee.end())
                distanceTypes.push_back(p->second);
    uint64_t total = 0;
    for (uint32_t type : distanceTypes) {
        // Per-vertex arrays of stages with several vertices nest one array deeper: the inner one counts.
        uint64_t length = 1;
        if (const auto a = arrayLength.find(type); a != arrayLength.end()) {
            const auto c = constants.find(a->second);
            length = c == constants.end() ? kMaxDistances + 1 : c->second;
        }
        total += length;
    }
    if (total > kMaxDistances)
        throw Error("shader '" + name + "': gl_ClipDistance and gl_CullDistance hold " +
                    std::to_string(total) + " distances; every device has " +
                    std::to_string(kMaxDistances));
}

// An image write's texel has at least as many components as the image's declared format (a
// Vulkan rule the validator leaves to the layer, VUID-RuntimeSpirv-OpImageWrite-07112; the
// capture-file fuzzer changed a format word and the layer, not the device, said so). Walked with
// SPIRV-Tools' parser, which knows each instruction's result type.
void checkImageWrites(std::span<const uint32_t> spirv, SpirvRules rules, const std::string& name) {
    struct Walk {
        std::unordered_map<uint32_t, uint32_t> components, imageFormat, resultType;
        std::vector<std::pair<uint32_t, uint32_t>> writes;  // (image id, texel id)
    } walk;
    auto instruction = [](void* user, const spv_parsed_instruction_t* in) -> spv_result_t {
        Walk& w = *static_cast<Walk*>(user);
        constexpr uint16_t kOpTypeInt = 21, kOpTypeFloat = 22, kOpTypeVector = 23,
                           kOpTypeImage = 25, kOpImageWrite = 99;
        const uint32_t* words = in->words;
        if (in->opcode == kOpTypeInt || in->opcode == kOpTypeFloat)
            w.components[words[1]] = 1;
        else if (in->opcode == kOpTypeVector && in->num_words >= 4)
            w.components[words[1]] = words[3];
        else if (in->opcode == kOpTypeImage && in->num_words >= 9)
            w.imageFormat[words[1]] = words[8];
        else if (in->opcode == kOpImageWrite && in->num_words >= 4)
            w.writes.push_back({words[1], words[3]});
        if (in->result_id && in->type_id) w.resultType[in->result_id] = in->type_id;
        return SPV_SUCCESS;
    };
    if (spvBinaryParse(spirvContext(rules), &walk, spirv.data(), spirv.size(), nullptr, instruction,
                       nullptr) != SPV_SUCCESS)
        return;
    auto formatComponents = [](uint32_t f) -> uint32_t {  // spv::ImageFormat; 0 where unknown
        switch (f) {
            case 1:
            case 2:
            case 4:
            case 5:
            case 10:
            case 11:
            case 16:
            case 21:
            case 22:
            case 23:
            case 30:
            case 31:
            case 32:
            case 34:
                return 4;
            case 8:
                return 3;
            case 6:
            case 7:
            case 12:
            case 13:
            case 17:
            case 18:
            case 25:
            case 26:
            case 27:
            case 35:
            case 36:
            case 37:
                return 2;
            case 3:
            case 9:
            case 14:
            case 15:
            case 19:
            case 20:
            case 24:
            case 28:
            case 29:
            case 33:
            case 38:
            case 39:
            case 40:
            case 41:
                return 1;
            default:
                return 0;
        }
    };
    for (const auto& [image, texel] : walk.writes) {
        const auto imageType = walk.resultType.find(image), texelType = walk.resultType.find(texel);
        if (imageType == walk.resultType.end() || texelType == walk.resultType.end()) continue;
        const auto format = walk.imageFormat.find(imageType->second);
        const auto texelComponents = walk.components.find(texelType->second);
        if (format == walk.imageFormat.end() || texelComponents == walk.components.end()) continue;
        const uint32_t needed = formatComponents(format->second);
        if (texelComponents->second < needed)
            throw Error("shader '" + name + "': an image write gives " +
                        std::to_string(texelComponents->second) +
                        " component(s) to an image whose format has " + std::to_string(needed));
    }
}

}  // namespace

namespace {

// Validating and reflecting a module is most of what creating a shader costs on a software
// rasterizer (3 s of an 8 s accuracy test, measured with perf), and a process creates the same
// modules again: on each device, in each renderer, and reflection validates what
// validateShaderBinary did. What a module gave under the same rules (and stage and entry point)
// it gives again (the checks read nothing else), so successes are kept, each module whole and
// compared word for word: a hash alone could let a damaged module through. Bounded, so a program
// that streams generated shaders does not grow without end.
template <class Value>
class ModuleMemo {
public:
    std::optional<Value> find(std::span<const uint32_t> spirv, const std::string& salt) {
        std::lock_guard lock(mutex_);
        auto [first, last] = entries_.equal_range(key(spirv, salt));
        for (auto it = first; it != last; ++it)
            if (it->second.salt == salt && std::ranges::equal(it->second.words, spirv))
                return it->second.value;
        return std::nullopt;
    }
    void add(std::span<const uint32_t> spirv, const std::string& salt, Value value) {
        std::lock_guard lock(mutex_);
        if (words_ + spirv.size() > kMaxWords) return;
        words_ += spirv.size();
        entries_.emplace(
            key(spirv, salt),
            Entry{salt, std::vector<uint32_t>(spirv.begin(), spirv.end()), std::move(value)});
    }

private:
    static constexpr size_t kMaxWords = size_t(32) << 20 >> 2;  // 32 MiB of modules
    struct Entry {
        std::string salt;
        std::vector<uint32_t> words;
        Value value;
    };
    static uint64_t key(std::span<const uint32_t> spirv, const std::string& salt) {
        uint64_t h = 1469598103934665603ull;  // FNV-1a over the salt and the words
        for (char c : salt) h = (h ^ uint8_t(c)) * 1099511628211ull;
        for (uint32_t w : spirv) h = (h ^ w) * 1099511628211ull;
        return h;
    }
    std::mutex mutex_;
    std::unordered_multimap<uint64_t, Entry> entries_;
    size_t words_ = 0;
};

ModuleMemo<bool>& validatedModules() {
    static ModuleMemo<bool> memo;
    return memo;
}

// spvValidateWithOptions; friendly names (OpName in the validator's messages) cost a third of
// its time, building a name for every id, so they are asked for only to word a failure.
spv_result_t runValidator(std::span<const uint32_t> spirv, SpirvRules rules, bool friendlyNames,
                          spv_diagnostic* diagnostic) {
    struct Options {
        spv_validator_options options = spvValidatorOptionsCreate();
        explicit Options(bool names) {
            spvValidatorOptionsSetRelaxBlockLayout(options, true);
            spvValidatorOptionsSetFriendlyNames(options, names);
        }
        ~Options() { spvValidatorOptionsDestroy(options); }
    };
    static const Options quick(false), named(true);
    spv_const_binary_t binary{spirv.data(), spirv.size()};
    return spvValidateWithOptions(spirvContext(rules), (friendlyNames ? named : quick).options,
                                  &binary, diagnostic);
}

}  // namespace

void validateSpirv(std::span<const uint32_t> spirv, SpirvRules rules, const std::string& name) {
    const std::string what = std::string("shader '") + name + "': not a valid SPIR-V module" +
                             (rules == SpirvRules::OpenGL45    ? " for OpenGL"
                              : rules == SpirvRules::Universal ? ""
                                                               : " for Vulkan") +
                             ": ";
    // The header's schema word is 0 (the validator lets any value through; Mesa refuses others).
    if (spirv.size() >= 5 && spirv[4] != 0)
        throw Error(what + "header word 4 (schema) is " + std::to_string(spirv[4]) + ", not 0");
    const std::string salt(1, char('0' + int(rules)));
    if (validatedModules().find(spirv, salt)) return;
    if (runValidator(spirv, rules, false, nullptr) == SPV_SUCCESS) {
        checkLocationLiterals(spirv, name);
        checkDistanceArrays(spirv, name);
        checkImageWrites(spirv, rules, name);
        validatedModules().add(spirv, salt, true);
        return;
    }
    spv_diagnostic diagnostic = nullptr;
    runValidator(spirv, rules, true, &diagnostic);
    const std::string why =
        diagnostic && diagnostic->error ? diagnostic->error : "rejected by the SPIR-V validator";
    spvDiagnosticDestroy(diagnostic);
    throw Error(what + why);
}

namespace {

SpvExecutionModel executionModel(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex:
            return SpvExecutionModelVertex;
        case ShaderStage::TessControl:
            return SpvExecutionModelTessellationControl;
        case ShaderStage::TessEvaluation:
            return SpvExecutionModelTessellationEvaluation;
        case ShaderStage::Geometry:
            return SpvExecutionModelGeometry;
        case ShaderStage::Fragment:
            return SpvExecutionModelFragment;
        default:
            return SpvExecutionModelGLCompute;
    }
}

// The module (valid here) declares an entry point of this name for this stage.
void checkEntryPoint(std::span<const uint32_t> spirv, ShaderStage stage, const char* entryPoint,
                     const std::string& name) {
    constexpr uint32_t kOpEntryPoint = 15;
    const uint32_t model = uint32_t(executionModel(stage));
    const std::string_view wanted = entryPoint ? entryPoint : "main";
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size()) break;
        if (op == kOpEntryPoint && words >= 4 && spirv[i + 1] == model) {
            // The name: a nul-terminated UTF-8 literal packed from word 3 on.
            const auto* bytes = reinterpret_cast<const char*>(&spirv[i + 3]);
            const size_t room = (words - 3) * 4;
            if (std::string_view(bytes, strnlen(bytes, room)) == wanted) return;
        }
        i += words;
    }
    throw Error("shader '" + name + "': no " + shaderStageName(stage) + " entry point '" +
                std::string(wanted) + "'");
}

// The capabilities a module may declare: what every device of the API offers with the features
// the backends enable (a declared one the device lacks is a validation-layer error on Vulkan,
// found by the capture-file fuzzer: CullDistance without shaderCullDistance). GL SPIR-V may use
// draw parameters (ARB_shader_draw_parameters); Vulkan's need a feature the device leaves off.
void checkCapabilities(std::span<const uint32_t> spirv, bool vulkan, const DeviceFeatures& features,
                       const std::string& name) {
    constexpr uint32_t kOpCapability = 17;
    enum : uint32_t {
        Matrix = 0,
        Shader = 1,
        Geometry = 2,
        Tessellation = 3,
        ClipDistance = 32,
        CullDistance = 33,
        ImageCubeArray = 34,
        Sampled1D = 43,
        Image1D = 44,
        SampledCubeArray = 45,
        SampledBuffer = 46,
        ImageBuffer = 47,
        ImageQuery = 50,
        DerivativeControl = 51,
        StorageImageExtendedFormats = 49,
        InterpolationFunction = 52,
        DrawParameters = 4427
    };
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size()) break;
        if (op == kOpCapability && words == 2) {
            const uint32_t c = spirv[i + 1];
            bool offered = false;
            switch (c) {
                case Matrix:
                case Shader:
                case Sampled1D:
                case Image1D:
                case SampledBuffer:
                case ImageBuffer:
                case ImageQuery:
                case DerivativeControl:
                case InterpolationFunction:
                    offered = true;
                    break;
                case ImageCubeArray:
                case SampledCubeArray:
                    offered = features.textureCubeArray;
                    break;
                case DrawParameters:
                    offered = !vulkan;
                    break;
                case StorageImageExtendedFormats:  // formatCaps(f).storage says the same per format
                    offered = features.storageImageExtendedFormats;
                    break;
                case Geometry:
                    offered = features.geometryShaders;
                    break;
                case Tessellation:
                    offered = features.tessellationShaders;
                    break;
                default:
                    break;
            }
            if (!offered) {
                const char* known = c == ClipDistance       ? " (ClipDistance)"
                                    : c == CullDistance     ? " (CullDistance)"
                                    : c == DrawParameters   ? " (DrawParameters)"
                                    : c == ImageCubeArray   ? " (ImageCubeArray)"
                                    : c == SampledCubeArray ? " (SampledCubeArray)"
                                    : c == StorageImageExtendedFormats
                                        ? " (StorageImageExtendedFormats)"
                                    : c == Geometry     ? " (Geometry)"
                                    : c == Tessellation ? " (Tessellation)"
                                                        : "";
                throw Error("shader '" + name + "': its " + (vulkan ? "Vulkan" : "OpenGL") +
                            " SPIR-V declares capability " + std::to_string(c) + known +
                            ", which the device does not offer");
            }
        }
        i += words;
    }
}

}  // namespace

void validateShaderBinary(const ShaderDesc& desc, SpirvRules vulkanRules,
                          const DeviceFeatures& features) {
    constexpr uint32_t kSpirvMagic = 0x07230203;
    const std::string name = desc.binary.name ? desc.binary.name : "";
    struct Half {
        std::span<const uint32_t> words;
        SpirvRules rules;
        const char* api;
    };
    for (const Half& half : {Half{desc.binary.vulkan, vulkanRules, "Vulkan"},
                             Half{desc.binary.opengl, SpirvRules::OpenGL45, "OpenGL"}}) {
        if (half.words.empty()) continue;
        if (half.words.size() < 5 || half.words[0] != kSpirvMagic)
            throw Error("shader '" + name + "': not a SPIR-V binary for " + half.api + " (" +
                        std::to_string(half.words.size()) + " words, missing magic number)");
        validateSpirv(half.words, half.rules, name);
        checkCapabilities(half.words, half.rules != SpirvRules::OpenGL45, features, name);
        checkEntryPoint(half.words, desc.stage, desc.entryPoint, name);
    }
}

// Some of SPIRV-Cross's C API entry points let its C++ exceptions through (set_entry_point on a
// valid module whose entry point is of another stage, say): reflectShader turns them into Error.
// The members of the struct `typeId` at `base` bytes, named from `prefix`, appended to `out`
// (BlockMember): nested structs by path, arrays of structs element by element up to 64.
static void reflectMembers(spvc_compiler comp, spvc_type_id typeId, uint32_t base,
                           const std::string& prefix, std::vector<BlockMember>& out) {
    const spvc_type type = spvc_compiler_get_type_handle(comp, typeId);
    const unsigned count = spvc_type_get_num_member_types(type);
    for (unsigned i = 0; i < count; ++i) {
        const spvc_type_id memberId = spvc_type_get_member_type(type, i);
        const spvc_type member = spvc_compiler_get_type_handle(comp, memberId);
        unsigned offset = 0;
        size_t size = 0;
        spvc_compiler_type_struct_member_offset(comp, type, i, &offset);
        spvc_compiler_get_declared_struct_member_size(comp, type, i, &size);
        const char* raw = spvc_compiler_get_member_name(comp, typeId, i);
        const std::string name = prefix + (raw && *raw ? raw : "_m" + std::to_string(i));
        const unsigned dims = spvc_type_get_num_array_dimensions(member);
        uint32_t elements = 1;
        for (unsigned d = 0; d < dims; ++d)
            elements *= spvc_type_array_dimension_is_literal(member, d)
                            ? std::max(1u, spvc_type_get_array_dimension(member, d))
                            : 0u;  // a specialization-sized array: not listed by element
        unsigned arrayStride = 0;
        if (dims) spvc_compiler_type_struct_member_array_stride(comp, type, i, &arrayStride);
        if (spvc_type_get_basetype(member) == SPVC_BASETYPE_STRUCT) {
            // The struct's own type carries its member names (an array type does not).
            const spvc_type_id structId = spvc_type_get_base_type_id(member);
            if (!dims) {
                reflectMembers(comp, structId, base + offset, name + ".", out);
                continue;
            }
            for (uint32_t e = 0; e < std::min<uint32_t>(elements, 64); ++e)
                reflectMembers(comp, structId, base + offset + e * arrayStride,
                               name + "[" + std::to_string(e) + "].", out);
            continue;
        }
        BlockMember m{.name = name, .offset = base + offset, .size = uint32_t(size)};
        switch (spvc_type_get_basetype(member)) {
            case SPVC_BASETYPE_FP32:
                m.kind = ScalarKind::Float;
                break;
            case SPVC_BASETYPE_INT32:
                m.kind = ScalarKind::Int;
                break;
            case SPVC_BASETYPE_UINT32:
                m.kind = ScalarKind::Uint;
                break;
            default:
                m.kind = ScalarKind::Other;
                break;
        }
        m.vectorSize = std::max(1u, spvc_type_get_vector_size(member));
        m.columns = std::max(1u, spvc_type_get_columns(member));
        if (m.columns > 1) {
            unsigned stride = 0;
            spvc_compiler_type_struct_member_matrix_stride(comp, type, i, &stride);
            m.matrixStride = stride;
            m.rowMajor =
                spvc_compiler_has_member_decoration(comp, typeId, i, SpvDecorationRowMajor);
        }
        if (dims) m.arrayCount = elements, m.arrayStride = arrayStride;
        out.push_back(std::move(m));
    }
}

static ShaderInterface reflectUnguarded(std::span<const uint32_t> spirv, ShaderStage stage,
                                        const char* entryPoint, const std::string& name,
                                        SpirvRules rules) {
    Context c;
    auto fail = [&](const std::string& what) -> Error {
        const char* detail = c.ctx ? spvc_context_get_last_error_string(c.ctx) : "";
        return Error("shader '" + name + "': " + what +
                     (detail && *detail ? std::string(": ") + detail : std::string()));
    };
    if (!c.ctx) throw fail("SPIRV-Cross could not start");
    validateSpirv(spirv, rules, name);
    spvc_parsed_ir ir = nullptr;
    spvc_compiler comp = nullptr;
    if (spvc_context_parse_spirv(c.ctx, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS)
        throw fail("not a valid SPIR-V module");
    if (spvc_context_create_compiler(c.ctx, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &comp) != SPVC_SUCCESS)
        throw fail("SPIR-V reflection failed");
    const SpvExecutionModel model = executionModel(stage);
    if (spvc_compiler_set_entry_point(comp, entryPoint ? entryPoint : "main", model) !=
        SPVC_SUCCESS)
        throw fail(std::string("no ") + shaderStageName(stage) + " entry point '" +
                   (entryPoint ? entryPoint : "main") + "'");
    spvc_set active = nullptr;
    spvc_resources res = nullptr;
    if (spvc_compiler_get_active_interface_variables(comp, &active) != SPVC_SUCCESS ||
        spvc_compiler_create_shader_resources_for_active_variables(comp, &res, active) !=
            SPVC_SUCCESS)
        throw fail("SPIR-V reflection failed");

    ShaderInterface out;
    out.stage = stage;
    auto each = [&](spvc_resource_type type, auto&& f) {
        const spvc_reflected_resource* list = nullptr;
        size_t count = 0;
        spvc_resources_get_resource_list_for_type(res, type, &list, &count);
        for (size_t i = 0; i < count; ++i) f(list[i]);
    };
    auto declaredSize = [&](spvc_type_id type) {
        size_t size = 0;
        spvc_compiler_get_declared_struct_size(comp, spvc_compiler_get_type_handle(comp, type),
                                               &size);
        return size;
    };
    auto binding = [&](BindingType type) {
        return [&, type](const spvc_reflected_resource& r) {
            const uint32_t set =
                spvc_compiler_get_decoration(comp, r.id, SpvDecorationDescriptorSet);
            if (set != 0)
                throw fail("'" + std::string(r.name) + "' is in descriptor set " +
                           std::to_string(set) +
                           "; the device binds set 0 only (layout(binding = slot))");
            const uint32_t slot = spvc_compiler_get_decoration(comp, r.id, SpvDecorationBinding);
            if (type == BindingType::UniformBuffer &&
                slot == kConstantsGlBinding) {  // FE_CONSTANTS on GL
                out.pushConstantBytes = uint32_t(declaredSize(r.base_type_id));
                return;
            }
            uint8_t dimension = 0;
            if (type == BindingType::SampledTexture || type == BindingType::StorageTexture) {
                const spvc_type t = spvc_compiler_get_type_handle(comp, r.base_type_id);
                const bool arrayed = spvc_type_get_image_arrayed(t);
                if (spvc_type_get_image_multisampled(t)) {
                    // texelFetch of one sample: sampled textures only (no multisampled storage)
                    if (type == BindingType::SampledTexture && !arrayed &&
                        spvc_type_get_image_dimension(t) == SpvDim2D)
                        dimension = kTexture2DMultisampleKind;
                } else
                    switch (spvc_type_get_image_dimension(t)) {
                        case SpvDim2D:
                            dimension = 1 + uint8_t(arrayed ? TextureDimension::Texture2DArray
                                                            : TextureDimension::Texture2D);
                            break;
                        case SpvDimCube:
                            dimension = 1 + uint8_t(arrayed ? TextureDimension::TextureCubeArray
                                                            : TextureDimension::TextureCube);
                            break;
                        case SpvDim3D:
                            dimension = 1 + uint8_t(TextureDimension::Texture3D);
                            break;
                        default:
                            break;
                    }
                // No texture of the device can be bound there: refused here, not left to the draw
                // (Vulkan's validation layer complained, GL read zeros).
                if (dimension == 0)
                    throw fail(
                        "'" + std::string(r.name) + "' is a " +
                        (spvc_type_get_image_multisampled(t) ? "multisampled array or storage"
                                                             : "1D or buffer") +
                        " texture, which the device has none of: bind 2D, 2D array, cube, cube array, "
                        "3D or multisampled 2D (sampler2DMS) textures");
            }
            ShaderInterface::Binding b{slot, type, r.name, dimension};
            if (type == BindingType::UniformBuffer || type == BindingType::StorageBuffer) {
                b.blockBytes = uint32_t(declaredSize(r.base_type_id));
                reflectMembers(comp, r.base_type_id, 0, "", b.members);
            }
            out.bindings.push_back(std::move(b));
        };
    };
    each(SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, binding(BindingType::UniformBuffer));
    each(SPVC_RESOURCE_TYPE_STORAGE_BUFFER, binding(BindingType::StorageBuffer));
    each(SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, binding(BindingType::SampledTexture));
    each(SPVC_RESOURCE_TYPE_STORAGE_IMAGE, binding(BindingType::StorageTexture));
    for (spvc_resource_type t :
         {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS})
        each(t, [&](const spvc_reflected_resource& r) {
            throw fail("'" + std::string(r.name) +
                       "' is a separate image or sampler; the device binds combined "
                       "image samplers (sampler2D and the like)");
        });
    // Stage inputs and outputs stay within the 16 locations (64 components) every Vulkan and GL
    // 4.5 device has; beyond that the pipeline would be the driver's error, not ours. Every
    // interface variable counts, used or not (as the drivers count them).
    // Tessellation and geometry stages see one element per vertex of the patch or primitive: that
    // outermost array (SPIRV-Cross lists it last) takes no locations of its own. Per-patch
    // variables (`patch out`) are not arrays of vertices.
    auto perVertexDimensions = [&](const spvc_reflected_resource& r, bool input) -> unsigned {
        const bool arrayed =
            (stage == ShaderStage::TessControl) ||
            (input && (stage == ShaderStage::TessEvaluation || stage == ShaderStage::Geometry));
        return arrayed && !spvc_compiler_has_decoration(comp, r.id, SpvDecorationPatch) ? 1u : 0u;
    };
    auto locationsOf = [&](const spvc_reflected_resource& r, bool input) {
        const spvc_type t = spvc_compiler_get_type_handle(comp, r.type_id);
        uint64_t locations = std::max(1u, spvc_type_get_columns(t));
        const unsigned dims = spvc_type_get_num_array_dimensions(t);
        const unsigned skip = std::min(dims, perVertexDimensions(r, input));
        for (unsigned d = 0; d + skip < dims; ++d)
            locations *= std::max<uint64_t>(1, spvc_type_get_array_dimension(t, d));
        return locations;
    };
    bool checkingInputs = true;
    auto checkLocations = [&](const spvc_reflected_resource& r) {
        const uint32_t location = spvc_compiler_get_decoration(comp, r.id, SpvDecorationLocation);
        const uint64_t locations = locationsOf(r, checkingInputs);
        if (uint64_t(location) + locations > kMaxInterfaceLocations)
            throw fail("'" + std::string(r.name) + "' at location " + std::to_string(location) +
                       " takes locations up to " +
                       std::to_string(uint64_t(location) + locations - 1) + "; every device has " +
                       std::to_string(kMaxInterfaceLocations) + " (0 to " +
                       std::to_string(kMaxInterfaceLocations - 1) + ")");
    };
    spvc_resources all = nullptr;
    if (spvc_compiler_create_shader_resources(comp, &all) != SPVC_SUCCESS)
        throw fail("SPIR-V reflection failed");
    for (spvc_resource_type type :
         {SPVC_RESOURCE_TYPE_STAGE_INPUT, SPVC_RESOURCE_TYPE_STAGE_OUTPUT}) {
        const spvc_reflected_resource* list = nullptr;
        size_t count = 0;
        spvc_resources_get_resource_list_for_type(all, type, &list, &count);
        checkingInputs = type == SPVC_RESOURCE_TYPE_STAGE_INPUT;
        for (size_t i = 0; i < count; ++i) checkLocations(list[i]);
    }
    auto variable = [&](std::vector<ShaderInterface::Variable>& into, bool input) {
        return [&, input](const spvc_reflected_resource& r) {
            const spvc_type t = spvc_compiler_get_type_handle(comp, r.type_id);
            const uint32_t location =
                spvc_compiler_get_decoration(comp, r.id, SpvDecorationLocation);
            const bool patch = spvc_compiler_has_decoration(comp, r.id, SpvDecorationPatch);
            into.push_back({location, kindOf(spvc_type_get_basetype(t)),
                            spvc_type_get_vector_size(t), r.name, uint32_t(locationsOf(r, input)),
                            patch});
        };
    };
    each(SPVC_RESOURCE_TYPE_STAGE_INPUT, variable(out.inputs, true));
    each(SPVC_RESOURCE_TYPE_STAGE_OUTPUT, variable(out.outputs, false));
    each(SPVC_RESOURCE_TYPE_PUSH_CONSTANT, [&](const spvc_reflected_resource& r) {
        out.pushConstantBytes = uint32_t(declaredSize(r.base_type_id));
    });
    const spvc_specialization_constant* specs = nullptr;
    size_t specCount = 0;
    spvc_compiler_get_specialization_constants(comp, &specs, &specCount);
    for (size_t i = 0; i < specCount; ++i) {
        const spvc_constant c = spvc_compiler_get_constant_handle(comp, specs[i].id);
        const spvc_basetype base =
            spvc_type_get_basetype(spvc_compiler_get_type_handle(comp, spvc_constant_get_type(c)));
        const char* name = spvc_compiler_get_name(comp, specs[i].id);
        const bool word = base == SPVC_BASETYPE_FP32 || base == SPVC_BASETYPE_INT32 ||
                          base == SPVC_BASETYPE_UINT32;
        out.specConstants.push_back({specs[i].constant_id, word ? kindOf(base) : ScalarKind::Other,
                                     base == SPVC_BASETYPE_BOOLEAN, name ? name : ""});
    }
    if (stage == ShaderStage::Fragment)  // OpDecorate %v BuiltIn SampleMask
        for (size_t i = 5; i + 3 < spirv.size() && (spirv[i] >> 16) != 0; i += spirv[i] >> 16)
            if (spirv[i] == (4u << 16 | 71u) && spirv[i + 2] == 11 && spirv[i + 3] == 20)
                out.writesSampleMask = true;
    if (stage == ShaderStage::Compute)
        for (uint32_t i = 0; i < 3; ++i)
            out.workgroupSize[i] = spvc_compiler_get_execution_mode_argument_by_index(
                comp, SpvExecutionModeLocalSize, i);
    auto bySlot = [](const auto& a, const auto& b) { return a.slot < b.slot; };
    auto byLocation = [](const auto& a, const auto& b) { return a.location < b.location; };
    std::sort(out.bindings.begin(), out.bindings.end(), bySlot);
    std::sort(out.inputs.begin(), out.inputs.end(), byLocation);
    std::sort(out.outputs.begin(), out.outputs.end(), byLocation);
    std::sort(out.specConstants.begin(), out.specConstants.end(),
              [](const auto& a, const auto& b) { return a.id < b.id; });
    return out;
}

std::vector<uint32_t> withNamesPrefixed(std::span<const uint32_t> spirv,
                                        const std::string& prefix) {
    constexpr uint32_t kOpName = 5;
    std::vector<uint32_t> out(spirv.begin(), spirv.begin() + std::min<size_t>(5, spirv.size()));
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size())
            throw Error("SPIR-V instruction stream is damaged at word " + std::to_string(i));
        if (op == kOpName && words >= 3 &&
            spirv[i + 2] != 0) {  // an empty name stays empty (anonymous)
            // OpName <target> "string": a nul-terminated UTF-8 literal padded to whole words.
            const char* old = reinterpret_cast<const char*>(&spirv[i + 2]);
            const std::string name = prefix + std::string(old, strnlen(old, size_t(words - 2) * 4));
            const size_t literalWords = name.size() / 4 + 1;
            out.push_back(uint32_t((2 + literalWords) << 16) | kOpName);
            out.push_back(spirv[i + 1]);
            const size_t at = out.size();
            out.resize(at + literalWords, 0);
            std::memcpy(&out[at], name.data(), name.size());
        } else {
            out.insert(out.end(), spirv.begin() + long(i), spirv.begin() + long(i + words));
        }
        i += words;
    }
    return out;
}

// SPIRV-Cross knows where each decoration's literal sits in the module (the word offset it
// reports is the one to patch), so the renumbering needs no instruction walk of its own.
std::vector<uint32_t> withStorageTextureSlots(std::span<const uint32_t> spirv,
                                              const std::array<uint8_t, 64>& newSlot) {
    std::vector<uint32_t> out(spirv.begin(), spirv.end());
    Context c;
    spvc_parsed_ir ir = nullptr;
    spvc_compiler comp = nullptr;
    spvc_resources all = nullptr;
    if (!c.ctx ||
        spvc_context_parse_spirv(c.ctx, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS ||
        spvc_context_create_compiler(c.ctx, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &comp) != SPVC_SUCCESS ||
        spvc_compiler_create_shader_resources(comp, &all) != SPVC_SUCCESS)
        throw Error("SPIR-V reflection failed while renumbering storage textures");
    const spvc_reflected_resource* list = nullptr;
    size_t count = 0;
    spvc_resources_get_resource_list_for_type(all, SPVC_RESOURCE_TYPE_STORAGE_IMAGE, &list, &count);
    for (size_t i = 0; i < count; ++i) {
        const uint32_t slot = spvc_compiler_get_decoration(comp, list[i].id, SpvDecorationBinding);
        uint32_t offset = 0;
        if (slot < newSlot.size() && newSlot[slot] != 0xff &&
            spvc_compiler_get_binary_offset_for_decoration(comp, list[i].id, SpvDecorationBinding,
                                                           &offset) &&
            offset < out.size())
            out[offset] = newSlot[slot];
    }
    return out;
}

ShaderInterface reflectShader(std::span<const uint32_t> spirv, ShaderStage stage,
                              const char* entryPoint, const std::string& name, SpirvRules rules) {
    static ModuleMemo<ShaderInterface> reflected;  // see ModuleMemo: a success is kept
    const std::string salt = std::to_string(int(rules)) + "/" + std::to_string(int(stage)) + "/" +
                             (entryPoint ? entryPoint : "main");
    if (std::optional<ShaderInterface> known = reflected.find(spirv, salt)) return *known;
    try {
        ShaderInterface iface = reflectUnguarded(spirv, stage, entryPoint, name, rules);
        reflected.add(spirv, salt, iface);
        return iface;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("shader '" + name + "': SPIR-V reflection failed: " + e.what());
    }
}

}  // namespace fe::gdi
