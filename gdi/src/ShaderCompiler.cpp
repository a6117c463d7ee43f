#include "fe/gdi/ShaderCompiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/optimizer.hpp>  // SPIRV-Tools-opt, which glslang::SPIRV links

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <shared_mutex>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include <spirv_cross/spirv_cross_c.h>

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

// Every compile holds this shared while it is inside glslang; the HLSL translation holds it alone
// while it forks, so no other thread is inside glslang (or holds glslang's global lock) when the
// child is made.
std::shared_mutex& glslangInUse() {
    static std::shared_mutex m;
    return m;
}

// The source's defines ("NAME" or "NAME=VALUE") as the preamble's #define lines, as -D does.
std::string definesOf(const ShaderSourceCompile& s) {
    std::string lines;
    for (const std::string& d : s.defines) {
        const size_t eq = d.find('=');
        lines += "#define " +
                 (eq == std::string::npos ? d + " 1" : d.substr(0, eq) + " " + d.substr(eq + 1)) +
                 "\n";
    }
    return lines;
}

// A graphics stage's encoding through SPIRV-Tools' performance passes, as the build step runs
// spirv-opt -O on both (cmake/fe-spirv-embed.sh says why, and why not compute stages). Bindings
// and specialization constants are kept. A module the optimizer refuses stays as glslang wrote it.
std::vector<uint32_t> optimized(const std::vector<uint32_t>& spirv, bool vulkan) {
    spvtools::Optimizer optimizer(vulkan ? SPV_ENV_VULKAN_1_2 : SPV_ENV_OPENGL_4_5);
    optimizer.RegisterPerformancePasses();
    spvtools::OptimizerOptions options;
    options.set_preserve_bindings(true);
    options.set_preserve_spec_constants(true);
    std::vector<uint32_t> out;
    if (!optimizer.Run(spirv.data(), spirv.size(), &out, options) || out.empty()) return spirv;
    return out;
}

// One encoding: FE_VULKAN for Vulkan 1.2 SPIR-V, FE_OPENGL for GL 4.5's ARB_gl_spirv (as
// glslangValidator -V and -G with those defines, and the build step's optimization).
std::vector<uint32_t> compileFor(const ShaderSourceCompile& s, bool vulkan, Includer& includer) {
    const EShLanguage stage = glslangStage(s.stage);
    const std::shared_lock inGlslang(glslangInUse());  // see isolatedHlslToGlsl
    glslang::TShader shader(stage);
    const char* text = s.text.data();
    const int length = int(s.text.size());
    const char* name = s.name.c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
    const std::string preamble =
        (vulkan ? "#define FE_VULKAN 1\n" : "#define FE_OPENGL 1\n") + definesOf(s);
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
    if (s.stage != ShaderStage::Compute) return optimized(spirv, vulkan);
    return spirv;
}

// glslang 11.13's HLSL front end dereferences a null name when an entry point's parameter has
// none ("float4 main(float : TEXCOORD0)": SEGV in HlslParseContext::remapEntryPointIO, found by
// ShaderSourceFuzzer), so such a parameter is refused before glslang sees the source. A parameter
// is its type then its name: one word before the semantic or the end is an unnamed one.
void checkEntryParameters(const ShaderSourceCompile& s) {
    const std::string text(s.text);
    for (size_t at = text.find(s.entryPoint); at != std::string::npos;
         at = text.find(s.entryPoint, at + 1)) {
        const size_t end = at + s.entryPoint.size();
        const bool word =
            (at == 0 || !(std::isalnum(uint8_t(text[at - 1])) || text[at - 1] == '_'));
        size_t open = end;
        while (open < text.size() && std::isspace(uint8_t(text[open]))) ++open;
        if (!word || open >= text.size() || text[open] != '(') continue;
        const size_t close = text.find(')', open);
        if (close == std::string::npos) return;  // glslang reports the syntax
        std::string params = text.substr(open + 1, close - open - 1);
        size_t index = 0;
        for (size_t from = 0; from <= params.size(); ++index) {
            const size_t comma = std::min(params.find(',', from), params.size());
            const std::string p = params.substr(from, comma - from);
            const std::string declared = p.substr(0, p.find(':'));
            int words = 0;
            bool inWord = false;
            for (char ch : declared) {
                const bool part = std::isalnum(uint8_t(ch)) || ch == '_';
                words += part && !inWord;
                inWord = part;
            }
            const bool blank = p.find_first_not_of(" \t\r\n") == std::string::npos;
            if (!(blank && index == 0 && comma == params.size()) && words < 2)
                throw Error("shader '" + s.name + "': parameter " + std::to_string(index + 1) +
                            " of entry point '" + s.entryPoint +
                            "' has no name (HLSL's entry parameters are named: 'float2 uv : "
                            "TEXCOORD0')");
            from = comma + 1;
        }
    }
}

