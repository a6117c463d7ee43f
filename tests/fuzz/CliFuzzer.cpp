// libFuzzer harness: fe's option and scene parsing, without rendering. The input's lines are
// either `fe render`'s arguments (first line "render"), parsed by CLI11 and checked into a
// RenderJob whose scene spec is then loaded (builtin scenes are generated; paths mostly do not
// exist), or (first line "sweep") an `fe bench --sweep` file expanded into its cases. Bad
// input must end in the documented errors: UsageError, AssetError or gdi::Error.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "Cli.h"
#include "FuzzSupport.h"
#include "assets/AssetError.h"
#include "assets/BuiltinScenes.h"
#include "fe/gdi/Device.h"
#include <nlohmann/json.hpp>

#include "fe/gdi/InfoJson.h"
#include "integration/Bench.h"

namespace {

void render(std::vector<std::string> args) {
    args.insert(args.begin(), "fe");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const fe::cli::Args parsed = fe::cli::parse(int(argv.size() - 1), argv.data(), 2,
                                                fe::cli::kRenderOptions, fe::cli::kRenderFlags);
    const fe::cli::RenderJob job = fe::cli::renderJob(parsed);
    // Builtin scenes are generated in proportion to --lights; a few thousand keeps an input fast.
    if (job.builtin.lights <= 4096)
        fe::assets::Scene scene = fe::assets::loadScene(job.spec, {}, job.builtin);
}

void sweep(const std::string& text) {
    const fe::gdi::Json j = fe::gdi::Json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return;
    const std::vector<fe::render::BenchCase> cases = fe::render::sweepFromJson(j);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool quiet = [] {
        spdlog::set_level(
            spdlog::level::off);  // --help and --log-level print; the fuzzer needs no output
        return true;
    }();
    (void)quiet;
    const std::string text(reinterpret_cast<const char*>(data), size);
    const size_t firstEnd = text.find('\n');
    const std::string first = text.substr(0, firstEnd);
    const std::string rest = firstEnd == std::string::npos ? "" : text.substr(firstEnd + 1);
    std::string undocumented;  // what escaped other than the documented errors
    try {
        if (first == "render") {
            std::vector<std::string> args{"render"};
            size_t at = 0;
            while (at <= rest.size() && !rest.empty()) {
                const size_t end = rest.find('\n', at);
                args.push_back(
                    rest.substr(at, end == std::string::npos ? std::string::npos : end - at));
                if (end == std::string::npos) break;
                at = end + 1;
            }
            render(args);
        } else if (first == "sweep") {
            sweep(rest);
        }
    } catch (const fe::cli::UsageError&) {
    } catch (const fe::cli::HelpShown&) {
    } catch (const fe::assets::AssetError&) {
    } catch (const fe::gdi::Error&) {
    } catch (const std::exception& e) {
        undocumented = e.what();
    }
    FUZZ_CHECK(undocumented.empty(), "parsing threw an undocumented exception:", undocumented);
    return 0;
}
