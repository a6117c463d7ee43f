#include "CaptureJson.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace fe::gdi::capture {

namespace {

[[noreturn]] void bad(const char* key, const std::string& why) {
    throw std::runtime_error(std::string("field '") + key + "' " + why);
}
const json& at(const json& j, const char* key) {
    if (!j.is_object())
        throw std::runtime_error(std::string("expected an object holding '") + key + "'");
    const auto it = j.find(key);
    if (it == j.end()) bad(key, "is missing");
    return *it;
}
bool flag(const json& j, const char* key) {
    const json& v = at(j, key);
    if (!v.is_boolean()) bad(key, "is not a boolean");
    return v.get<bool>();
}
float real(const json& j, const char* key) {
    const json& v = at(j, key);
    if (!v.is_number()) bad(key, "is not a number");
    const double d = v.get<double>();
    // Descriptions hold finite floats; anything else (or beyond float range) is damage.
    if (!(std::abs(d) <= double(std::numeric_limits<float>::max())))
        bad(key, "is not a finite float");
    return float(d);
}
// An enum stored as its value, which must be at most `last`.
template <class E>
E enumValue(const json& j, const char* key, E last) {
    const uint64_t v = u64(j, key);
    if (v > uint64_t(last)) bad(key, "has no such value (" + std::to_string(v) + ")");
    return E(v);
}
// Flags stored as their bits, which must lie in `all`.
template <class E>
E flags(const json& j, const char* key, E all) {
    const uint64_t v = u64(j, key);
    if (v & ~uint64_t(all)) bad(key, "has unknown bits (" + std::to_string(v) + ")");
    return E(v);
}
const json& array(const json& j, const char* key) {
    const json& v = at(j, key);
    if (!v.is_array()) bad(key, "is not an array");
    return v;
}
template <class E>
uint64_t raw(E e) {
    return uint64_t(e);
}
void putName(json& j, const char* name) {
    if (name) j["name"] = name;
}
constexpr BufferUsage kAllBufferUsage = BufferUsage(127);
constexpr TextureUsage kAllTextureUsage =
    TextureUsage((uint32_t(TextureUsage::Transient) << 1) - 1);
constexpr Format kLastFormat = Format(uint32_t(Format::Count) - 1);

json toJson(const StencilFaceState& s) {
    return {{"fail", raw(s.failOp)},
            {"depthFail", raw(s.depthFailOp)},
            {"pass", raw(s.passOp)},
            {"compare", raw(s.compare)}};
}
StencilFaceState stencilFace(const json& j) {
    return {.failOp = enumValue(j, "fail", StencilOp::DecrementWrap),
            .depthFailOp = enumValue(j, "depthFail", StencilOp::DecrementWrap),
            .passOp = enumValue(j, "pass", StencilOp::DecrementWrap),
            .compare = enumValue(j, "compare", CompareOp::Always)};
}
json toJson(const std::vector<BindingSlot>& bindings) {
    json a = json::array();
    for (const BindingSlot& b : bindings)
        a.push_back({{"slot", b.slot}, {"type", raw(b.type)}, {"stages", raw(b.stages)}});
    return a;
}
std::vector<BindingSlot> bindingSlots(const json& j) {
    std::vector<BindingSlot> out;
    for (const json& b : array(j, "bindings"))
        out.push_back({.slot = u32(b, "slot"),
                       .type = enumValue(b, "type", BindingType::StorageTexture),
                       .stages = flags(b, "stages", ShaderStage::All)});
    return out;
}
json toJson(const std::vector<SpecializationConstant>& s) {
    json a = json::array();
    for (const SpecializationConstant& c : s) a.push_back({c.id, c.bits});
    return a;
}
std::vector<SpecializationConstant> specialization(const json& j) {
    std::vector<SpecializationConstant> out;
    for (const json& c : array(j, "specialization")) {
        if (!c.is_array() || c.size() != 2 || !c[0].is_number_unsigned() ||
            !c[1].is_number_unsigned() || c[0].get<uint64_t>() > UINT32_MAX ||
            c[1].get<uint64_t>() > UINT32_MAX)
            bad("specialization", "holds something other than [id, bits] pairs");
        out.push_back({c[0].get<uint32_t>(), c[1].get<uint32_t>()});
    }
    return out;
}
json formats(const std::vector<Format>& f) {
    json a = json::array();
    for (Format x : f) a.push_back(raw(x));
    return a;
}
std::vector<Format> formatList(const json& j, const char* key) {
    std::vector<Format> out;
    for (const json& f : array(j, key)) {
        if (!f.is_number_unsigned() || f.get<uint64_t>() > uint64_t(kLastFormat))
            bad(key, "holds an unknown format");
        out.push_back(Format(f.get<uint32_t>()));
    }
    return out;
}

}  // namespace