// HLSL to Vulkan SPIR-V (glslang's HLSL front end: registers are binding numbers whatever their
// letter, stage inputs and outputs take locations in declaration order).
std::vector<uint32_t> hlslToSpirv(const ShaderSourceCompile& s, Includer& includer) {
    checkEntryParameters(s);
    const EShLanguage stage = glslangStage(s.stage);
    glslang::TShader shader(stage);
    const char* text = s.text.data();
    const int length = int(s.text.size());
    const char* name = s.name.c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
    const std::string preamble = definesOf(s);
    shader.setPreamble(preamble.c_str());
    shader.setEntryPoint(s.entryPoint.c_str());
    shader.setSourceEntryPoint(s.entryPoint.c_str());
    shader.setEnvInput(glslang::EShSourceHlsl, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
    shader.setAutoMapLocations(true);
    const EShMessages messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules | EShMsgReadHlsl);
    if (!shader.parse(GetDefaultResources(), 100, false, messages, includer))
        throw Error("shader '" + s.name + "' does not compile as HLSL:\n" +
                    errorText(shader.getInfoLog(), s.name));
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages) || !program.mapIO())
        throw Error("shader '" + s.name + "' does not link as HLSL:\n" +
                    errorText(program.getInfoLog(), s.name));
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &options);
    return spirv;
}

