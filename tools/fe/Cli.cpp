#include "Cli.h"

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include <cctype>
#include <limits>

#include "assets/Animation.h"
#include "fe/gdi/Backend.h"
#include "render/TechniqueRenderer.h"
#include "shading/Tonemap.h"

namespace fe::cli {

namespace {

constexpr const char* kUsage =
    "usage: fe <command> [options]\n"
    "commands:\n"
    "  info [--backend NAME] [--json]  every backend: available or why not, device, API, driver, limits, features\n"
    "  render [SCENE]             SCENE: a .gltf/.glb path or builtin:NAME; none: the quick start's image\n"
    "      (builtin:shadows, --environment builtin:sky --ibl-samples 256 --shadows on unless given)\n"
    "      a model without lights of its own, unless --environment or --ibl-* is given, gets the default look:\n"
    "        the built-in sky as prefiltered image-based light and background, and a sun with shadows\n"
    "      --backend NAME --technique NAME|auto (below; default auto: the render director chooses, --verbose says why)\n"
    "      --illum-scale 1|2|4 --msaa 1|2|4|8 (every technique but the redeferred ones)\n"
    "      --illum-split (redeferred-tiled: specular sums at full rate, L_dg at 1/scale)\n"
    "      --one-pass-culling (deferred-tiled: each work group culls its tile in shared memory, no culling pass)\n"
    "      --no-cluster-bounds (clustered techniques, visibility buffer: cluster lists not bounded by the opaque depth)\n"
    "      --rebuild-nov (redeferred: w_o.n rebuilt from depth and normal, not read from the G-buffer)\n"
    "      --error-budget PERCENT: with auto, a reduced illumination rate may be chosen if a probe frame has at\n"
    "        most PERCENT % of pixels beyond 5/255 of the exact image (default 0: exact techniques only)\n"
    "      --environment FILE.hdr|builtin:sky: the light from far away, drawn as the background\n"
    "      --ibl-samples N: light the scene by the environment, N importance samples per term (every technique);\n"
    "        with --ibl-* and no --environment the environment is builtin:sky\n"
    "      --ibl-prefiltered: light the scene by the environment through the fast path (prefiltered cube,\n"
    "        split-sum table, SH irradiance) instead of sampling it\n"
    "      --rates SOURCE=RATE,...: redeferred, each illumination source in an I-buffer of its own rate (1, 2, 4;\n"
    "        unset: --illum-scale): punctual, shadowed, ibl-diffuse, ibl-specular\n"
    "      --temporal (redeferred, --illum-scale 2|4): the reduced-rate samples jitter and accumulate over frames\n"
    "      --orbit DEGREES: the camera turns about the scene's vertical axis over the --frames\n"
    "      --animation INDEX|NAME|all --time SECONDS: the file's animation (all: every one at once) at that instant (glTF 2.0: node transforms,\n"
    "        skins, morph weights; before the first key the first value, after the last the last); --frames N\n"
    "        --fps F (default 30): frame k at --time + k / F; --loop: the time wraps around the animation\n"
    "      --camera INDEX|NAME: one of the file's cameras (default: its first; animated with its node)\n"
    "      --camera-position X,Y,Z --camera-target X,Y,Z --camera-up X,Y,Z --fov DEGREES: a camera of your own\n"
    "        (each unset one from the scene's camera; a position alone looks at the scene's centre)\n"
    "      --azimuth DEGREES --elevation DEGREES: the camera turned about the scene's centre (vertical axis, then\n"
    "        its own horizontal one)\n"
    "      --shadows on|off: shadow maps for directional lights (cascaded), spot lights and the most important\n"
    "        point lights (cubes); default on for scenes made to show them (builtin:shadows, builtin:particles,\n"
    "        the default look's sun) and when a --shadow-* option is given, else off\n"
    "        --shadow-map-size N (default 1024) --shadow-cascades 1-4 (default 4)\n"
    "        --shadow-point-budget N (default 4) --shadow-filter pcf|none (default pcf: 2x2 hardware comparison)\n"
    "      --size WxH (default 960x540) --out FILE(.png|.pfm) --exposure X --frames N --lights N\n"
    "      --out 'DIR/f_{frame:04}.png': every frame of --frames N written, {frame} replaced by its number\n"
    "        (from 0; {frame:0N} zero-padded to N digits); missing directories are created\n"
    "      --background auto|environment|transparent|#RRGGBB|R,G,B: the .png where nothing is drawn (auto: the\n"
    "        environment, else black; transparent: an RGBA .png, alpha 0 there; a colour: exactly that sRGB value)\n"
    "      --brdf auto|gltf|separable: glTF 2.0's BRDF (Appendix B) or the seeds' separable one, which redeferred and\n"
    "        light-prepass need (auto: glTF wherever the technique can evaluate it; docs/SHADING.md)\n"
    "      --tonemap clamp|aces|pbr-neutral (the .png: default Khronos PBR Neutral, as the glTF Sample Viewer;\n"
    "        clamp keeps it comparable with the exact reference; aces: the ACES fit) --aa none|fxaa|taa (the .png: FXAA after tone mapping, or TAA: jittered\n"
    "        frames blended with the reprojected history; it converges over --frames)\n"
    "      --dump-graph FILE.dot (the compiled render graph) --no-aliasing (transients in memory of their own)\n"
    "      --renderdoc-capture FILE: the first frame captured by RenderDoc (librenderdoc) into FILE_capture.rdc;\n"
    "        vulkan as is, gl-egl/gl-glfw only with LD_PRELOAD=/usr/lib/librenderdoc.so, gl-osmesa never\n"
    "      --pipeline-cache FILE: compiled pipelines kept across runs (loaded at start, saved at exit; a file made\n"
    "        for another device, driver or build is ignored with a warning); start-up times are printed\n"
    "      --debug-view NAME: the .png shows an intermediate texture of the frame (a name of the graph's,\n"
    "        e.g. \"gbuffer1 normal+roughness\", \"depth\", \"shadow 0 map\"; or \"light count\" / \"lights evaluated\", heat maps)\n"
    "      --strict: the loader's warnings (content skipped or approximated, printed on stderr) are errors\n"
    "      --verbose: also pass times, transient memory, the director's reasons, lights per pixel;\n"
    "        --quiet: only warnings and errors; --json: the run as one JSON document on stdout\n"
    "      an option the technique does not use (--msaa, --illum-scale, --temporal, ...) is a warning, ignored\n"
    "      --window: show the frames in a window until it is closed, or for --frames N; --backend auto\n"
    "        (Vulkan, else GL), vulkan, gl, vulkan-glfw or gl-glfw; --vsync on|off (default on)\n"
    "  view [SCENE] [--backend auto|vulkan|gl] [--technique NAME] [--size WxH] [--environment FILE.hdr|builtin:sky]\n"
    "      [--frames N] [--screenshot FILE.png] [--debug-view TEXTURE|\"light count\"|\"lights evaluated\"] [--no-ui] [--validation]\n"
    "      [--switch-backend-at FRAME] (tests: restart on the other API there, as the panel's buttons do)\n"
    "      [--input-script FRAME:KEY|FRAME:drop=PATH,...] (tests: keys pressed and files dropped at those frames)\n"
    "      [--post-shader FILE.frag|FILE.frag.hlsl]: a fragment shader over the image (it samples binding 0 /\n"
    "      register t0 at gl_FragCoord / SV_Position), compiled again whenever the file changes; an error keeps\n"
    "      the last good version and is printed and shown in the panel\n"
    "      [--animation INDEX|NAME] [--camera INDEX|NAME]: an animated file plays (its first animation unless named),\n"
    "      looped; the panel picks the animation, plays, pauses, loops and scrubs it, and lists the file's cameras\n"
    "      every look option of render in its units: --illum-scale --msaa --ibl-samples --ibl-prefiltered --shadows\n"
    "      --shadow-* --rates --tonemap --aa --exposure --brdf --background --lights and render's flags\n"
    "      an interactive window with a panel beside the scene (technique and options, backend, tone mapping, debug\n"
    "      views, pass times; F1 or its arrow folds it); drag to orbit, wheel to zoom, W A S D Q E to fly, R resets\n"
    "      the camera, F frames the scene, F12 writes fe-view-NNN.png, Esc quits; drop a .gltf/.glb or .hdr on the\n"
    "      window to open it; --frames N stops after N frames and --screenshot writes the last one (under xvfb-run\n"
    "      for tests)\n"
    "  bench [--quick | --sweep FILE.json] [--backend NAME|all] [--out DIR] [--frames N] [--warmup-ms MS] [--interleave]\n"
    "      [--stability | --stability-cases LIST] [--conformance | --conformance-cases LIST]\n"
    "      every case of the sweep (default --quick: every technique and option at 96x72) on each backend:\n"
    "      frame and pass times, transient memory, error against the CPU reference (PSNR, SSIM, FLIP, % over\n"
    "      5/255, max); with --quick (or --stability, --conformance) also the stability suite's table and the\n"
    "      conformance suite's cross-backend images (--stability-cases \"one light,NaN\": only the stability\n"
    "      cases whose name contains a part; --conformance-cases likewise); writes DIR/results.json,\n"
    "      DIR/results.csv, charts, report.html and summary.md (default DIR: bench; while it runs,\n"
    "      DIR/results.partial.json holds what is measured so far); --interleave: each\n"
    "      backend's cases render their timed frames in alternation, all held at once, for steadier ratios\n"
    "  bench --compare A.json B.json [--time-ratio X] [--error-points P]: what changed from A to B; exit 1 when\n"
    "      a frame got slower than X times (default 1.25) or P more percent of pixels over 5/255 (default 0.5)\n"
    "  conformance [--backend NAME|all] [--report FILE.json] [--out-dir DIR] [--case SUBSTRING] [--no-validation]\n"
    "      [--list]: the case names (those --case matches), nothing run\n"
    "      [--capture FILE[,FILE...]]: the captures are the cases (each replayed on every backend, its images\n"
    "      compared across backends with the suite's tolerance)\n"
    "  capture [--out FILE] [--frames N | --frame K] [--no-compress] -- PROGRAM [ARGS...]\n"
    "      runs PROGRAM (any program using the device, e.g. fe render) with FE_CAPTURE=FILE (default\n"
    "      capture.fecap): every call of its first device, with its data, goes into FILE; --frames N: only the\n"
    "      first N frames (a frame ends with the renderer's frame, a present, or a read-back, after a submit); --frame K: only\n"
    "      frame K (from 0), the objects made before it written in the state they have when it starts\n"
    "  replay FILE [--backend NAME] [--out DIR] [--validation] [--present] [--pass NAME | --draw N | --list]\n"
    "      replays a capture on any backend (captured on vulkan, replayed on gl-egl, or the other way round);\n"
    "      --out DIR: every read-back and presented image as PNG; prints the frame times; --present: in a window;\n"
    "      --pass NAME / --draw N: stop after that render pass or draw (counted from 0 over the capture) and\n"
    "      write the render targets there; --list: every render pass by name with its draws' numbers\n"
    "  bisect FILE [--backends A,B] [--tolerance ABS[,FRACTION]] [--out DIR] [--perturb BACKEND:DRAW]\n"
    "      replays on both backends (default vulkan,gl-egl), compares the render targets after every render\n"
    "      pass, then draw by draw in the first pass that differs, and prints the first divergent pass and draw:\n"
    "      debug groups, pipeline, shaders, bound resources, pixels that differ; writes DIR/bisect.json (default\n"
    "      DIR: bisect) with both images and a heat map; tolerance default 0.0196,0.001 (5/255 on 0.1 % of\n"
    "      pixels); --perturb leaves one draw out on one backend (a test of the bisection); exit 1 when they differ\n"
    "backends: auto, vulkan, gl, gl-egl, gl-osmesa, vulkan-glfw, gl-glfw (also FE_BACKEND)\n"
    "exit codes: 0 success, 1 error (out of memory included), 2 usage, 3 asset, 4 device lost\n";

// Each option's line in `fe COMMAND --help`: its value's name and what it does, keyed by
// "COMMAND --option" where commands differ, else by "--option". The usage text above stays the
// full account (the --help footer); these are the one-line summaries CLI11 lists.
struct OptionHelp {
    const char* value;  // "" for a flag
    const char* text;
};
const std::map<std::string, OptionHelp> kOptionHelp = {
    {"--backend",
     {"NAME", "auto, vulkan, gl, gl-egl, gl-osmesa, vulkan-glfw or gl-glfw (also FE_BACKEND)"}},
    {"info --backend", {"NAME[,NAME]", "only these backends (or all)"}},
    {"bench --backend", {"NAME[,NAME]|all", "the backends to measure (default all)"}},
    {"conformance --backend",
     {"NAME[,NAME]|all", "the backends to run the cases on (default all)"}},
    {"--json", {"", "print the report as JSON"}},
    {"render --json",
     {"", "print the run as one JSON document (device, timings, passes, memory, warnings)"}},
    {"--quiet", {"", "print nothing but warnings and errors"}},
    {"capture --out", {"FILE", "the capture file written (default capture.fecap)"}},
    {"capture --frames", {"N", "capture only the first N frames (default: all)"}},
    {"--frame", {"K", "capture only frame K, starting from the state the frames before left"}},
    {"--no-compress", {"", "write chunks without zstd"}},
    {"replay --out", {"DIR", "write every read-back and presented image there as PNG"}},
    {"replay --backend", {"NAME", "the backend to replay on (default auto)"}},
    {"--present", {"", "present the captured frames in a window (vulkan-glfw, gl-glfw)"}},
    {"replay --list",
     {"", "name the capture's render passes and their draws (what --pass and --draw take)"}},
    {"conformance --list", {"", "name the cases (those --case matches) without running them"}},
    {"--capture",
     {"FILE[,FILE...]", "run these capture files as the cases (fe capture makes them)"}},
    {"--pass", {"NAME", "stop after the first render pass of this name and write its targets"}},
    {"--draw", {"N", "stop after draw N (from 0, over the capture) and write its pass's targets"}},
    {"--backends", {"A,B", "the two backends to compare (default vulkan,gl-egl)"}},
    {"--tolerance",
     {"ABS[,FRACTION]",
      "per channel, and the fraction of pixels allowed beyond it (default 0.0196,0.001)"}},
    {"bisect --out", {"DIR", "where bisect.json and the images go (default bisect)"}},
    {"--perturb", {"BACKEND:DRAW", "leave draw DRAW out on BACKEND (tests the bisection)"}},
    {"--technique",
     {"NAME|auto",
      "the lighting technique (fe --help lists them); auto, the default: the render director chooses"}},
    {"view --technique", {"NAME", "the technique to start with (default deferred-tiled)"}},
    {"--illum-scale",
     {"1|2|4", "redeferred: the I-buffer at 1/N of the resolution on each axis (default 1)"}},
    {"--size", {"WxH", "image size in pixels (default 960x540)"}},
    {"view --size", {"WxH", "window size in pixels (default 640x480)"}},
    {"--out", {"FILE", ".png (tone mapped) or .pfm (linear radiance) (default out.png)"}},
    {"bench --out", {"DIR", "where the results, charts and report go (default bench)"}},
    {"--exposure", {"X", "multiplies the radiance before tone mapping (default 1)"}},
    {"--frames", {"N", "frames to render (default 1; with --window: until it is closed)"}},
    {"view --frames", {"N", "stop after N frames (default: when the window is closed)"}},
    {"bench --frames", {"N", "timed frames per case; medians are reported"}},
    {"--warmup-ms",
     {"MS",
      "untimed frames for at least MS ms per case on a GPU, so its clocks rise first (default 1000)"}},
    {"--lights",
     {"N", "builtin:lights and builtin:atrium: the number of point lights (default 512)"}},
    {"--dump-graph", {"FILE.dot", "write the compiled render graph as Graphviz"}},
    {"--pipeline-cache",
     {"FILE", "load and save compiled pipelines (Vulkan cache data, GL program binaries)"}},
    {"--renderdoc-capture",
     {"FILE", "capture the first frame with RenderDoc into FILE_capture.rdc"}},
    {"--vsync", {"on|off", "with --window: wait for the display (default on)"}},
    {"--msaa",
     {"1|2|4|8",
      "samples per pixel: every technique but redeferred and redeferred-tiled (default 1)"}},
    {"--error-budget",
     {"PERCENT",
      "with auto: % of pixels beyond 5/255 of exact a reduced rate may cost (default 0)"}},
    {"--environment", {"FILE.hdr|builtin:sky", "the light from far away, drawn as the background"}},
    {"--ibl-samples", {"N", "light the scene by the environment, N importance samples per term"}},
    {"--shadows",
     {"on|off",
      "shadow maps for directional, spot and the most important point lights (default: on where the scene is made to show them)"}},
    {"--shadow-map-size", {"N", "shadow map size in texels (default 1024)"}},
    {"--shadow-cascades", {"1-4", "cascades of a directional light's shadow (default 4)"}},
    {"--shadow-point-budget",
     {"N", "point lights given cube shadow maps, the most important first (default 4)"}},
    {"--shadow-filter", {"pcf|none", "2x2 hardware comparison or one tap (default pcf)"}},
    {"--rates",
     {"SOURCE=RATE,...",
      "redeferred: an I-buffer rate per source (punctual, shadowed, ibl-diffuse, ibl-specular)"}},
    {"--orbit", {"DEGREES", "the camera turns about the vertical axis over the frames"}},
    {"--animation",
     {"INDEX|NAME|all",
      "play the file's animation, or all at once (glTF node transforms, skins, morph weights)"}},
    {"--time", {"SECONDS", "the animation's instant of the first frame (default 0)"}},
    {"--fps", {"F", "frames per second of an animated sequence (default 30)"}},
    {"--loop", {"", "the animation's time wraps around its duration"}},
    {"--camera", {"INDEX|NAME", "one of the file's cameras (default: the first)"}},
    {"view --camera",
     {"INDEX|NAME", "look through one of the file's cameras (default: the orbit camera)"}},
    {"view --animation", {"INDEX|NAME", "the animation played (default: the file's first)"}},
    {"--camera-position", {"X,Y,Z", "a camera of your own at this point"}},
    {"--camera-target", {"X,Y,Z", "... looking at this point (default: the scene's centre)"}},
    {"--camera-up", {"X,Y,Z", "... with this up direction (default +Y)"}},
    {"--fov", {"DEGREES", "... and this vertical field of view"}},
    {"--azimuth", {"DEGREES", "the camera turned about the scene's vertical axis"}},
    {"--elevation", {"DEGREES", "the camera raised about the scene's centre"}},
    {"--tonemap", {"clamp|aces|pbr-neutral", "the .png's tone mapping (default pbr-neutral)"}},
    {"--brdf",
     {"auto|gltf|separable",
      "glTF 2.0's BRDF or the seeds' separable one (auto: glTF where the technique can, docs/SHADING.md)"}},
    {"--background",
     {"auto|environment|transparent|#RRGGBB|R,G,B",
      "what shows where nothing is drawn (default: the environment, else black)"}},
    {"--aa", {"none|fxaa|taa", "the .png's anti-aliasing (default none)"}},
    {"--debug-view",
     {"TEXTURE",
      "show an intermediate texture of the frame, or \"light count\" (lights reaching each pixel) or \"lights evaluated\" (lights the technique's loop walks)"}},
    {"--no-aliasing", {"", "transient textures in memory of their own"}},
    {"--window", {"", "show the frames in a window"}},
    {"--verbose",
     {"",
      "also print pass times, transient memory, the render director's reasons and the lights evaluated per pixel"}},
    {"--strict", {"", "the glTF loader's warnings are errors"}},
    {"--illum-split", {"", "redeferred-tiled: specular sums at full rate, diffuse at 1/scale"}},
    {"--rebuild-nov",
     {"", "redeferred: w_o.n rebuilt from depth and normal, not read from the G-buffer"}},
    {"--one-pass-culling", {"", "deferred-tiled: each work group culls its tile, no culling pass"}},
    {"--no-cluster-bounds",
     {"",
      "clustered techniques: cluster lists not bounded by the opaque depth each cluster holds"}},
    {"--ibl-prefiltered",
     {"", "light by the environment through prefiltered maps, not by sampling it"}},
    {"--temporal",
     {"", "redeferred at illum-scale 2|4: jittered reduced-rate samples accumulate over frames"}},
    {"--screenshot", {"FILE.png", "write the last frame"}},
    {"--switch-backend-at", {"FRAME", "tests: restart on the other API at this frame"}},
    {"--input-script",
     {"FRAME:KEY,...",
      "tests: keys (Esc, F12, F1, R, F) or drop=PATH as if given at those frames"}},
    {"--post-shader",
     {"FILE",
      "a fragment shader (GLSL, or HLSL for .hlsl) over the image, reloaded when it changes"}},
    {"--no-ui", {"", "no panel"}},
    {"--validation", {"", "the Khronos validation layer / GL debug output on"}},
    {"--sweep", {"FILE.json", "the cases to measure (bench/sweeps/ has the documented ones)"}},
    {"--compare", {"A.json", "compare A with the results file given after it"}},
    {"--time-ratio", {"X", "with --compare: a frame this many times slower fails (default 1.25)"}},
    {"--error-points",
     {"P", "with --compare: this many more % of pixels over 5/255 fails (default 0.5)"}},
    {"--quick",
     {"", "every technique and option at 96x72, with the stability and conformance suites"}},
    {"--stability", {"", "with --sweep: also the stability suite's table"}},
    {"--stability-cases",
     {"LIST", "only the stability cases whose name contains one of these comma-separated parts"}},
    {"--conformance", {"", "with --sweep: also the conformance suite's cross-backend images"}},
    {"--conformance-cases",
     {"LIST", "only the conformance cases whose name contains one of these comma-separated parts"}},
    {"--interleave",
     {"", "the cases' timed frames in alternation, so interference hits all alike"}},
    {"--report", {"FILE.json", "write the results as JSON"}},
    {"--out-dir", {"DIR", "write each case's image per backend"}},
    {"--case", {"SUBSTRING", "only the cases whose name contains it"}},
    {"--no-validation", {"", "without the validation layer / GL debug output"}},
};

// One option's --help line; an option missing from the table is a programming error, caught by
// the cli_help_describes_every_option test.
const OptionHelp& optionHelp(const std::string& command, const std::string& option) {
    static const OptionHelp missing{"VALUE", ""};
    auto it = kOptionHelp.find(command + " " + option);
    if (it == kOptionHelp.end()) it = kOptionHelp.find(option);
    return it == kOptionHelp.end() ? missing : it->second;
}

}  // namespace

std::string builtinSceneList() {
    std::string list;
    for (const std::string& n : assets::builtinSceneNames())
        list += (list.empty() ? "builtin:" : ", builtin:") + n;
    return list;
}

// The techniques of the engine's table, one line each.
std::string techniqueList() {
    std::string u = "techniques (--technique):\n";
    for (const render::TechniqueInfo& t : render::techniques()) {
        std::string name = t.name;
        u += "  " + name + std::string(name.size() < 20 ? 20 - name.size() : 1, ' ') + t.summary +
             "\n";
    }
    return u;
}

const Positionals kScenePositional{
    "SCENE", "a glTF 2.0 file (.gltf, .glb) or builtin:NAME (fe render --help lists them)"};

// The usage text with every technique of the engine's table, one line each.
std::string usage() {
    return kUsage + ("builtin scenes: " + builtinSceneList() + "\n") + techniqueList();
}

// The usage lines of one command (from kUsage: the line starting "  COMMAND" and its
// continuation lines), the footer of its --help.
std::string commandUsage(const std::string& command) {
    std::istringstream in(usage());
    std::string line, out;
    bool inside = false;
    while (std::getline(in, line)) {
        if (line.rfind("  " + command + " ", 0) == 0 || line == "  " + command)
            inside = true;
        else if (line.rfind("      ", 0) != 0)
            inside = false;
        if (inside) out += line + "\n";
    }
    return out;
}

Args parse(int argc, char** argv, int first, const std::vector<std::string>& valued,
           const std::vector<std::string>& flags, const Positionals& positionals) {
    const std::string command = argv[first - 1];
    CLI::App app{"fe " + command + ": the options, then the full usage", "fe " + command};
    // render and view also list what SCENE and --technique take.
    const bool scenes = command == "render" || command == "view";
    app.footer("\nUsage:\n" + commandUsage(command) +
               (scenes ? "\nbuiltin scenes: " + builtinSceneList() + "\n" + techniqueList() : ""));
    app.allow_extras(false);
    app.positionals_at_end(false);
    std::map<std::string, std::string> values;
    std::map<std::string, bool> on;
    for (const std::string& o : valued) {
        const OptionHelp& h = optionHelp(command, o);
        app.add_option(o, values[o], h.text)->type_name(h.value)->allow_extra_args(false);
    }
    app.add_option("--log-level", values["--log-level"],
                   "trace, debug, info, warn (default), error or off; also FE_LOG_LEVEL")
        ->type_name("LEVEL");
    for (const std::string& f : flags) app.add_flag(f, on[f], optionHelp(command, f).text);
    Args a;
    if (positionals.name)
        app.add_option(positionals.name, a.positional, positionals.help)->type_name("");
    try {
        // CLI11 skips argv[0] as the program's name: the command's name stands in for it.
        app.parse(argc - first + 1, argv + first - 1);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        throw HelpShown{};
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
    for (const std::string& o : valued)
        if (app.count(o)) a.options[o] = values[o];
    for (const std::string& f : flags)
        if (on[f]) a.options[f] = "1";
    if (app.count("--log-level")) {
        const spdlog::level::level_enum level = spdlog::level::from_str(values["--log-level"]);
        if (level == spdlog::level::off && values["--log-level"] != "off")
            throw UsageError("--log-level must be trace, debug, info, warn, error or off, got '" +
                             values["--log-level"] + "'");
        spdlog::set_level(level);
    }
    return a;
}

uint32_t parseUint(const std::string& s, const char* what, uint32_t lo, uint32_t hi) {
    char* end = nullptr;
    long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end || v < long(lo) || v > long(hi))
        throw UsageError(std::string(what) + " must be an integer in [" + std::to_string(lo) +
                         ", " + std::to_string(hi) + "], got '" + s + "'");
    return uint32_t(v);
}

std::string reportCommand(const std::string& resultsJson) {
    std::error_code ec;
    std::string script = FE_BENCH_REPORT_SCRIPT;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const std::filesystem::path installed =
            exe.parent_path().parent_path() / "share/fe/bench/report.py";
        if (std::filesystem::exists(installed, ec)) script = installed.string();
    }
    const std::string python =
        std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    return python + " '" + script + "' '" + resultsJson + "'";
}