uint64_t u64(const json& j, const char* key) {
    const json& v = at(j, key);
    if (!v.is_number_unsigned()) bad(key, "is not an unsigned integer");
    return v.get<uint64_t>();
}
uint32_t u32(const json& j, const char* key) {
    const uint64_t v = u64(j, key);
    if (v > UINT32_MAX) bad(key, "is out of range");
    return uint32_t(v);
}
const char* text(const json& j, const char* key, Strings& keep) {
    const auto it = j.find(key);
    if (it == j.end()) return nullptr;
    if (!it->is_string()) bad(key, "is not a string");
    return keep.emplace_back(it->get<std::string>()).c_str();
}
ShaderStage shaderStage(const json& j) { return flags(j, "stage", ShaderStage::All); }

json toJson(const BufferDesc& d) {
    json j = {{"size", d.size}, {"usage", raw(d.usage)}, {"access", raw(d.access)}};
    putName(j, d.debugName);
    return j;
}
BufferDesc bufferDesc(const json& j, Strings& keep) {
    return {.size = u64(j, "size"),
            .usage = flags(j, "usage", kAllBufferUsage),
            .access = enumValue(j, "access", MemoryAccess::Readback),
            .debugName = text(j, "name", keep)};
}

json toJson(const TextureDesc& d) {
    json j = {{"dimension", raw(d.dimension)},
              {"format", raw(d.format)},
              {"width", d.width},
              {"height", d.height},
              {"depthOrLayers", d.depthOrLayers},
              {"mips", d.mipLevels},
              {"samples", d.sampleCount},
              {"usage", raw(d.usage)},
              {"heap", d.heap.id},
              {"heapOffset", d.heapOffset},
              {"viewFormats", formats(d.viewFormats)}};
    putName(j, d.debugName);
    return j;
}
TextureDesc textureDesc(const json& j, Strings& keep) {
    return {.dimension = enumValue(j, "dimension", TextureDimension::Texture3D),
            .format = enumValue(j, "format", kLastFormat),
            .width = u32(j, "width"),
            .height = u32(j, "height"),
            .depthOrLayers = u32(j, "depthOrLayers"),
            .mipLevels = u32(j, "mips"),
            .sampleCount = u32(j, "samples"),
            .usage = flags(j, "usage", kAllTextureUsage),
            .heap = {u32(j, "heap")},
            .heapOffset = u64(j, "heapOffset"),
            .viewFormats = formatList(j, "viewFormats"),
            .debugName = text(j, "name", keep)};
}

json toJson(const TextureViewDesc& d) {
    json j = {
        {"format", raw(d.format)},
        {"baseMip", d.baseMip},
        {"mipCount", d.mipCount},
        {"baseLayer", d.baseLayer},
        {"layerCount", d.layerCount},
        {"swizzle", {raw(d.swizzle[0]), raw(d.swizzle[1]), raw(d.swizzle[2]), raw(d.swizzle[3])}}};
    if (d.dimension) j["dimension"] = raw(*d.dimension);
    putName(j, d.debugName);
    return j;
}
TextureViewDesc textureViewDesc(const json& j, Strings& keep) {
    TextureViewDesc d{.format = enumValue(j, "format", kLastFormat),
                      .baseMip = u32(j, "baseMip"),
                      .mipCount = u32(j, "mipCount"),
                      .baseLayer = u32(j, "baseLayer"),
                      .layerCount = u32(j, "layerCount"),
                      .debugName = text(j, "name", keep)};
    if (j.contains("dimension"))
        d.dimension = enumValue(j, "dimension", TextureDimension::Texture3D);
    const json& s = array(j, "swizzle");
    if (s.size() != 4) bad("swizzle", "does not hold 4 values");
    for (size_t i = 0; i < 4; ++i) {
        if (!s[i].is_number_unsigned() || s[i].get<uint64_t>() > uint64_t(Swizzle::A))
            bad("swizzle", "holds an unknown value");
        d.swizzle[i] = Swizzle(s[i].get<uint32_t>());
    }
    return d;
}

