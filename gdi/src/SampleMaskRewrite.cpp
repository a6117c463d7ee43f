// withSampleMaskAsDiscard: a fragment shader's gl_SampleMask made to act on a single-sample GL
// target as it does on Vulkan. Written by hand because no listed library rewrites SPIR-V this way
// (SPIRV-Cross emits source, not modules; SPIRV-Tools is not a dependency), and the change is
// small: one variable's storage class, a few types and constants, and a test before each return.
#include <algorithm>
#include <optional>

#include "fe/gdi/ShaderReflection.h"

namespace fe::gdi {

namespace {

enum Op : uint32_t {
    OpEntryPoint = 15,
    OpTypeBool = 20,
    OpTypeInt = 21,
    OpTypeArray = 28,
    OpTypePointer = 32,
    OpConstant = 43,
    OpFunction = 54,
    OpFunctionEnd = 56,
    OpVariable = 59,
    OpLoad = 61,
    OpAccessChain = 65,
    OpInBoundsAccessChain = 66,
    OpDecorate = 71,
    OpIEqual = 170,
    OpBitwiseAnd = 199,
    OpSelectionMerge = 247,
    OpLabel = 248,
    OpBranchConditional = 250,
    OpKill = 252,
    OpReturn = 253,
};
constexpr uint32_t kBuiltIn = 11, kSampleMask = 20, kOutput = 3, kPrivate = 6, kFragment = 4;

using Instruction = std::vector<uint32_t>;

Instruction instruction(Op op, std::initializer_list<uint32_t> operands) {
    Instruction i{uint32_t(operands.size() + 1) << 16 | op};
    i.insert(i.end(), operands);
    return i;
}

struct Module {
    std::vector<uint32_t> header;
    std::vector<Instruction> code;
    uint32_t bound = 0;