std::string humanBytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 4) bytes /= 1024.0, ++u;
    char text[32];
    std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
    return text;
}

void makeOutputDirectory(const std::string& path, const char* option) {
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec || !std::filesystem::is_directory(path))
        throw gdi::Error("cannot create the directory " + path + " for " + option + ": " +
                         (ec ? ec.message() : std::string("a file of that name exists")));
}

void checkWritableFile(const std::string& file, const char* option) {
    const std::filesystem::path path(file);
    std::error_code ec;
    if (path.has_parent_path()) makeOutputDirectory(path.parent_path().string(), option);
    if (std::filesystem::is_directory(path, ec))
        throw gdi::Error(std::string(option) + " " + file + " is a directory");
    const bool existed = std::filesystem::exists(path, ec);
    std::ofstream probe(path, std::ios::app);
    if (!probe)
        throw gdi::Error("cannot write " + file + " (" + option + "): " + std::strerror(errno));
    probe.close();
    if (!existed) std::filesystem::remove(path, ec);
}

// The look: what fe render and fe view both take, in the same units (renderJob reads them).
const std::vector<std::string> kLookOptions = {"--illum-scale",
                                               "--msaa",
                                               "--ibl-samples",
                                               "--shadows",
                                               "--shadow-map-size",
                                               "--shadow-cascades",
                                               "--shadow-point-budget",
                                               "--shadow-filter",
                                               "--rates",
                                               "--tonemap",
                                               "--aa",
                                               "--exposure",
                                               "--brdf",
                                               "--background",
                                               "--lights"};