json toJson(const SamplerDesc& d) {
    json j = {{"min", raw(d.minFilter)},
              {"mag", raw(d.magFilter)},
              {"mip", raw(d.mipFilter)},
              {"u", raw(d.addressU)},
              {"v", raw(d.addressV)},
              {"w", raw(d.addressW)},
              {"anisotropy", d.maxAnisotropy},
              {"compareEnable", d.compareEnable},
              {"compare", raw(d.compare)},
              {"border", raw(d.borderColor)},
              {"lodBias", d.lodBias},
              {"minLod", d.minLod},
              {"maxLod", d.maxLod}};
    putName(j, d.debugName);
    return j;
}
SamplerDesc samplerDesc(const json& j, Strings& keep) {
    return {.minFilter = enumValue(j, "min", Filter::Linear),
            .magFilter = enumValue(j, "mag", Filter::Linear),
            .mipFilter = enumValue(j, "mip", MipFilter::Linear),
            .addressU = enumValue(j, "u", AddressMode::ClampToBorder),
            .addressV = enumValue(j, "v", AddressMode::ClampToBorder),
            .addressW = enumValue(j, "w", AddressMode::ClampToBorder),
            .maxAnisotropy = real(j, "anisotropy"),
            .compareEnable = flag(j, "compareEnable"),
            .compare = enumValue(j, "compare", CompareOp::Always),
            .borderColor = enumValue(j, "border", BorderColor::OpaqueWhite),
            .lodBias = real(j, "lodBias"),
            .minLod = real(j, "minLod"),
            .maxLod = real(j, "maxLod"),
            .debugName = text(j, "name", keep)};
}

