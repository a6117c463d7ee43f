#include "Viewer.h"

#include <imgui.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "assets/Animation.h"
#include "assets/BuiltinScenes.h"
#include "assets/Environment.h"
#include "fe/gdi/Backend.h"
#include "integration/SceneRenderer.h"
#include "PostShader.h"
#include "integration/UiRenderer.h"
#include "render/TechniqueRenderer.h"

namespace fe::tools {

namespace {

using Clock = std::chrono::steady_clock;
constexpr float kPi = 3.14159265358979f;

// An orbit camera about a target (left drag turns, the wheel zooms) that also flies (W A S D
// move the target and eye along the view, Q E down and up).
struct OrbitCamera {
    glm::vec3 target{0.0f};
    float yaw = 0, pitch = 0, distance = 5;
    float yfov = 0.785f, znear = 0.1f, zfar = std::numeric_limits<float>::infinity();

    static OrbitCamera from(const assets::Camera& c, const glm::vec3& target) {
        OrbitCamera o;
        o.target = target;
        const glm::vec3 d = c.eye() - target;
        o.distance = std::max(0.1f, glm::length(d));
        o.yaw = std::atan2(d.x, d.z);
        o.pitch = std::asin(std::clamp(d.y / o.distance, -1.0f, 1.0f));
        o.yfov = c.yfov, o.znear = c.znear, o.zfar = c.zfar;
        return o;
    }
    glm::vec3 eye() const {
        return target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                             std::cos(pitch) * std::cos(yaw));
    }
    assets::Camera camera() const {
        return assets::Camera::lookAlong(eye(), target - eye(), glm::vec3(0, 1, 0), yfov, znear,
                                         zfar);
    }
};

// The panel's column at the window's left: the scene is drawn beside it, never under it.
constexpr uint32_t kPanelWidth = 300;

std::atomic<bool> interrupted{false};  // set by SIGINT / SIGTERM (runViewer)

class Viewer {
public:
    explicit Viewer(const ViewerOptions& o) : options_(o) {
        loadLook(o.scene, o.look);
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;  // no imgui.ini beside the user's files
        // ImGui 1.86 reads keys through a map into KeysDown: our Key values are the indices.
        const std::pair<ImGuiKey_, gdi::Key> keys[] = {{ImGuiKey_Tab, gdi::Key::Tab},
                                                       {ImGuiKey_LeftArrow, gdi::Key::Left},
                                                       {ImGuiKey_RightArrow, gdi::Key::Right},
                                                       {ImGuiKey_UpArrow, gdi::Key::Up},
                                                       {ImGuiKey_DownArrow, gdi::Key::Down},
                                                       {ImGuiKey_Home, gdi::Key::Home},
                                                       {ImGuiKey_End, gdi::Key::End},
                                                       {ImGuiKey_Delete, gdi::Key::Delete},
                                                       {ImGuiKey_Backspace, gdi::Key::Backspace},
                                                       {ImGuiKey_Enter, gdi::Key::Enter},
                                                       {ImGuiKey_Escape, gdi::Key::Escape},
                                                       {ImGuiKey_Space, gdi::Key::Space}};
        for (const auto& [imgui, key] : keys) io.KeyMap[imgui] = int(key);
        startDevice(o.backend);
    }
    ~Viewer() {
        stopDevice();
        ImGui::DestroyContext();
    }

