// Pipeline keys (PipelineSharing.h) from the capture format's description of a pipeline, so
// that a field added to a description and recorded by captures is part of the key as well.
#include "CaptureJson.h"
#include "fe/gdi/PipelineSharing.h"

namespace fe::gdi {

std::string pipelineKey(const GraphicsPipelineDesc& d,
                        const std::function<uint64_t(ShaderHandle)>& codeOf) {
    capture::json j = capture::toJson(d);
    for (const char* stage : {"vs", "fs", "gs", "tcs", "tes"})
        if (j.contains(stage)) j[stage] = 0;
    j["code"] = {codeOf(d.vertexShader), codeOf(d.fragmentShader), codeOf(d.geometryShader),
                 codeOf(d.tessControlShader), codeOf(d.tessEvaluationShader)};
    return j.dump();
}

std::string pipelineKey(const ComputePipelineDesc& d,
                        const std::function<uint64_t(ShaderHandle)>& codeOf) {
    capture::json j = capture::toJson(d);
    j["cs"] = codeOf(d.computeShader);
    return j.dump();
}

}  // namespace fe::gdi