    explicit Module(std::span<const uint32_t> spirv) : header(spirv.begin(), spirv.begin() + 5) {
        bound = spirv[3];
        for (size_t i = 5; i < spirv.size();) {
            const uint32_t words = spirv[i] >> 16;
            if (words == 0 || i + words > spirv.size())
                throw Error("SPIR-V instruction stream is damaged at word " + std::to_string(i));
            code.emplace_back(spirv.begin() + long(i), spirv.begin() + long(i + words));
            i += words;
        }
    }
    std::vector<uint32_t> words() {
        header[3] = bound;
        std::vector<uint32_t> out = header;
        for (const Instruction& i : code) out.insert(out.end(), i.begin(), i.end());
        return out;
    }
    // The result id (word idWord) of an existing declaration matching `match`, or of a new one
    // made by `make(id)` and queued in `declared`.
    template <class Match, class Make>
    uint32_t find(size_t idWord, Match&& match, Make&& make, std::vector<Instruction>& declared) {
        for (const auto* list : {&code, &declared})
            for (const Instruction& i : *list)
                if (match(i)) return i[idWord];
        const uint32_t id = bound++;
        declared.push_back(make(id));
        return id;
    }
};

uint32_t opOf(const Instruction& i) { return i[0] & 0xffffu; }

}  // namespace

std::vector<uint32_t> withSampleMaskAsDiscard(std::span<const uint32_t> spirv) {
    Module m(spirv);
    // The SampleMask output variable, its array type and element type.
    std::optional<uint32_t> mask;
    for (const Instruction& i : m.code)
        if (opOf(i) == OpDecorate && i.size() == 4 && i[2] == kBuiltIn && i[3] == kSampleMask)
            mask = i[1];
    if (!mask) return {spirv.begin(), spirv.end()};
    auto variable = std::find_if(m.code.begin(), m.code.end(), [&](const Instruction& i) {
        return opOf(i) == OpVariable && i.size() >= 4 && i[2] == *mask && i[3] == kOutput;
    });
    if (variable == m.code.end()) return {spirv.begin(), spirv.end()};
    auto pointeeOf = [&](uint32_t pointer) -> uint32_t {
        for (const Instruction& i : m.code)
            if (opOf(i) == OpTypePointer && i[1] == pointer) return i[3];
        throw Error("SampleMask rewrite: no pointer type %" + std::to_string(pointer));
    };
    const uint32_t arrayType = pointeeOf((*variable)[1]);
    uint32_t element = 0;
    for (const Instruction& i : m.code)
        if (opOf(i) == OpTypeArray && i[1] == arrayType) element = i[2];
    if (element == 0) throw Error("SampleMask rewrite: the SampleMask output is not an array");

    std::vector<Instruction> declared;  // new types and constants, placed before the variable
    auto privatePointer = [&](uint32_t pointee) {
        return m.find(
            1,
            [&](const Instruction& i) {
                return opOf(i) == OpTypePointer && i[2] == kPrivate && i[3] == pointee;
            },
            [&](uint32_t id) {
                return instruction(OpTypePointer, {id, kPrivate, pointee});
            },
            declared);
    };
    auto constant = [&](uint32_t value) {
        return m.find(
            2,
            [&](const Instruction& i) {
                return opOf(i) == OpConstant && i.size() == 4 && i[1] == element && i[3] == value;
            },
            [&](uint32_t id) {
                return instruction(OpConstant, {element, id, value});
            },
            declared);
    };
    const uint32_t boolType = m.find(
        1, [](const Instruction& i) { return opOf(i) == OpTypeBool; },
        [](uint32_t id) { return instruction(OpTypeBool, {id}); }, declared);
    const uint32_t zero = constant(0), one = constant(1);
    const uint32_t privateArray = privatePointer(arrayType);
    const uint32_t privateElement = privatePointer(element);

    // The variable becomes Private (no built-in): what the shader writes stays in it.
    (*variable)[1] = privateArray;
    (*variable)[3] = kPrivate;
    for (Instruction& i : m.code)
        if ((opOf(i) == OpAccessChain || opOf(i) == OpInBoundsAccessChain) && i[3] == *mask)
            i[1] = privatePointer(pointeeOf(i[1]));
    std::erase_if(m.code, [&](const Instruction& i) {
        return opOf(i) == OpDecorate && i.size() == 4 && i[1] == *mask && i[2] == kBuiltIn;
    });
    // Private variables are listed in an entry point's interface from SPIR-V 1.4 on only.
    uint32_t entry = 0;
    for (Instruction& i : m.code)
        if (opOf(i) == OpEntryPoint && i[1] == kFragment) {
            entry = i[2];
            if (m.header[1] < 0x00010400) {
                std::erase(i, *mask);
                i[0] = uint32_t(i.size()) << 16 | OpEntryPoint;
            }
        }
    // Before every return of the entry point: bit 0 of the mask clear discards the fragment.
    std::vector<Instruction> out;
    bool inEntry = false;
    for (Instruction& i : m.code) {
        if (opOf(i) == OpVariable && i[2] == *mask)
            out.insert(out.end(), declared.begin(), declared.end());
        if (opOf(i) == OpFunction) inEntry = i[2] == entry;
        if (opOf(i) == OpFunctionEnd) inEntry = false;
        if (!inEntry || opOf(i) != OpReturn) {
            out.push_back(std::move(i));
            continue;
        }
        const uint32_t p = m.bound++, value = m.bound++, bit = m.bound++, clear = m.bound++,
                       kill = m.bound++, keep = m.bound++;
        out.push_back(instruction(OpAccessChain, {privateElement, p, *mask, zero}));
        out.push_back(instruction(OpLoad, {element, value, p}));
        out.push_back(instruction(OpBitwiseAnd, {element, bit, value, one}));
        out.push_back(instruction(OpIEqual, {boolType, clear, bit, zero}));
        out.push_back(instruction(OpSelectionMerge, {keep, 0}));
        out.push_back(instruction(OpBranchConditional, {clear, kill, keep}));
        out.push_back(instruction(OpLabel, {kill}));
        out.push_back(instruction(OpKill, {}));
        out.push_back(instruction(OpLabel, {keep}));
        out.push_back(std::move(i));
    }
    m.code = std::move(out);
    return m.words();
}

}  // namespace fe::gdi