    int run() {
        bool open = true;
        auto last = Clock::now();
        uint32_t frame = 0;
        for (; open && (options_.frames == 0 || frame < options_.frames); ++frame) {
            if (interrupted.load()) {  // Ctrl-C or SIGTERM: end as the last frame would
                std::cout << "fe view: interrupted after " << frame << " frame(s)\n";
                break;
            }
            const auto now = Clock::now();
            const float dt = std::max(1e-4f, std::chrono::duration<float>(now - last).count());
            last = now;
            gdi::InputState in = device_->input();
            scriptedInput(frame, in);
            ImGuiIO& io = ImGui::GetIO();
            io.DisplaySize = ImVec2(float(options_.width), float(options_.height));  // the window
            io.DeltaTime = dt;
            io.MousePos = ImVec2(in.mouseX, in.mouseY);
            for (int b = 0; b < 3; ++b) io.MouseDown[b] = in.mouse[b];
            io.MouseWheel += in.wheel;
            for (size_t k = 0; k < size_t(gdi::Key::Count); ++k) io.KeysDown[k] = in.keys[k];
            io.KeyShift = in.down(gdi::Key::LeftShift);
            io.KeyCtrl = in.down(gdi::Key::LeftControl);
            if (!in.text.empty()) io.AddInputCharactersUTF8(in.text.c_str());
            ImGui::NewFrame();
            if (options_.ui) panel();
            ImGui::Render();
            if (!handleKeys(in)) {
                std::cout << "fe view: Esc: quit after " << frame << " frame(s)\n";
                break;
            }
            moveCamera(in, dt);

            const auto t0 = Clock::now();
            if (animation_ != -1) {
                if (playing_) time_ += dt;
                const double duration = animationDuration();
                if (loop_ && duration > 0.0)
                    time_ = std::fmod(time_, duration);
                else if (time_ > duration)
                    time_ = duration, playing_ = false;
                assets::poseScene(scene_,
                                  {.animation = animation_, .seconds = time_, .loop = loop_});
                renderer_->updatePose();
            }
            renderer_->setCamera(fileCamera_ >= 0 ? scene_.cameras[size_t(fileCamera_)]
                                                  : camera_.camera());
            renderer_->renderFrame();
            timings_ = renderer_->passTimings();  // waits for the frame
            frameMs_ = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            const gdi::TextureHandle shown = composeWindow();
            if (options_.ui) ui_->render(*ImGui::GetDrawData(), shown);
            shown_ = shown;
            open = device_->present(shown);
            if (options_.switchBackendAt && frame + 1 == options_.switchBackendAt)
                pendingBackend_ =
                    device_->info().backend == "vulkan-glfw" ? "gl-glfw" : "vulkan-glfw";
            applyPendingChanges();
        }
        if (!options_.screenshot.empty()) screenshot(options_.screenshot);
        if (const uint32_t errors = device_->validationErrorCount()) {
            std::cerr << "fe view: " << errors << " validation error(s)\n";
            return 1;
        }
        return 0;
    }

private:
    // The scene and how it is lit: fe render's look (ViewerOptions::look) where given, else
    // the defaults fe render has: PBR Neutral; a model without lights of its own under the sky
    // and a sun (assets::useDefaultSkyAndSun) unless --environment is given; shadows where the
    // scene is made to show them. Also for a file dropped on the window.
    void loadLook(const std::string& spec, const std::optional<cli::RenderJob>& look) {
        const ViewerOptions& o = options_;
        if (look) {
            cli::RenderJob job = *look;
            job.spec = spec;
            scene_ = assets::loadScene(spec, {}, job.builtin);
            job.applyScene(scene_);
            settings_ = job.settings;
        } else {
            scene_ = assets::loadScene(spec);
            if (!o.environment.empty()) scene_.environment = assets::loadEnvironment(o.environment);
            settings_ = {.technique = o.technique};
            settings_.debugView = o.debugView;
            settings_.tonemap = shading::Tonemap::PbrNeutral;
            if (o.environment.empty() && assets::useDefaultSkyAndSun(scene_))
                settings_.iblPrefiltered = true;
            settings_.shadows.enabled = scene_.showsShadows;
        }
        // Interactive on a CPU rasterizer: the quick start's sky through the fast path.
        if (o.quickStartLighting && spec == o.scene)
            settings_.iblSamples = 0, settings_.iblPrefiltered = true;
        settings_.displayImage = true;
        settings_.height = o.height;
        settings_.width = sceneWidth();
        camera_ = OrbitCamera::from(*scene_.camera, scene_.bounds.center());
        wantEnvironment_ = bool(scene_.environment);
        // Animated files play their first animation (or --animation) in a loop; --camera looks
        // through one of the file's cameras instead of the orbit camera.
        animation_ = -1, time_ = 0.0, fileCamera_ = -1;
        const bool first = spec == o.scene;
        if (!scene_.animations.empty())
            animation_ =
                assets::findAnimation(scene_, first && !o.animation.empty() ? o.animation : "0");
        else if (first && !o.animation.empty())
            throw assets::AssetError(spec + " has no animation");
        if (first && !o.camera.empty()) fileCamera_ = assets::findCamera(scene_, o.camera);
    }