// Vulkan SPIR-V as GLSL 450 (SPIRV-Cross): each texture and the sampler it is sampled with
// become one combined sampler at the texture's binding, the device's binding model. A texture
// sampled with two samplers would need two slots: an Error.
std::string spirvToGlsl(const std::vector<uint32_t>& spirv, const std::string& name) {
    struct Context {
        spvc_context ctx = nullptr;
        Context() { spvc_context_create(&ctx); }
        ~Context() {
            if (ctx) spvc_context_destroy(ctx);
        }
    } c;
    auto fail = [&](const std::string& what) {
        const char* detail = c.ctx ? spvc_context_get_last_error_string(c.ctx) : "";
        return Error("shader '" + name + "': " + what +
                     (detail && *detail ? std::string(": ") + detail : std::string()));
    };
    spvc_parsed_ir ir = nullptr;
    spvc_compiler comp = nullptr;
    spvc_compiler_options options = nullptr;
    if (!c.ctx ||
        spvc_context_parse_spirv(c.ctx, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS ||
        spvc_context_create_compiler(c.ctx, SPVC_BACKEND_GLSL, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &comp) != SPVC_SUCCESS ||
        spvc_compiler_create_compiler_options(comp, &options) != SPVC_SUCCESS)
        throw fail("SPIRV-Cross could not read the HLSL's SPIR-V");
    spvc_compiler_options_set_uint(options, SPVC_COMPILER_OPTION_GLSL_VERSION, 450);
    spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_GLSL_ES, SPVC_FALSE);
    spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_GLSL_VULKAN_SEMANTICS, SPVC_FALSE);
    spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_GLSL_SUPPORT_NONZERO_BASE_INSTANCE,
                                   SPVC_FALSE);  // no uniform of its own: FE_INSTANCE_ID below
    spvc_compiler_install_compiler_options(comp, options);
    // Texture.Load (texelFetch) uses no sampler: SPIRV-Cross pairs it with a dummy one, which
    // the device's combined binding at the texture's slot stands for.
    spvc_variable_id dummy = 0;
    if (spvc_compiler_build_dummy_sampler_for_combined_images(comp, &dummy) != SPVC_SUCCESS)
        throw fail("pairing its loaded textures with a sampler failed");
    if (spvc_compiler_build_combined_image_samplers(comp) != SPVC_SUCCESS)
        throw fail("combining its textures and samplers failed");
    const spvc_combined_image_sampler* combined = nullptr;
    size_t count = 0;
    spvc_compiler_get_combined_image_samplers(comp, &combined, &count);
    std::map<uint32_t, uint32_t> samplersOf;  // texture id -> its combined samplers
    for (size_t i = 0; i < count; ++i) {
        const uint32_t binding =
            spvc_compiler_get_decoration(comp, combined[i].image_id, SpvDecorationBinding);
        if (++samplersOf[combined[i].image_id] > 1)
            throw Error("shader '" + name + "': texture '" +
                        spvc_compiler_get_name(comp, combined[i].image_id) +
                        "' is sampled with two samplers (Load counting as one); the device binds "
                        "one sampler per texture slot (setTexture)");
        spvc_compiler_set_decoration(comp, combined[i].combined_id, SpvDecorationBinding, binding);
        spvc_compiler_set_decoration(comp, combined[i].combined_id, SpvDecorationDescriptorSet, 0);
    }
    const char* written = nullptr;
    if (spvc_compiler_compile(comp, &written) != SPVC_SUCCESS || !written)
        throw fail("SPIRV-Cross could not write it as GLSL");
    // SPIRV-Cross writes GL's vertex and instance ids; the text is compiled for Vulkan too, so
    // they become fe_common.glsl's portable names (which count from firstVertex and
    // firstInstance on both, as SV_VertexID and SV_InstanceID do).
    std::string glsl = written;
    bool portable = false;
    for (const auto& [gl, fe] :
         {std::pair{"gl_VertexID", "FE_VERTEX_ID"}, std::pair{"gl_InstanceID", "FE_INSTANCE_ID"}})
        for (size_t at = glsl.find(gl); at != std::string::npos; at = glsl.find(gl, at + 1)) {
            const size_t end = at + std::strlen(gl);
            if (end < glsl.size() && (std::isalnum(uint8_t(glsl[end])) || glsl[end] == '_'))
                continue;
            glsl.replace(at, end - at, fe);
            portable = true;
        }
    if (portable)
        glsl.insert(
            glsl.find('\n') + 1,
            "#extension GL_GOOGLE_include_directive : require\n#include \"fe_common.glsl\"\n");
    return glsl;
}

// How long a translation may take, and how long its child may sit asleep without using the
// processor before it counts as stalled.
constexpr auto kTranslationLimit = std::chrono::seconds(60);
constexpr auto kStallLimit = std::chrono::seconds(2);
constexpr int kTranslationAttempts = 3;

// The state letter (R, S, D, Z...) and processor time (clock ticks) of a process, from
// /proc/PID/stat; nullopt where it cannot be read.
std::optional<std::pair<char, unsigned long long>> processProgress(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    std::getline(in, line);
    const size_t close = line.rfind(')');  // the command name may hold spaces and parentheses
    if (close == std::string::npos || close + 2 >= line.size()) return std::nullopt;
    std::istringstream fields(line.substr(close + 2));
    char state = 0;
    std::string skipped;
    unsigned long long user = 0, system = 0;
    fields >> state;
    for (int field = 4; field <= 13; ++field) fields >> skipped;
    fields >> user >> system;
    if (!fields) return std::nullopt;
    return std::pair{state, user + system};
}