json toJson(const GraphicsPipelineDesc& d) {
    json vb = json::array();
    for (const VertexBufferLayout& b : d.vertexBuffers) {
        json attrs = json::array();
        for (const VertexAttribute& a : b.attributes)
            attrs.push_back({a.location, raw(a.format), a.offset});
        vb.push_back({{"stride", b.stride}, {"perInstance", b.perInstance}, {"attributes", attrs}});
    }
    json blend = json::array();
    for (const BlendTargetState& b : d.blend)
        blend.push_back({{"enable", b.enable},
                         {"srcColor", raw(b.srcColor)},
                         {"dstColor", raw(b.dstColor)},
                         {"colorOp", raw(b.colorOp)},
                         {"srcAlpha", raw(b.srcAlpha)},
                         {"dstAlpha", raw(b.dstAlpha)},
                         {"alphaOp", raw(b.alphaOp)},
                         {"mask", raw(b.writeMask)}});
    const RasterState& r = d.raster;
    const DepthStencilState& ds = d.depthStencil;
    json j = {{"vs", d.vertexShader.id},
              {"fs", d.fragmentShader.id},
              {"vertexBuffers", vb},
              {"topology", raw(d.topology)},
              {"primitiveRestart", d.primitiveRestart},
              {"raster",
               {{"cull", raw(r.cullMode)},
                {"front", raw(r.frontFace)},
                {"biasConstant", r.depthBiasConstant},
                {"biasSlope", r.depthBiasSlope},
                {"biasClamp", r.depthBiasClamp},
                {"depthClamp", r.depthClamp}}},
              {"multisample",
               {{"samples", d.multisample.sampleCount},
                {"alphaToCoverage", d.multisample.alphaToCoverage},
                {"mask", d.multisample.sampleMask}}},
              {"depthStencil",
               {{"test", ds.depthTest},
                {"write", ds.depthWrite},
                {"compare", raw(ds.depthCompare)},
                {"stencil", ds.stencilTest},
                {"front", toJson(ds.front)},
                {"back", toJson(ds.back)},
                {"readMask", ds.stencilReadMask},
                {"writeMask", ds.stencilWriteMask},
                {"reference", ds.stencilReference}}},
              {"blend", blend},
              {"blendConstant",
               {d.blendConstant[0], d.blendConstant[1], d.blendConstant[2], d.blendConstant[3]}},
              {"colorFormats", formats(d.colorFormats)},
              {"depthFormat", raw(d.depthFormat)},
              {"bindings", toJson(d.bindings)},
              {"specialization", toJson(d.specialization)}};
    // The optional stages only when used, so captures without them read as before.
    if (d.geometryShader) j["gs"] = d.geometryShader.id;
    if (d.tessControlShader || d.tessEvaluationShader) {
        j["tcs"] = d.tessControlShader.id;
        j["tes"] = d.tessEvaluationShader.id;
    }
    if (d.patchControlPoints) j["patchControlPoints"] = d.patchControlPoints;
    putName(j, d.debugName);
    return j;
}
GraphicsPipelineDesc graphicsPipelineDesc(const json& j, Strings& keep) {
    GraphicsPipelineDesc d;
    d.vertexShader = {u32(j, "vs")};
    d.fragmentShader = {u32(j, "fs")};
    if (j.contains("gs")) d.geometryShader = {u32(j, "gs")};
    if (j.contains("tcs")) d.tessControlShader = {u32(j, "tcs")};
    if (j.contains("tes")) d.tessEvaluationShader = {u32(j, "tes")};
    if (j.contains("patchControlPoints")) d.patchControlPoints = u32(j, "patchControlPoints");
    for (const json& b : array(j, "vertexBuffers")) {
        VertexBufferLayout l{.stride = u32(b, "stride"), .perInstance = flag(b, "perInstance")};
        for (const json& a : array(b, "attributes")) {
            if (!a.is_array() || a.size() != 3)
                bad("attributes", "holds something other than [location, format, offset]");
            const json named = {{"location", a[0]}, {"format", a[1]}, {"offset", a[2]}};
            l.attributes.push_back(
                {.location = u32(named, "location"),
                 .format =
                     enumValue(named, "format", VertexFormat(uint32_t(VertexFormat::Count) - 1)),
                 .offset = u32(named, "offset")});
        }
        d.vertexBuffers.push_back(std::move(l));
    }
    d.topology = enumValue(j, "topology", PrimitiveTopology::PatchList);
    d.primitiveRestart = flag(j, "primitiveRestart");
    const json& r = at(j, "raster");
    d.raster = {.cullMode = enumValue(r, "cull", CullMode::Back),
                .frontFace = enumValue(r, "front", FrontFace::Clockwise),
                .depthBiasConstant = real(r, "biasConstant"),
                .depthBiasSlope = real(r, "biasSlope"),
                .depthBiasClamp = real(r, "biasClamp"),
                .depthClamp = flag(r, "depthClamp")};
    const json& m = at(j, "multisample");
    d.multisample = {.sampleCount = u32(m, "samples"),
                     .alphaToCoverage = flag(m, "alphaToCoverage"),
                     .sampleMask = u32(m, "mask")};
    const json& ds = at(j, "depthStencil");
    auto byte = [&](const char* key) {
        const uint32_t v = u32(ds, key);
        if (v > 255) bad(key, "is out of range");
        return uint8_t(v);
    };
    d.depthStencil = {.depthTest = flag(ds, "test"),
                      .depthWrite = flag(ds, "write"),
                      .depthCompare = enumValue(ds, "compare", CompareOp::Always),
                      .stencilTest = flag(ds, "stencil"),
                      .front = stencilFace(at(ds, "front")),
                      .back = stencilFace(at(ds, "back")),
                      .stencilReadMask = byte("readMask"),
                      .stencilWriteMask = byte("writeMask"),
                      .stencilReference = byte("reference")};
    for (const json& b : array(j, "blend"))
        d.blend.push_back({.enable = flag(b, "enable"),
                           .srcColor = enumValue(b, "srcColor", BlendFactor::OneMinusConstantColor),
                           .dstColor = enumValue(b, "dstColor", BlendFactor::OneMinusConstantColor),
                           .colorOp = enumValue(b, "colorOp", BlendOp::Max),
                           .srcAlpha = enumValue(b, "srcAlpha", BlendFactor::OneMinusConstantColor),
                           .dstAlpha = enumValue(b, "dstAlpha", BlendFactor::OneMinusConstantColor),
                           .alphaOp = enumValue(b, "alphaOp", BlendOp::Max),
                           .writeMask = flags(b, "mask", ColorMask::All)});
    const json& bc = array(j, "blendConstant");
    if (bc.size() != 4) bad("blendConstant", "does not hold 4 numbers");
    for (size_t i = 0; i < 4; ++i) {
        d.blendConstant[i] = real(json{{"blendConstant", bc[i]}}, "blendConstant");
    }
    d.colorFormats = formatList(j, "colorFormats");
    d.depthFormat = enumValue(j, "depthFormat", kLastFormat);
    d.bindings = bindingSlots(j);
    d.specialization = specialization(j);
    d.debugName = text(j, "name", keep);
    return d;
}