    // The scene's width: the window's less the panel's column while the panel is open.
    uint32_t sceneWidth() const {
        return panelDocked() ? options_.width - panelWidth() : options_.width;
    }
    uint32_t panelWidth() const { return std::min(kPanelWidth, options_.width / 2); }
    bool panelDocked() const { return options_.ui && !panelCollapsed_; }

    // What the window shows: the scene texture, or beside an open panel a window-sized texture
    // the scene is copied into at the panel's right.
    gdi::TextureHandle composeWindow() {
        gdi::TextureHandle display = renderer_->displayTexture();
        if (post_) {
            if (const std::optional<std::string> news = post_->refresh()) {
                std::cout << "fe view: post shader " << options_.postShader << ": " << *news
                          << std::endl;
                message_ = *news == "compiled" ? "" : *news;
            }
            display = post_->apply(display);
        }
        if (!panelDocked()) return display;
        const gdi::TextureDesc d = device_->desc(display);
        if (!windowTexture_ || device_->desc(windowTexture_).width != options_.width) {
            if (windowTexture_) device_->destroy(windowTexture_);
            windowTexture_ = device_->createTexture(
                {.format = d.format,
                 .width = options_.width,
                 .height = options_.height,
                 .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Sampled |
                          gdi::TextureUsage::CopyDst | gdi::TextureUsage::CopySrc,
                 .debugName = "fe view window"});
        }
        auto cmd = device_->createCommandList();
        cmd->copyTexture(windowTexture_, {.x = panelWidth()}, display,
                         {.width = d.width, .height = d.height, .depth = 1});
        device_->submit(*cmd);
        return windowTexture_;
    }

    // Keys that act on a press (counted by the device, so a tap between slow frames counts):
    // Esc quits, F12 a numbered screenshot, R the scene's camera again, F frames the scene, F1
    // opens or closes the panel; files dropped on the window are opened.
    bool handleKeys(const gdi::InputState& in) {
        const ImGuiIO& io = ImGui::GetIO();
        if (in.pressed(gdi::Key::F12)) screenshot(nextScreenshotPath());
        if (!io.WantCaptureKeyboard) {
            if (in.pressed(gdi::Key::Escape)) return false;
            if (in.pressed(gdi::Key::R))
                camera_ = OrbitCamera::from(*scene_.camera, scene_.bounds.center()),
                fileCamera_ = -1;
            if (in.pressed(gdi::Key::F)) frameAll();
            if (in.pressed(gdi::Key::F1) && options_.ui) setPanelCollapsed(!panelCollapsed_);
        }
        for (const std::string& path : in.droppedFiles) openDropped(path);
        return true;
    }

    // The orbit camera keeps its direction and takes the scene's bounds whole into view.
    void frameAll() {
        fileCamera_ = -1;
        camera_.target = scene_.bounds.center();
        const float radius = std::max(1e-3f, glm::length(scene_.bounds.size()) * 0.5f);
        const float aspect = float(sceneWidth()) / float(options_.height);
        const float halfFov =
            0.5f * std::min(camera_.yfov, 2.0f * std::atan(std::tan(0.5f * camera_.yfov) * aspect));
        camera_.distance = radius / std::sin(halfFov);
    }

    void setPanelCollapsed(bool collapsed) {
        if (collapsed == panelCollapsed_) return;
        panelCollapsed_ = collapsed;
        render::RenderSettings s = pendingSettings_ ? *pendingSettings_ : settings_;
        s.width = sceneWidth();
        pendingSettings_ = s;
    }