const std::vector<std::string> kLookFlags = {"--ibl-prefiltered",   "--illum-split",
                                             "--rebuild-nov",       "--one-pass-culling",
                                             "--no-cluster-bounds", "--temporal"};

namespace {
std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}
}  // namespace

const std::vector<std::string> kRenderOptions = with({"--backend",
                                                      "--technique",
                                                      "--size",
                                                      "--out",
                                                      "--frames",
                                                      "--dump-graph",
                                                      "--vsync",
                                                      "--error-budget",
                                                      "--environment",
                                                      "--orbit",
                                                      "--debug-view",
                                                      "--pipeline-cache",
                                                      "--renderdoc-capture",
                                                      "--animation",
                                                      "--time",
                                                      "--fps",
                                                      "--camera",
                                                      "--camera-position",
                                                      "--camera-target",
                                                      "--camera-up",
                                                      "--fov",
                                                      "--azimuth",
                                                      "--elevation"},
                                                     kLookOptions);
const std::vector<std::string> kRenderFlags =
    with({"--no-aliasing", "--quiet", "--json", "--window", "--verbose", "--strict", "--loop"},
         kLookFlags);

render::Background parseBackground(const std::string& text) {
    using Kind = render::Background::Kind;
    if (text == "auto") return {};
    if (text == "environment") return {.kind = Kind::Environment};
    if (text == "transparent") return {.kind = Kind::Transparent};
    const std::string usage =
        "--background takes auto, environment, transparent, #RRGGBB or R,G,B (sRGB, 0-1); got '" +
        text + "'";
    render::Background b{.kind = Kind::Color};
    if (text.size() == 7 && text[0] == '#') {
        for (int c = 0; c < 3; ++c) {
            const std::string hex = text.substr(1 + 2 * c, 2);
            if (hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
                throw UsageError(usage);
            b.color[c] = float(std::stoul(hex, nullptr, 16)) / 255.0f;
        }
        return b;
    }
    std::stringstream list(text);
    int c = 0;
    for (std::string item; std::getline(list, item, ','); ++c) {
        char* end = nullptr;
        const float v = std::strtof(item.c_str(), &end);
        if (c > 2 || item.empty() || *end || !(v >= 0.0f && v <= 1.0f)) throw UsageError(usage);
        b.color[c] = v;
    }
    if (c != 3) throw UsageError(usage);
    return b;
}

namespace {

double parseNumber(const std::string& text, const char* what, double lo, double hi) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end || !std::isfinite(v) || v < lo || v > hi)
        throw UsageError(std::string(what) + " takes a number in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got '" + text + "'");
    return v;
}