// Length-prefixed strings, the framing of everything parent and child send each other.
void putString(std::string& out, const std::string& v) {
    const uint32_t n = uint32_t(v.size());
    out.append(reinterpret_cast<const char*>(&n), 4).append(v);
}
// The string at `at` in `in` (advancing `at`), or false where `in` does not hold all of it yet.
bool getString(const std::string& in, size_t& at, std::string& v) {
    uint32_t n = 0;
    if (at + 4 > in.size()) return false;
    std::memcpy(&n, in.data() + at, 4);
    if (at + 4 + size_t(n) > in.size()) return false;
    v.assign(in, at + 4, n);
    at += 4 + size_t(n);
    return true;
}
bool sendAll(int fd, const std::string& bytes) {
    for (size_t done = 0; done < bytes.size();) {
        const ssize_t n = send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += size_t(n);
    }
    return true;
}

// Children that are to sleep for good before translating, and the stall limit meanwhile
// (stallHlslChildrenForTesting).
std::atomic<int> childrenToStall{0};
std::atomic<int64_t> stallLimitMs{std::chrono::milliseconds(kStallLimit).count()};

// The child's side: glslang and SPIRV-Cross only, then _exit. Its include requests go to the
// parent, which calls the source's callback ('I', name, includer; the answer: '1' and the text,
// or '0'): the callback runs in the caller's process, where its locks and what it records are
// the caller's. Then the reply: 'G' or 'E', the GLSL (or the message), and name, includer and
// text of each include read.
[[noreturn]] void translateInChild(const ShaderSourceCompile& s, int fd, bool stall) {
    // A crash here is the failure the parent reports ("crashed"): the child dies by its signal
    // at once, with no handler of the parent's (a sanitizer's report, symbolized, took over a
    // minute under load in the sanitized suite, starving the next compile's child past its 60 s).
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) signal(sig, SIG_DFL);
    while (stall) pause();
    ShaderSourceCompile remote = s;
    if (s.include)
        remote.include = [fd](const std::string& name,
                              const std::string& includer) -> std::optional<std::string> {
            std::string request = "I";
            putString(request, name);
            putString(request, includer);
            if (!sendAll(fd, request)) _exit(2);
            std::string answer;
            size_t at = 1;
            std::string text;
            for (char buffer[4096];
                 answer.empty() || (answer[0] == '1' && !getString(answer, at, text));) {
                const ssize_t n = read(fd, buffer, sizeof buffer);
                if (n < 0 && errno == EINTR) continue;
                if (n <= 0) _exit(2);
                answer.append(buffer, size_t(n));
            }
            return answer[0] == '1' ? std::optional<std::string>(text) : std::nullopt;
        };
    std::string reply;
    Includer includes(remote);
    try {
        const std::string glsl = spirvToGlsl(hlslToSpirv(remote, includes), s.name);
        reply = "G";
        putString(reply, glsl);
    } catch (const std::exception& e) {
        reply = "E";
        putString(reply, e.what());
    }
    for (const Includer::Seen& i : includes.seen)
        putString(reply, i.name), putString(reply, i.includer), putString(reply, i.text);
    sendAll(fd, reply);
    _exit(0);
}

// Forks the translation of `s` over the socket pair `fds` (the child gets fds[1]). Returns the
// child's pid, or -1.
pid_t forkTranslation(const ShaderSourceCompile& s, const int fds[2]) {
    int stallsLeft = childrenToStall.load();
    while (stallsLeft > 0 && !childrenToStall.compare_exchange_weak(stallsLeft, stallsLeft - 1)) {}
    pid_t pid;
    {
        std::unique_lock lock(glslangInUse());
        pid = fork();
    }
    if (pid != 0) return pid;
    close(fds[0]);
    translateInChild(s, fds[1], stallsLeft > 0);
}

// What came of one forked translation.
struct ChildOutcome {
    std::string reply;
    enum class End { Finished, TimedOut, Stalled } end = End::Finished;
    int status = 0;  // waitpid's, where it finished
};