    // A .gltf/.glb replaces the scene (lit as fe render would), an .hdr the environment.
    void openDropped(const std::string& path) {
        std::string ext = path.size() > 4 ? path.substr(path.find_last_of('.') + 1) : "";
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
        try {
            if (ext == "hdr") {
                scene_.environment = assets::loadEnvironment(path);
                wantEnvironment_ = true;
                render::RenderSettings s = pendingSettings_ ? *pendingSettings_ : settings_;
                if (!s.ibl()) s.iblPrefiltered = true;
                pendingSettings_ = s;
            } else if (ext == "gltf" || ext == "glb") {
                renderer_.reset();
                loadLook(path, options_.look);
                rebuildRenderer();
            } else {
                throw gdi::Error(
                    path + ": unsupported format: drop a glTF 2.0 file (.gltf, .glb) or an .hdr");
            }
            message_.clear();
            std::cout << "opened " << path << "\n";
        } catch (const std::exception& e) {
            message_ = e.what();
            std::cerr << "fe view: cannot open " << path << ": " << e.what() << "\n";
            if (!renderer_) {  // the old scene is gone: show the quick start's again
                loadLook(options_.scene, options_.look);
                rebuildRenderer();
            }
        }
    }

    // ViewerOptions::inputScript's entries for `frame`, added to what the window reported.
    void scriptedInput(uint32_t frame, gdi::InputState& in) const {
        static const std::map<std::string, gdi::Key> keys = {{"Esc", gdi::Key::Escape},
                                                             {"F12", gdi::Key::F12},
                                                             {"F1", gdi::Key::F1},
                                                             {"R", gdi::Key::R},
                                                             {"F", gdi::Key::F}};
        std::stringstream script(options_.inputScript);
        for (std::string entry; std::getline(script, entry, ',');) {
            const size_t colon = entry.find(':');
            if (colon == std::string::npos || std::stoul(entry.substr(0, colon)) != frame) continue;
            const std::string what = entry.substr(colon + 1);
            if (what.rfind("drop=", 0) == 0)
                in.droppedFiles.push_back(what.substr(5));
            else if (keys.count(what))
                ++in.presses[size_t(keys.at(what))];
        }
    }

    // fe-view-001.png, fe-view-002.png, ...: the first name not taken in the working directory.
    std::string nextScreenshotPath() const {
        for (uint32_t n = 1;; ++n) {
            char name[32];
            std::snprintf(name, sizeof name, "fe-view-%03u.png", n);
            if (!std::filesystem::exists(name)) return name;
        }
    }

    void startDevice(const std::string& backend) {
        device_ = gdi::createDevice(
            {.backend = backend, .validation = options_.validation, .window = true});
        ui_ = std::make_unique<render::UiRenderer>(*device_);
        if (!options_.postShader.empty())
            post_ = std::make_unique<PostShader>(*device_, options_.postShader);
        rebuildRenderer();
    }
    void stopDevice() {
        if (windowTexture_) device_->destroy(windowTexture_);
        windowTexture_ = {};
        post_.reset();
        renderer_.reset();
        ui_.reset();
        device_.reset();
    }
    void rebuildRenderer() {
        renderer_.reset();
        renderer_ = std::make_unique<render::SceneRenderer>(*device_, scene_, settings_);
    }

    // The panel's changes take effect between frames: a new renderer, or a new device.
    void applyPendingChanges() {
        if (!pendingBackend_.empty()) {
            const std::string backend = pendingBackend_;
            pendingBackend_.clear();
            const std::string previous = device_->info().backend;
            stopDevice();
            try {
                startDevice(backend);
                message_.clear();
            } catch (const gdi::Error& e) {
                message_ = e.what();
                startDevice(previous);
            }
            return;
        }
        if (!pendingSettings_) return;
        const render::RenderSettings previous = settings_;
        settings_ = *pendingSettings_;
        pendingSettings_.reset();
        if (wantEnvironment_ != bool(scene_.environment)) {
            if (wantEnvironment_)
                scene_.environment = assets::loadEnvironment("builtin:sky");
            else
                scene_.environment.reset(), settings_.iblSamples = 0,
                                            settings_.iblPrefiltered = false;
        }
        try {
            rebuildRenderer();
            message_.clear();
        } catch (const gdi::Error&
                     e) {  // a combination the technique refuses: say so, keep the last one
            message_ = e.what();
            settings_ = previous;
            wantEnvironment_ = bool(scene_.environment) || previous.ibl();
            rebuildRenderer();
        }
    }

