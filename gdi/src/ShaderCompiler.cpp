#include "fe/gdi/ShaderCompiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <atomic>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "fe/gdi/ShaderReflection.h"
#include "fe_common_glsl.h"  // generated: the text of shaders/include/fe_common.glsl

namespace fe::gdi {

namespace {

std::atomic<uint64_t> compiles{0};

EShLanguage glslangStage(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex:
            return EShLangVertex;
        case ShaderStage::Fragment:
            return EShLangFragment;
        case ShaderStage::Compute:
            return EShLangCompute;
        case ShaderStage::Geometry:
            return EShLangGeometry;
        case ShaderStage::TessControl:
            return EShLangTessControl;
        case ShaderStage::TessEvaluation:
            return EShLangTessEvaluation;
        default:
            throw Error(
                "compileShader: the stage must be one of Vertex, TessControl, TessEvaluation, "
                "Geometry, Fragment, Compute, not " +
                std::string(shaderStageName(stage)));
    }
}

// glslang's includes: fe_common.glsl built in, the rest from the source's callback. The texts
// are kept (in `seen`) for the cache key and for the results glslang holds on to.
class Includer : public glslang::TShader::Includer {
public:
    explicit Includer(const ShaderSourceCompile& s) : source_(s) {}
    IncludeResult* includeLocal(const char* name, const char* includer, size_t) override {
        std::optional<std::string> text;
        if (std::strcmp(name, "fe_common.glsl") == 0)
            text = kFeCommonGlsl;
        else if (source_.include)
            text = source_.include(name, includer);
        if (!text) return nullptr;  // glslang reports the include it could not open
        seen.push_back({name, includer ? includer : "", std::move(*text)});
        const Seen& kept = seen.back();
        return new IncludeResult(kept.name, kept.text.data(), kept.text.size(), nullptr);
    }
    IncludeResult* includeSystem(const char* name, const char* includer, size_t depth) override {
        return includeLocal(name, includer, depth);
    }
    void releaseInclude(IncludeResult* result) override { delete result; }
    struct Seen {
        std::string name, includer, text;
    };
    std::deque<Seen> seen;  // a deque: the texts glslang points into stay where they are

private:
    const ShaderSourceCompile& source_;
};

// glslang's "ERROR: NAME:LINE: message" lines as "NAME:LINE: message", and the portable name
// for a built-in only one API has (what cmake/fe-glslang.sh adds to the build step's errors).
std::string errorText(const std::string& log, const std::string& name) {
    std::istringstream in(log);
    std::string out;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("ERROR: ", 0) != 0) continue;
        line = line.substr(7);
        line.erase(line.find_last_not_of(" \r") + 1);  // glslang ends its lines with a space
        if (line.find("compilation terminated") != std::string::npos ||
            line.find("compilation errors.") != std::string::npos)
            continue;
        out += (out.empty() ? "" : "\n") + line;
    }
    if (out.empty()) out = name + ": " + log;
    for (const auto& [vulkan, gl, portable, counts] :
         {std::tuple{"gl_VertexIndex", "gl_VertexID", "FE_VERTEX_ID", "firstVertex"},
          std::tuple{"gl_InstanceIndex", "gl_InstanceID", "FE_INSTANCE_ID", "firstInstance"}})
        if (out.find(vulkan) != std::string::npos || out.find(gl) != std::string::npos)
            out += std::string("\n") + vulkan + " is Vulkan's name and " + gl + " GL's: write " +
                   portable + " (#include \"fe_common.glsl\"), which counts from " + counts +
                   " on both";
    return out;
}