glm::vec3 parseVec3(const std::string& text, const char* what) {
    std::stringstream list(text);
    glm::vec3 v(0.0f);
    int c = 0;
    for (std::string item; std::getline(list, item, ','); ++c) {
        if (c > 2) break;
        char* end = nullptr;
        v[c] = std::strtof(item.c_str(), &end);
        if (item.empty() || *end || !std::isfinite(v[c])) c = 4;
    }
    if (c != 3)
        throw UsageError(std::string(what) + " takes X,Y,Z (three finite numbers), got '" + text +
                         "'");
    return v;
}

// The camera asked for by --camera-position/-target/-up and --fov, each defaulting to `from`'s.
assets::Camera customCamera(const RenderJob& job, const assets::Camera& from,
                            const assets::AABB& bounds) {
    const glm::vec3 eye = job.cameraPosition.value_or(from.eye());
    const glm::vec3 target = job.cameraTarget     ? *job.cameraTarget
                             : job.cameraPosition ? bounds.center()
                                                  : from.eye() + from.forward();
    const glm::vec3 up = job.cameraUp.value_or(
        job.cameraPosition || job.cameraTarget ? glm::vec3(0.0f, 1.0f, 0.0f) : from.up());
    const glm::vec3 forward = target - eye;
    if (!(glm::length(forward) > 1e-6f))
        throw UsageError("--camera-target must differ from the camera's position");
    if (!(glm::length(glm::cross(glm::normalize(forward), glm::normalize(up))) > 1e-4f))
        throw UsageError(
            "--camera-up must not be parallel to the view direction (give --camera-up)");
    const float yfov =
        job.fovDegrees ? float(*job.fovDegrees * 3.14159265358979 / 180.0) : from.yfov;
    // Near and far planes around the scene as seen from the new position.
    const float radius = std::max(0.5f * glm::length(bounds.size()), 1e-3f);
    const float distance = glm::length(bounds.center() - eye);
    const float znear = std::max(1e-3f * (distance + radius), 0.5f * (distance - radius));
    assets::Camera c = assets::Camera::lookAlong(eye, forward, up, yfov, znear,
                                                 std::numeric_limits<float>::infinity());
    c.name = "command line";
    return c;
}