    void moveCamera(const gdi::InputState& in, float dt) {
        const ImGuiIO& io = ImGui::GetIO();
        if (!io.WantCaptureMouse) {
            if (in.mouse[0] && mouseWasDown_) {
                camera_.yaw -= (in.mouseX - lastMouse_.x) * 0.01f;
                camera_.pitch =
                    std::clamp(camera_.pitch + (in.mouseY - lastMouse_.y) * 0.01f, -1.5f, 1.5f);
            }
            if (in.wheel != 0)
                camera_.distance = std::max(0.05f, camera_.distance * std::pow(0.9f, in.wheel));
        }
        mouseWasDown_ = in.mouse[0];
        lastMouse_ = {in.mouseX, in.mouseY};
        if (io.WantCaptureKeyboard) return;
        const glm::vec3 forward = glm::normalize(camera_.target - camera_.eye());
        const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
        const float speed = camera_.distance * dt * (in.down(gdi::Key::LeftShift) ? 3.0f : 1.0f);
        glm::vec3 move{0.0f};
        if (in.down(gdi::Key::W)) move += forward;
        if (in.down(gdi::Key::S)) move -= forward;
        if (in.down(gdi::Key::D)) move += right;
        if (in.down(gdi::Key::A)) move -= right;
        if (in.down(gdi::Key::E)) move += glm::vec3(0, 1, 0);
        if (in.down(gdi::Key::Q)) move -= glm::vec3(0, 1, 0);
        camera_.target += move * speed;
    }