// Answers the include requests at the front of `in` (the source's callback, in this process),
// removing them; false when `in` starts with a request not all here yet.
bool answerIncludes(const ShaderSourceCompile& s, std::string& in, int fd) {
    while (!in.empty() && in[0] == 'I') {
        size_t at = 1;
        std::string name, includer;
        if (!getString(in, at, name) || !getString(in, at, includer)) return false;
        in.erase(0, at);
        const std::optional<std::string> text = s.include(name, includer);
        std::string answer = text ? "1" : "0";
        if (text) putString(answer, *text);
        sendAll(fd, answer);  // a child gone by now is seen at the next read
    }
    return true;
}

// Reads the child's messages until it closes its end, answering its include requests. Two ways
// it may not close: the child loops (past kTranslationLimit of its own time: TimedOut), or it
// sleeps for good (Stalled). The second is what a fork in a threaded process risks: the child has
// only the forking thread, so a lock another thread held at that instant (a library's) is never
// released in it. Asleep, with no processor time spent and nothing sent for kStallLimit, it is
// stalled. A child that exited while the socket stays open (another fork holding its end) has
// said all. The time the include callback takes is not the child's.
ChildOutcome awaitTranslation(const ShaderSourceCompile& s, pid_t pid, int fd) {
    using Clock = std::chrono::steady_clock;
    ChildOutcome out;
    auto start = Clock::now();
    auto lastProgress = start;
    std::optional<unsigned long long> lastCpu;
    std::string& in = out.reply;
    try {
        for (char buffer[65536];;) {
            if (Clock::now() - start >= kTranslationLimit) {
                out.end = ChildOutcome::End::TimedOut;
                break;
            }
            pollfd p{fd, POLLIN, 0};
            const int ready = poll(&p, 1, 250);
            if (ready < 0 && errno == EINTR) continue;
            if (ready > 0) {
                const ssize_t n = read(fd, buffer, sizeof buffer);
                if (n < 0 && errno == EINTR) continue;
                if (n <= 0) break;
                in.append(buffer, size_t(n));
                const auto before = Clock::now();
                answerIncludes(s, in, fd);
                start += Clock::now() - before;
                lastProgress = Clock::now();
                continue;
            }
            const auto progress = processProgress(pid);
            if (!progress) continue;
            const auto [state, cpu] = *progress;
            if (state == 'Z') {  // exited: what it sent is in the socket
                for (ssize_t n; poll(&p, 1, 0) > 0 && (n = read(fd, buffer, sizeof buffer)) > 0;)
                    in.append(buffer, size_t(n));
                break;
            }
            if (state == 'R' || cpu != lastCpu) {  // running, or waiting for a processor
                lastCpu = cpu;
                lastProgress = Clock::now();
            } else if (Clock::now() - lastProgress >=
                       std::chrono::milliseconds(stallLimitMs.load())) {
                out.end = ChildOutcome::End::Stalled;
                break;
            }
        }
    } catch (...) {  // the include callback threw: the child goes, the exception on
        kill(pid, SIGKILL);
        while (waitpid(pid, &out.status, 0) < 0 && errno == EINTR) {}
        throw;
    }
    if (out.end != ChildOutcome::End::Finished) kill(pid, SIGKILL);
    while (waitpid(pid, &out.status, 0) < 0 && errno == EINTR) {}
    return out;
}