// --azimuth turns the camera about the vertical axis through the scene's centre, --elevation
// raises it about its own horizontal axis through that centre (positive: from above).
assets::Camera turned(const assets::Camera& camera, const assets::AABB& bounds, double azimuth,
                      double elevation) {
    const glm::vec3 center = bounds.center();
    assets::Camera c = camera.orbited(center, float(azimuth * 3.14159265358979 / 180.0));
    if (elevation != 0.0) {
        const glm::vec3 right = glm::normalize(glm::vec3(c.worldFromView[0]));
        const glm::mat4 r =
            glm::rotate(glm::mat4(1.0f), float(-elevation * 3.14159265358979 / 180.0), right);
        c.worldFromView = glm::translate(glm::mat4(1.0f), center) * r *
                          glm::translate(glm::mat4(1.0f), -center) * c.worldFromView;
    }
    return c;
}

}  // namespace

void RenderJob::applyScene(assets::Scene& scene) {
    if (!environment.empty()) scene.environment = assets::loadEnvironment(environment);
    // The animation and camera named: a name the file lacks is the command line's mistake.
    try {
        if (animated) {
            if (scene.animations.empty())
                throw UsageError("--animation, --time, --fps and --loop: " + spec +
                                 " has no animation");
            animation = assets::findAnimation(scene, animationName.empty() ? "0" : animationName);
        }
        poseFrame(scene, 0);
        if (!cameraName.empty()) {
            scene.cameraIndex = assets::findCamera(scene, cameraName);
            scene.camera = scene.cameras[size_t(scene.cameraIndex)];
        }
    } catch (const assets::AssetError& e) {
        throw UsageError(e.what());
    }
    if (cameraPosition || cameraTarget || cameraUp || fovDegrees) {
        scene.camera = customCamera(*this, *scene.camera, scene.bounds);
        scene.cameraIndex = -1;  // not moved by the animation
    }
    if (azimuthDegrees != 0.0 || elevationDegrees != 0.0) {
        scene.camera = turned(*scene.camera, scene.bounds, azimuthDegrees, elevationDegrees);
        scene.cameraIndex = -1;
    }
    defaultLookApplied = defaultLook && assets::useDefaultSkyAndSun(scene);
    if (defaultLookApplied) settings.iblPrefiltered = true;
    if (!shadowsGiven) settings.shadows.enabled = scene.showsShadows;
}