    void panel() {
        // A column of its own, full height, opaque: beside the scene. Collapsing it (its arrow,
        // or F1) gives the scene the whole window.
        ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(float(panelWidth()), float(options_.height)),
                                 ImGuiCond_Always);
        ImGui::SetNextWindowCollapsed(panelCollapsed_, ImGuiCond_Always);
        ImGui::SetNextWindowBgAlpha(1.0f);
        const bool open =
            ImGui::Begin("fe view", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
        if (!open) {
            ImGui::End();
            return;
        }
        ImGui::PushItemWidth(150);
        const gdi::DeviceInfo& info = device_->info();
        ImGui::Text("backend");
        for (const char* b : {"vulkan-glfw", "gl-glfw"}) {
            ImGui::SameLine();
            if (ImGui::RadioButton(b == std::string("vulkan-glfw") ? "Vulkan" : "GL",
                                   info.backend == b) &&
                info.backend != b)
                pendingBackend_ = b;
        }
        ImGui::TextWrapped("%s%s", info.deviceName.c_str(),
                           info.softwareRasterizer ? " (software rasterizer)" : "");
        render::RenderSettings s = pendingSettings_ ? *pendingSettings_ : settings_;
        bool changed = false;
        const render::TechniqueInfo& current = render::findTechnique(s.technique);
        if (ImGui::BeginCombo("technique", s.technique.c_str())) {
            for (const render::TechniqueInfo& t : render::techniques())
                if (ImGui::Selectable(t.name, s.technique == t.name)) {
                    s.technique = t.name;
                    if (!t.msaa) s.msaa = 1;
                    if (!t.illumScale) s.illumScale = 1;
                    changed = true;
                }
            ImGui::EndCombo();
        }
        if (current.illumScale) {
            int scale = int(s.illumScale);
            ImGui::Text("illumination scale");
            for (int v : {1, 2, 4}) {
                ImGui::SameLine();
                changed |= ImGui::RadioButton(("1/" + std::to_string(v)).c_str(), &scale, v);
            }
            s.illumScale = uint32_t(scale);
        }
        if (current.msaa) {
            int msaa = int(s.msaa);
            ImGui::Text("MSAA");
            for (int v : {1, 2, 4, 8}) {
                ImGui::SameLine();
                changed |= ImGui::RadioButton(("x" + std::to_string(v)).c_str(), &msaa, v);
            }
            s.msaa = uint32_t(msaa);
        }
        changed |= ImGui::Checkbox("shadows", &s.shadows.enabled);
        bool environment = wantEnvironment_ || bool(scene_.environment);
        if (ImGui::Checkbox("sky environment", &environment))
            wantEnvironment_ = environment, changed = true;
        if (environment) {
            int samples = int(s.iblSamples);
            if (ImGui::SliderInt("IBL samples", &samples, 0, 256))
                s.iblSamples = uint32_t(samples), s.iblPrefiltered = false;
            changed |= ImGui::IsItemDeactivatedAfterEdit();
            if (ImGui::Checkbox("IBL prefiltered", &s.iblPrefiltered))
                s.iblSamples = 0, changed = true;
        }
        if (ImGui::BeginCombo("tone mapper", shading::tonemapName(s.tonemap))) {
            for (shading::Tonemap t :
                 {shading::Tonemap::Clamp, shading::Tonemap::Aces, shading::Tonemap::PbrNeutral})
                if (ImGui::Selectable(shading::tonemapName(t), s.tonemap == t))
                    s.tonemap = t, changed = true;
            ImGui::EndCombo();
        }
        int aa = int(s.antiAliasing);
        ImGui::Text("AA");
        for (auto [name, value] :
             {std::pair{"none", 0}, std::pair{"FXAA", 1}, std::pair{"TAA", 2}}) {
            ImGui::SameLine();
            if (ImGui::RadioButton(name, &aa, value))
                s.antiAliasing = render::AntiAliasing(aa), changed = true;
        }
        // A multiplier, as fe render's --exposure.
        ImGui::SliderFloat("exposure", &s.exposure, 1.0f / 256.0f, 256.0f, "x%.3g",
                           ImGuiSliderFlags_Logarithmic);
        changed |= ImGui::IsItemDeactivatedAfterEdit();
        // Debug views: any 2D intermediate of this frame's graph.
        if (ImGui::BeginCombo("debug view",
                              s.debugView.empty() ? "frame (L_o)" : s.debugView.c_str())) {
            if (ImGui::Selectable("frame (L_o)", s.debugView.empty()))
                s.debugView.clear(), changed = true;
            for (const char* view : {render::SceneRenderer::kLightCountView,
                                     render::SceneRenderer::kLightsEvaluatedView})
                if (ImGui::Selectable(view, s.debugView == view))
                    s.debugView = view, changed = true;
            for (const graph::TextureInfo& t : renderer_->graph().textures()) {
                const auto& f = gdi::formatInfo(t.desc.format);
                if (!t.used() || f.isInteger || t.name == "debug view" ||
                    t.name.rfind("display", 0) == 0 || t.name == "tonemapped sRGB" ||
                    t.desc.dimension == gdi::TextureDimension::TextureCubeArray ||
                    t.desc.dimension == gdi::TextureDimension::Texture3D || t.desc.sampleCount > 1)
                    continue;
                if (ImGui::Selectable(t.name.c_str(), s.debugView == t.name))
                    s.debugView = t.name, changed = true;
            }
            ImGui::EndCombo();
        }
        if (changed)
            pendingSettings_ = s;
        else if (s.exposure != settings_.exposure)
            settings_.exposure = s.exposure, pendingSettings_ = s;
        animationPanel();
        if (!message_.empty())
            ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", message_.c_str());
        ImGui::Separator();
        ImGui::Text("frame %.1f ms (CPU)", frameMs_);
        if (ImGui::BeginTable("passes", 2)) {
            for (const auto& t : timings_) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(t.name.c_str());
                ImGui::TableNextColumn();
                ImGui::Text("%.2f ms", t.gpuMilliseconds);
            }
            ImGui::EndTable();
        }
        ImGui::TextDisabled(
            "drag: orbit, wheel: zoom, W A S D Q E: fly\nR: reset camera, F: frame all, F1: panel\n"
            "F12: screenshot, Esc: quit; drop a .gltf, .glb or .hdr here");
        ImGui::PopItemWidth();
        ImGui::End();
    }

    // The playing animation's duration (all of them: the longest).
    double animationDuration() const {
        double d = 0.0;
        for (size_t i = 0; i < scene_.animations.size(); ++i)
            if (animation_ == assets::kAllAnimations || int32_t(i) == animation_)
                d = std::max(d, double(scene_.animations[i].duration));
        return d;
    }

