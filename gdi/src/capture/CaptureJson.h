// Object descriptions as JSON values (stored as CBOR in capture records) and back. Reading
// checks every field's presence, type and range (enums within their values, flags within their
// bits), so a damaged record becomes an error, never an out-of-range value handed to a device.
// Handle fields keep the capturing device's ids; replay maps them.
#pragma once
#include <deque>
#include <nlohmann/json.hpp>
#include <string>

#include "fe/gdi/Device.h"

namespace fe::gdi::capture {

using nlohmann::json;
// Strings a decoded description points at (debug names, shader names), kept by the replayer.
using Strings = std::deque<std::string>;

json toJson(const BufferDesc& d);
json toJson(const TextureDesc& d);
json toJson(const TextureViewDesc& d);
json toJson(const SamplerDesc& d);
json toJson(const GraphicsPipelineDesc& d);
json toJson(const ComputePipelineDesc& d);
json toJson(const HeapDesc& d);
json toJson(const QuerySetDesc& d);
json toJson(const TextureRegion& r);
json toJson(const TexelLayout& l);

// Each throws std::runtime_error saying which field is wrong.
BufferDesc bufferDesc(const json& j, Strings& keep);
TextureDesc textureDesc(const json& j, Strings& keep);
TextureViewDesc textureViewDesc(const json& j, Strings& keep);
SamplerDesc samplerDesc(const json& j, Strings& keep);
GraphicsPipelineDesc graphicsPipelineDesc(const json& j, Strings& keep);
ComputePipelineDesc computePipelineDesc(const json& j, Strings& keep);
HeapDesc heapDesc(const json& j, Strings& keep);
QuerySetDesc querySetDesc(const json& j, Strings& keep);
TextureRegion textureRegion(const json& j);
TexelLayout texelLayout(const json& j);
ShaderStage shaderStage(const json& j);

// Field access with the checks above.
uint64_t u64(const json& j, const char* key);
uint32_t u32(const json& j, const char* key);
const char* text(const json& j, const char* key, Strings& keep);  // null when absent

}  // namespace fe::gdi::capture