bool RenderJob::poseFrame(assets::Scene& scene, uint32_t k) const {
    if (!animated) return false;
    assets::poseScene(scene,
                      {.animation = animation, .seconds = time + double(k) / fps, .loop = loop});
    return true;
}

std::string RenderJob::outPath(uint32_t k) const {
    if (!sequence) return out;
    const size_t open = out.find("{frame"), close = out.find('}', open);
    const std::string field = out.substr(open, close - open + 1);  // {frame} or {frame:0N}
    std::string number = std::to_string(k);
    if (field.size() > 7) {
        const size_t width = size_t(std::stoul(field.substr(8, field.size() - 9)));
        if (number.size() < width) number = std::string(width - number.size(), '0') + number;
    }
    return out.substr(0, open) + number + out.substr(close + 1);
}

namespace {
// --animation, --time, --fps, --loop, the camera options and --out's {frame} field.
void parseAnimationAndCamera(const Args& a, RenderJob& job) {
    auto opt = [&](const char* k) {
        auto it = a.options.find(k);
        return it == a.options.end() ? std::string() : it->second;
    };
    job.animated = a.options.count("--animation") || a.options.count("--time") ||
                   a.options.count("--fps") || a.options.count("--loop");
    job.animationName = opt("--animation");
    if (a.options.count("--time")) job.time = parseNumber(opt("--time"), "--time", -1e6, 1e6);
    if (a.options.count("--fps")) job.fps = parseNumber(opt("--fps"), "--fps", 1e-3, 1e4);
    job.loop = a.options.count("--loop") > 0;
    job.cameraName = opt("--camera");
    if (a.options.count("--camera-position"))
        job.cameraPosition = parseVec3(opt("--camera-position"), "--camera-position");
    if (a.options.count("--camera-target"))
        job.cameraTarget = parseVec3(opt("--camera-target"), "--camera-target");
    if (a.options.count("--camera-up")) job.cameraUp = parseVec3(opt("--camera-up"), "--camera-up");
    if (job.cameraUp && !(glm::length(*job.cameraUp) > 0.0f))
        throw UsageError("--camera-up must not be 0,0,0");
    if (a.options.count("--fov"))
        job.fovDegrees = float(parseNumber(opt("--fov"), "--fov", 0.01, 179.0));
    if (a.options.count("--azimuth"))
        job.azimuthDegrees = parseNumber(opt("--azimuth"), "--azimuth", -3600, 3600);
    if (a.options.count("--elevation"))
        job.elevationDegrees = parseNumber(opt("--elevation"), "--elevation", -89.9, 89.9);
    if (!job.cameraName.empty() &&
        (job.cameraPosition || job.cameraTarget || job.cameraUp || job.fovDegrees))
        throw UsageError(
            "--camera picks a camera of the file; --camera-position/-target/-up and --fov make one: give one or the other");
    // --out 'dir/f_{frame:04}.png': every frame; a field other than {frame} or {frame:0N} is a mistake.
    const size_t open = job.out.find('{');
    if (open != std::string::npos) {
        const size_t close = job.out.find('}', open);
        const std::string field = close == std::string::npos
                                      ? job.out.substr(open)
                                      : job.out.substr(open, close - open + 1);
        const bool padded = field.size() == 11 && field.rfind("{frame:0", 0) == 0 &&
                            std::isdigit((unsigned char)field[8]) &&
                            std::isdigit((unsigned char)field[9]) && field[10] == '}';
        const bool padded1 = field.size() == 10 && field.rfind("{frame:0", 0) == 0 &&
                             std::isdigit((unsigned char)field[8]) && field[9] == '}';
        if (field != "{frame}" && !padded && !padded1)
            throw UsageError(
                "--out: the frame field is {frame} or {frame:0N} (N digits, zero padded), got '" +
                field + "'");
        if (job.out.find('{', open + 1) != std::string::npos)
            throw UsageError("--out: one {frame} field at most");
        if (job.window) throw UsageError("--out with {frame} writes files: not with --window");
        job.sequence = true;
    }
}
}  // namespace

