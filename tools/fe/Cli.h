// fe's command line, apart from the commands' work so it can be tested and fuzzed on its own
// (tests/fuzz/CliFuzzer.cpp): the usage text, CLI11 parsing into Args, and `fe render`'s
// options checked and turned into a RenderJob, with every bad value a UsageError.
#pragma once
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <optional>

#include "assets/BuiltinScenes.h"
#include "integration/RenderDirector.h"
#include "render/RenderSettings.h"

namespace fe::cli {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
struct HelpShown {};  // `fe COMMAND --help` printed its help: exit 0

// Every command's usage, and the techniques; the usage lines of one command.
std::string usage();
std::string commandUsage(const std::string& command);

// One command's arguments, parsed by CLI11: `--name value` options and flags as named (anything
// else is a usage error saying what), positional arguments, --help for each command, and
// --log-level for every command.
struct Args {
    std::map<std::string, std::string> options;
    std::vector<std::string> positional;
};
// The positional arguments a command takes, as its --help names them; a command without
// (name nullptr) refuses any.
struct Positionals {
    const char* name = nullptr;  // e.g. "SCENE"
    const char* help = "";
};
// argv[first - 1] is the command's name; its arguments follow.
Args parse(int argc, char** argv, int first, const std::vector<std::string>& valued,
           const std::vector<std::string>& flags, const Positionals& positionals = {});
// `fe render` and `fe view`'s positional argument.
extern const Positionals kScenePositional;
uint32_t parseUint(const std::string& s, const char* what, uint32_t lo, uint32_t hi);

// The command that draws fe bench's charts and report page from a results file: Debian's
// python3 (whose python3-matplotlib it is) with report.py, an installed fe's
// (PREFIX/share/fe/bench/report.py beside PREFIX/bin/fe), else the source tree's it was built from.
std::string reportCommand(const std::string& resultsJson);

// Bytes as people read them: "512 B", "3.5 KiB", "23.4 GiB".
std::string humanBytes(double bytes);
// An output file can be written, before any work: its directory is created, and a path that
// cannot be written is a gdi::Error naming the option, the path and why.
void checkWritableFile(const std::string& path, const char* option);
// An output directory exists (created with its parents) and is one, else such an error.
void makeOutputDirectory(const std::string& path, const char* option);

// `fe render`: its options and flags, and what they ask for.
extern const std::vector<std::string> kRenderOptions, kRenderFlags;
// fe render's look options and flags (technique options, light, shadows, tone mapping, ...),
// which fe view takes too, in the same units.
extern const std::vector<std::string> kLookOptions, kLookFlags;
// What `fe render` and `fe view` show when no scene is named: the quick start's image
// (tools/render-default.sh): builtin:shadows lit by the builtin sky (image-based lighting at
// kQuickStartIblSamples samples) with shadows on; options given on the command line win.
inline constexpr const char* kQuickStartScene = "builtin:shadows";
inline constexpr const char* kQuickStartEnvironment = "builtin:sky";
inline constexpr uint32_t kQuickStartIblSamples = 256;

// `fe render`'s default image size: large enough to look at, small enough that the default look
// (sky, sun, shadows) renders in about a second on a 2-core CPU rasterizer (docs/BENCHMARKS.md).
inline constexpr const char* kDefaultSize = "960x540";

// --background: auto, environment, transparent, #RRGGBB or R,G,B (sRGB-encoded, 0 to 1).
render::Background parseBackground(const std::string& text);

struct RenderJob {
    std::string spec;         // the scene: a path or builtin:NAME
    std::string environment;  // --environment, or the quick start's sky when no scene is named
    // No lighting asked for (--environment, --ibl-*): a model without lights of its own gets the
    // default look (assets::useDefaultSkyAndSun, prefiltered image-based lighting).
    bool defaultLook = false;
    bool defaultLookApplied = false;  // set by applyScene: the scene had no lights
    bool shadowsGiven = false;  // --shadows given; else on exactly when the scene showsShadows
    render::RenderSettings settings;
    render::DirectorOptions director;
    bool window = false;
    std::string backend;
    bool vsync = true;
    bool untilClosed = false;  // a window and no --frames: until it is closed
    uint32_t frames = 1;
    assets::BuiltinOptions builtin;
    std::string out;
    bool pfm = false;
    double orbitDegrees = 0;
    std::string dumpGraph;
    std::string pipelineCache;     // --pipeline-cache
    std::string renderdocCapture;  // --renderdoc-capture
    // Animation: --animation INDEX|NAME (empty: none; --time or --fps alone: the first), the
    // instant of the first frame, frames per second of a sequence, --loop.
    std::string animationName;
    bool animated = false;
    int32_t animation = -1;  // resolved by applyScene
    double time = 0.0, fps = 30.0;
    bool loop = false;
    // Cameras: --camera INDEX|NAME, or one made of --camera-position/-target/-up and --fov (each
    // defaulting to the scene's camera), turned by --azimuth and --elevation about the scene.
    std::string cameraName;
    std::optional<glm::vec3> cameraPosition, cameraTarget, cameraUp;
    std::optional<float> fovDegrees;
    double azimuthDegrees = 0.0, elevationDegrees = 0.0;
    // --out with "{frame}" or "{frame:0N}": every frame written, frame k to outPath(k).
    bool sequence = false;

    // What the loaded scene decides: its --environment (or the quick start's), the default look,
    // shadows unless --shadows was given, the animation's start pose and the camera.
    void applyScene(assets::Scene& scene);
    // Frame k (from 0) of the output: the scene posed at time + k / fps (no-op unless animated).
    // Returns whether it moved.
    bool poseFrame(assets::Scene& scene, uint32_t k) const;
    // The file frame k is written to (--out, its {frame} field replaced by k).
    std::string outPath(uint32_t k) const;
};
RenderJob renderJob(const Args& a);
// A builtin:NAME that names no builtin scene is a usage error listing them; other specs pass.
void checkBuiltinScene(const std::string& spec);
// "builtin:spheres, builtin:lights, ...".
std::string builtinSceneList();

}  // namespace fe::cli