// The HLSL translation in a child process. glslang 11.13's HLSL front end crashes on some
// malformed sources (ShaderSourceFuzzer found two null dereferences in a minute: an unnamed entry
// parameter, a register-less declaration after garbage), and a shader editor must not die of a
// typo: the child translates and sends the result back; a child that dies or loops (60 s) is a
// clear Error and the process goes on. A child that stalls on a lock it inherited is killed and
// the translation forked again (the lock's holder has moved on by then). The includes it read
// come back for the cache.
std::string isolatedHlslToGlsl(const ShaderSourceCompile& s, std::deque<Includer::Seen>& seen) {
    ChildOutcome outcome;
    for (int attempt = 1; attempt <= kTranslationAttempts; ++attempt) {
        int fds[2];
        if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
            throw Error("shader '" + s.name +
                        "': no socket for the HLSL compiler: " + strerror(errno));
        const pid_t pid = forkTranslation(s, fds);
        close(fds[1]);
        if (pid < 0) {
            close(fds[0]);
            throw Error("shader '" + s.name +
                        "': could not start the HLSL compiler: " + strerror(errno));
        }
        struct Closer {
            int fd;
            ~Closer() { close(fd); }
        } closer{fds[0]};
        outcome = awaitTranslation(s, pid, fds[0]);
        if (outcome.end != ChildOutcome::End::Stalled) break;
    }
    const std::string& reply = outcome.reply;
    size_t at = 1;
    std::string text;
    const bool whole = outcome.end == ChildOutcome::End::Finished && WIFEXITED(outcome.status) &&
                       WEXITSTATUS(outcome.status) == 0 && !reply.empty() &&
                       (reply[0] == 'G' || reply[0] == 'E') && getString(reply, at, text);
    if (!whole) {
        const char* what =
            outcome.end == ChildOutcome::End::TimedOut ? "did not finish in 60 s"
            : outcome.end == ChildOutcome::End::Stalled
                ? "stalled on each of its three tries (asleep on a lock another thread held when "
                  "it was forked)"
                : "crashed";
        throw Error("shader '" + s.name + "': the HLSL compiler (glslang's HLSL front end) " +
                    what + " on this source, which is refused (the process goes on)");
    }
    for (Includer::Seen i; getString(reply, at, i.name) && getString(reply, at, i.includer) &&
                           getString(reply, at, i.text);)
        seen.push_back(i);
    if (reply[0] == 'E') throw Error(text);
    return text;
}

struct Compiled {
    std::vector<uint32_t> vulkan, opengl;
    std::string name;
    std::deque<Includer::Seen> includes;  // what the callback gave, to see whether it still does
};

}  // namespace

std::string hlslToGlsl(const ShaderSourceCompile& s) {
    glslangStage(s.stage);
    static const bool initialised = glslang::InitializeProcess();
    (void)initialised;
    std::deque<Includer::Seen> seen;
    return isolatedHlslToGlsl(s, seen);
}

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
    std::string key = std::to_string(int(s.stage)) + '\0' + std::to_string(int(s.language)) + '\0' +
                      s.entryPoint + '\0' + s.name + '\0' + std::string(s.text);
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
    if (s.language == ShaderLanguage::HLSL) {
        // One translation, then the GLSL path with no includes left to resolve.
        const std::string glsl = isolatedHlslToGlsl(s, vulkanIncludes.seen);
        ShaderSourceCompile translated{.stage = s.stage, .text = glsl, .name = s.name};
        Includer none(translated), noneGl(translated);
        compiled->vulkan = compileFor(translated, true, none);
        compiled->opengl = compileFor(translated, false, noneGl);
    } else {
        compiled->vulkan = compileFor(s, true, vulkanIncludes);
        compiled->opengl = compileFor(s, false, glIncludes);
    }
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
    const bool hlsl = desc.source.language == ShaderLanguage::HLSL;
    compiled.binary = compileShader({.stage = desc.stage,
                                     .text = desc.source.text,
                                     .language = desc.source.language,
                                     .entryPoint = desc.entryPoint ? desc.entryPoint : "main",
                                     .name = desc.source.name,
                                     .defines = desc.source.defines,
                                     .include = desc.source.include});
    if (hlsl) compiled.entryPoint = "main";  // what the translation names it
    compiled.source = {};
    return compiled;
}

void stallHlslChildrenForTesting(int count, std::chrono::milliseconds stallLimit) {
    stallLimitMs.store(count > 0 ? stallLimit.count()
                                 : std::chrono::milliseconds(kStallLimit).count());
    childrenToStall.store(count);
}

uint64_t shaderCompileCount() { return compiles.load(std::memory_order_relaxed); }

}  // namespace fe::gdi