json toJson(const ComputePipelineDesc& d) {
    json j = {{"cs", d.computeShader.id},
              {"bindings", toJson(d.bindings)},
              {"specialization", toJson(d.specialization)}};
    putName(j, d.debugName);
    return j;
}
ComputePipelineDesc computePipelineDesc(const json& j, Strings& keep) {
    return {.computeShader = {u32(j, "cs")},
            .bindings = bindingSlots(j),
            .specialization = specialization(j),
            .debugName = text(j, "name", keep)};
}

json toJson(const HeapDesc& d) {
    json j = {{"size", d.size}};
    putName(j, d.debugName);
    return j;
}
HeapDesc heapDesc(const json& j, Strings& keep) {
    return {.size = u64(j, "size"), .debugName = text(j, "name", keep)};
}

json toJson(const QuerySetDesc& d) {
    json j = {{"type", raw(d.type)}, {"count", d.count}};
    putName(j, d.debugName);
    return j;
}
QuerySetDesc querySetDesc(const json& j, Strings& keep) {
    return {.type = enumValue(j, "type", QueryType::Timestamp),
            .count = u32(j, "count"),
            .debugName = text(j, "name", keep)};
}

json toJson(const TextureRegion& r) {
    json j = {{"mip", r.mipLevel}, {"x", r.x},           {"y", r.y},        {"z", r.z},
              {"width", r.width},  {"height", r.height}, {"depth", r.depth}};
    if (r.aspect != TextureAspect::All) j["aspect"] = raw(r.aspect);  // older captures lack it
    return j;
}
TextureRegion textureRegion(const json& j) {
    return {.mipLevel = u32(j, "mip"),
            .x = u32(j, "x"),
            .y = u32(j, "y"),
            .z = u32(j, "z"),
            .width = u32(j, "width"),
            .height = u32(j, "height"),
            .depth = u32(j, "depth"),
            .aspect = j.contains("aspect") ? enumValue(j, "aspect", TextureAspect::Stencil)
                                           : TextureAspect::All};
}
json toJson(const TexelLayout& l) {
    return {{"offset", l.offset}, {"bytesPerRow", l.bytesPerRow}, {"rowsPerImage", l.rowsPerImage}};
}
TexelLayout texelLayout(const json& j) {
    return {.offset = u64(j, "offset"),
            .bytesPerRow = u32(j, "bytesPerRow"),
            .rowsPerImage = u32(j, "rowsPerImage")};
}

}  // namespace fe::gdi::capture