void checkBuiltinScene(const std::string& spec) {
    if (spec.rfind("builtin:", 0) != 0) return;
    const auto& names = assets::builtinSceneNames();
    if (std::find(names.begin(), names.end(), spec.substr(8)) == names.end())
        throw UsageError("unknown scene '" + spec + "' (builtin scenes: " + builtinSceneList() +
                         ")");
}

RenderJob renderJob(const Args& a) {
    if (a.positional.size() > 1)
        throw UsageError("render takes one SCENE, got " + std::to_string(a.positional.size()));
    const bool quickStart = a.positional.empty();  // no scene named: the quick start's image
    std::string spec = quickStart ? kQuickStartScene : a.positional[0];
    checkBuiltinScene(spec);
    render::RenderSettings s;
    auto opt = [&](const char* k, const std::string& def) {
        auto it = a.options.find(k);
        return it == a.options.end() ? def : it->second;
    };
    const bool lightingAsked = a.options.count("--environment") ||
                               a.options.count("--ibl-samples") ||
                               a.options.count("--ibl-prefiltered");
    s.technique = opt("--technique", "auto");
    if (s.technique != "auto") try {  // an unknown name is a usage error (exit 2)
            s.technique = render::findTechnique(s.technique).name;
        } catch (const gdi::Error& e) {
            throw UsageError(e.what());
        }
    s.illumScale = parseUint(opt("--illum-scale", "1"), "--illum-scale", 1, 4);
    s.msaa = parseUint(opt("--msaa", "1"), "--msaa", 1, 8);
    s.iblSamples =
        parseUint(opt("--ibl-samples",
                      quickStart && !lightingAsked ? std::to_string(kQuickStartIblSamples) : "0"),
                  "--ibl-samples", 0, 65536);
    s.iblPrefiltered = a.options.count("--ibl-prefiltered") > 0;
    // Unless given, shadows are on for a scene made to show them (assets::Scene::showsShadows,
    // decided once the scene is loaded: RenderJob::applyScene).
    const std::string shadows = opt("--shadows", "on");
    if (shadows != "on" && shadows != "off")
        throw UsageError("--shadows must be on or off, got '" + shadows + "'");
    s.shadows.enabled = shadows == "on";
    s.shadows.mapSize = parseUint(opt("--shadow-map-size", "1024"), "--shadow-map-size", 16, 16384);
    s.shadows.cascades = parseUint(opt("--shadow-cascades", "4"), "--shadow-cascades", 1, 4);
    s.shadows.pointBudget =
        parseUint(opt("--shadow-point-budget", "4"), "--shadow-point-budget", 0, 1000);
    const std::string filter = opt("--shadow-filter", "pcf");
    if (filter != "pcf" && filter != "none")
        throw UsageError("--shadow-filter must be pcf or none, got '" + filter + "'");
    s.shadows.pcf = filter == "pcf";
    // A shadow option without --shadows asks for shadows; with --shadows off it is a mistake.
    bool shadowsGiven = a.options.count("--shadows") > 0;
    for (const char* k :
         {"--shadow-map-size", "--shadow-cascades", "--shadow-point-budget", "--shadow-filter"})
        if (a.options.count(k)) {
            if (!s.shadows.enabled) throw UsageError(std::string(k) + " applies to --shadows on");
            shadowsGiven = true;
        }
    // Image-based light asked for without an environment: the builtin sky, as the quick start.
    const bool iblAsked = a.options.count("--ibl-samples") || a.options.count("--ibl-prefiltered");
    const std::string environment = opt(
        "--environment", (quickStart && !lightingAsked) || iblAsked ? kQuickStartEnvironment : "");
    if (const std::string rates = opt("--rates", ""); !rates.empty()) {
        // SOURCE=RATE,... with sources punctual, shadowed, ibl-diffuse, ibl-specular.
        std::stringstream list(rates);
        for (std::string item; std::getline(list, item, ',');) {
            const size_t eq = item.find('=');
            const std::string source = item.substr(0, eq);
            uint32_t* r = source == "punctual"       ? &s.rates.punctual
                          : source == "shadowed"     ? &s.rates.shadowed
                          : source == "ibl-diffuse"  ? &s.rates.iblDiffuse
                          : source == "ibl-specular" ? &s.rates.iblSpecular
                                                     : nullptr;
            if (!r || eq == std::string::npos)
                throw UsageError(
                    "--rates takes SOURCE=RATE,... with sources punctual, shadowed, ibl-diffuse, ibl-specular; got '" +
                    item + "'");
            *r = parseUint(item.substr(eq + 1), "--rates", 1, 4);
            if (*r == 3) throw UsageError("--rates: a rate must be 1, 2 or 4, got 3");
        }
    }
    std::string size = opt("--size", kDefaultSize);
    size_t x = size.find('x');
    if (x == std::string::npos) throw UsageError("--size must be WxH, got '" + size + "'");
    s.width = parseUint(size.substr(0, x), "width", 1, 8192);
    s.height = parseUint(size.substr(x + 1), "height", 1, 8192);
    char* end = nullptr;
    std::string ex = opt("--exposure", "1");
    s.exposure = std::strtof(ex.c_str(), &end);
    if (*end || !std::isfinite(s.exposure) || s.exposure <= 0)
        throw UsageError("--exposure must be a positive number");
    const std::string tonemap = opt("--tonemap", "pbr-neutral");
    if (const auto t = shading::parseTonemap(tonemap))
        s.tonemap = *t;
    else
        throw UsageError("--tonemap must be clamp, aces or pbr-neutral, got '" + tonemap + "'");
    const std::string brdf = opt("--brdf", "auto");
    if (brdf != "auto" && brdf != "gltf" && brdf != "separable")
        throw UsageError("--brdf must be auto, gltf or separable, got '" + brdf + "'");
    s.shadingModel = brdf == "gltf"        ? render::ShadingModel::Gltf
                     : brdf == "separable" ? render::ShadingModel::Separable
                                           : render::ShadingModel::Auto;
    const std::string aa = opt("--aa", "none");
    if (aa != "none" && aa != "fxaa" && aa != "taa")
        throw UsageError("--aa must be none, fxaa or taa, got '" + aa + "'");
    s.antiAliasing = aa == "fxaa"  ? render::AntiAliasing::Fxaa
                     : aa == "taa" ? render::AntiAliasing::Taa
                                   : render::AntiAliasing::None;
    render::DirectorOptions director;
    const std::string budget = opt("--error-budget", "0");
    director.errorBudgetPercent = std::strtod(budget.c_str(), &end);
    if (*end || !(director.errorBudgetPercent >= 0 && director.errorBudgetPercent <= 100))
        throw UsageError("--error-budget must be a percentage from 0 to 100, got '" + budget + "'");
    if (a.options.count("--error-budget") && s.technique != "auto")
        throw UsageError("--error-budget applies to --technique auto");
    const bool window = a.options.count("--window") > 0;
    const std::string backend = opt("--backend", "auto");
    std::vector<std::string> windowed;
    try {  // throws for a name that is no backend: a usage error (exit 2)
        windowed = gdi::windowCandidates(backend);
    } catch (const gdi::Error& e) {
        throw UsageError(e.what());
    }
    if (window && windowed.empty())
        throw UsageError(
            "--window needs a backend with a window (auto, vulkan, gl, vulkan-glfw, gl-glfw); " +
            backend + " is headless");
    const std::string vsync = opt("--vsync", "on");
    if (vsync != "on" && vsync != "off")
        throw UsageError("--vsync must be on or off, got '" + vsync + "'");
    if (a.options.count("--vsync") && !window) throw UsageError("--vsync applies to --window");
    // With a window and no --frames, frames are shown until the window is closed.
    const bool untilClosed = window && !a.options.count("--frames");
    const uint32_t frames = untilClosed ? 1 : parseUint(opt("--frames", "1"), "--frames", 1, 10000);
    assets::BuiltinOptions builtin;
    builtin.lights = parseUint(opt("--lights", "512"), "--lights", 0, 100000);
    const std::string out = opt("--out", "out.png");
    const bool pfm = out.size() > 4 && out.substr(out.size() - 4) == ".pfm";
    if (!pfm && !(out.size() > 4 && out.substr(out.size() - 4) == ".png"))
        throw UsageError("--out must end in .png or .pfm, got '" + out + "'");

    s.background = parseBackground(opt("--background", "auto"));
    if (a.options.count("--background") && pfm)
        throw UsageError(
            "--background applies to the .png (a .pfm holds radiance, with no alpha or display colour)");
    s.displayImage = !pfm || window;  // the PNG (and the window) show the GPU's display pass output
    s.aliasing = !a.options.count("--no-aliasing");
    s.illumSplit = a.options.count("--illum-split") > 0;
    s.precomputedNoV = !a.options.count("--rebuild-nov");
    s.tileCullingPass = !a.options.count("--one-pass-culling");
    s.clusterDepthBounds = !a.options.count("--no-cluster-bounds");
    s.temporal = a.options.count("--temporal") > 0;
    s.debugView = opt("--debug-view", "");
    const std::string orbitText = opt("--orbit", "0");
    const double orbitDegrees = std::strtod(orbitText.c_str(), &end);
    if (*end || !std::isfinite(orbitDegrees) || std::abs(orbitDegrees) > 3600)
        throw UsageError("--orbit takes degrees (at most 3600), got '" + orbitText + "'");
    const std::string dumpGraph = opt("--dump-graph", "");
    RenderJob job{.spec = spec,
                  .environment = environment,
                  .defaultLook = !quickStart && !lightingAsked,
                  .shadowsGiven = shadowsGiven,
                  .settings = s,
                  .director = director,
                  .window = window,
                  .backend = backend,
                  .vsync = vsync == "on",
                  .untilClosed = untilClosed,
                  .frames = frames,
                  .builtin = builtin,
                  .out = out,
                  .pfm = pfm,
                  .orbitDegrees = orbitDegrees,
                  .dumpGraph = dumpGraph,
                  .pipelineCache = opt("--pipeline-cache", ""),
                  .renderdocCapture = opt("--renderdoc-capture", "")};
    parseAnimationAndCamera(a, job);
    return job;
}

}  // namespace fe::cli