// One encoding: FE_VULKAN for Vulkan 1.2 SPIR-V, FE_OPENGL for GL 4.5's ARB_gl_spirv (as
// glslangValidator -V and -G with those defines).
std::vector<uint32_t> compileFor(const ShaderSourceCompile& s, bool vulkan, Includer& includer) {
    const EShLanguage stage = glslangStage(s.stage);
    glslang::TShader shader(stage);
    const char* text = s.text.data();
    const int length = int(s.text.size());
    const char* name = s.name.c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
    std::string preamble = vulkan ? "#define FE_VULKAN 1\n" : "#define FE_OPENGL 1\n";
    for (const std::string& d : s.defines) {
        const size_t eq = d.find('=');
        preamble +=
            "#define " +
            (eq == std::string::npos ? d + " 1" : d.substr(0, eq) + " " + d.substr(eq + 1)) + "\n";
    }
    shader.setPreamble(preamble.c_str());
    if (vulkan) {
        shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
        shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
        shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
    } else {
        shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientOpenGL, 100);
        shader.setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
        shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
    }
    const EShMessages messages =
        EShMessages(EShMsgSpvRules | (vulkan ? EShMsgVulkanRules : EShMsgDefault));
    if (!shader.parse(GetDefaultResources(), 450, false, messages, includer))
        throw Error("shader '" + s.name + "' does not compile for " +
                    (vulkan ? "Vulkan" : "OpenGL") + ":\n" +
                    errorText(shader.getInfoLog(), s.name));
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages))
        throw Error("shader '" + s.name + "' does not link for " + (vulkan ? "Vulkan" : "OpenGL") +
                    ":\n" + errorText(program.getInfoLog(), s.name));
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    options.disableOptimizer = false;
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &options);
    return spirv;
}

struct Compiled {
    std::vector<uint32_t> vulkan, opengl;
    std::string name;
    std::deque<Includer::Seen> includes;  // what the callback gave, to see whether it still does
};

}  // namespace

ShaderBinary compileShader(const ShaderSourceCompile& s) {
    glslangStage(s.stage);  // a stage glslang is not given is an Error first
    if (s.text.empty()) throw Error("compileShader: shader '" + s.name + "' has no source text");
    // glslang's process state is set up once; its compiles may then run on any thread.
    static const bool initialised = glslang::InitializeProcess();
    (void)initialised;
    // The cache: by text, stage, name and defines, then by what the include callback gives now
    // for each include the compile asked for (an edited include is a new compile).
    static std::mutex mutex;
    static std::map<std::string, std::vector<std::unique_ptr<Compiled>>> cache;
    std::string key = std::to_string(int(s.stage)) + '\0' + s.name + '\0' + std::string(s.text);
    for (const std::string& d : s.defines) key += '\0' + d;
    auto unchanged = [&](const Compiled& c) {
        for (const Includer::Seen& i : c.includes) {
            if (i.name == "fe_common.glsl") continue;
            const std::optional<std::string> now =
                s.include ? s.include(i.name, i.includer) : std::nullopt;
            if (!now || *now != i.text) return false;
        }
        return true;
    };
    std::vector<const Compiled*> candidates;  // never freed: safe to read outside the lock
    {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& c : cache[key]) candidates.push_back(c.get());
    }
    for (const Compiled* c : candidates)  // the callback runs without the lock held
        if (unchanged(*c)) return {c->name.c_str(), c->vulkan, c->opengl};
    Includer vulkanIncludes(s), glIncludes(s);
    auto compiled = std::make_unique<Compiled>();
    compiled->vulkan = compileFor(s, true, vulkanIncludes);
    compiled->opengl = compileFor(s, false, glIncludes);
    compiled->name = s.name;
    compiled->includes = std::move(vulkanIncludes.seen);
    compiles.fetch_add(1, std::memory_order_relaxed);
    std::lock_guard<std::mutex> lock(mutex);
    const Compiled& kept = *cache[key].emplace_back(std::move(compiled));
    return {kept.name.c_str(), kept.vulkan, kept.opengl};
}

ShaderDesc withCompiledSource(const ShaderDesc& desc) {
    if (desc.source.text.empty()) return desc;
    if (!desc.binary.vulkan.empty() || !desc.binary.opengl.empty())
        throw Error(std::string("createShader '") + desc.source.name +
                    "': give a binary or a source, not both");
    ShaderDesc compiled = desc;
    compiled.binary = compileShader({.stage = desc.stage,
                                     .text = desc.source.text,
                                     .name = desc.source.name,
                                     .defines = desc.source.defines,
                                     .include = desc.source.include});
    compiled.source = {};
    return compiled;
}

uint64_t shaderCompileCount() { return compiles.load(std::memory_order_relaxed); }

}  // namespace fe::gdi