    // The file's animations (pick, play or pause, loop, scrub) and cameras (look through one).
    void animationPanel() {
        if (!scene_.animations.empty()) {
            ImGui::Separator();
            auto name = [&](int32_t i) {
                const std::string& n = scene_.animations[size_t(i)].name;
                return std::to_string(i) + (n.empty() ? "" : " " + n);
            };
            const std::string current = animation_ == -1                       ? "rest pose"
                                        : animation_ == assets::kAllAnimations ? "all"
                                                                               : name(animation_);
            if (ImGui::BeginCombo("animation", current.c_str())) {
                if (ImGui::Selectable("rest pose", animation_ == -1))
                    animation_ = -1, assets::poseScene(scene_, {}), renderer_->updatePose();
                if (ImGui::Selectable("all", animation_ == assets::kAllAnimations))
                    animation_ = assets::kAllAnimations, time_ = 0.0;
                for (int32_t i = 0; i < int32_t(scene_.animations.size()); ++i)
                    if (ImGui::Selectable(name(i).c_str(), animation_ == i))
                        animation_ = i, time_ = 0.0;
                ImGui::EndCombo();
            }
            if (animation_ != -1) {
                ImGui::Checkbox("play", &playing_);
                ImGui::SameLine();
                ImGui::Checkbox("loop", &loop_);
                float t = float(time_);
                if (ImGui::SliderFloat("time", &t, 0.0f, float(animationDuration()), "%.2f s"))
                    time_ = t;
            }
        }
        if (!scene_.cameras.empty()) {
            auto label = [&](int32_t i) {
                return std::to_string(i) + " " + scene_.cameras[size_t(i)].name;
            };
            if (ImGui::BeginCombo("camera",
                                  fileCamera_ < 0 ? "orbit (drag)" : label(fileCamera_).c_str())) {
                if (ImGui::Selectable("orbit (drag)", fileCamera_ < 0)) fileCamera_ = -1;
                for (int32_t i = 0; i < int32_t(scene_.cameras.size()); ++i)
                    if (ImGui::Selectable(label(i).c_str(), fileCamera_ == i)) fileCamera_ = i;
                ImGui::EndCombo();
            }
        }
    }

    // What the window shows (the panel too, unless --no-ui).
    void screenshot(const std::string& path) {
        gdi::writePng(device_->readTexture(shown_ ? shown_ : renderer_->displayTexture()), path);
        std::cout << "wrote " << path << " (" << device_->info().backend << ", "
                  << settings_.technique << (settings_.ibl() ? ", environment light" : "")
                  << (settings_.shadows.enabled ? ", shadows" : "");
        if (animation_ != -1) std::cout << ", animation " << animation_ << " at " << time_ << " s";
        if (fileCamera_ >= 0) std::cout << ", camera " << fileCamera_;
        std::cout << ")\n";
    }

    ViewerOptions options_;
    assets::Scene scene_;
    render::RenderSettings settings_;
    OrbitCamera camera_;
    std::unique_ptr<gdi::Device> device_;
    std::unique_ptr<render::UiRenderer> ui_;
    std::unique_ptr<render::SceneRenderer> renderer_;
    std::unique_ptr<PostShader> post_;  // --post-shader
    std::vector<graph::PassTiming> timings_;
    double frameMs_ = 0;
    int32_t animation_ = -1;  // playing (Scene::animations), -1: the rest pose
    double time_ = 0.0;       // its time, seconds
    bool playing_ = true, loop_ = true;
    int32_t fileCamera_ = -1;  // looking through Scene::cameras[i], -1: the orbit camera
    std::optional<render::RenderSettings> pendingSettings_;
    std::string pendingBackend_, message_;
    bool wantEnvironment_ = false;
    bool mouseWasDown_ = false;
    bool panelCollapsed_ = false;
    gdi::TextureHandle windowTexture_, shown_;
    glm::vec2 lastMouse_{0.0f};
};

}  // namespace

int runViewer(const ViewerOptions& options) {
    // Ctrl-C (and SIGTERM) end the loop after the frame in progress: the screenshot is written
    // and the device closed as after the last frame.
    std::signal(SIGINT, [](int) { interrupted.store(true); });
    std::signal(SIGTERM, [](int) { interrupted.store(true); });
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace fe::tools
