// glTF animation: keyframe sampling as the glTF 2.0 specification defines it, the
// CPU posing (assets::poseScene, float) against the double-precision reference evaluated from the
// keys on its own (reference/AnimationReference.h), and the device's deformation pass
// (render/MeshDeformation.h) against that reference on every backend: the deformed vertices the
// GPU wrote, read back, within 1e-5 of the model's size of the reference's.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "BackendTest.h"
#include "assets/Animation.h"
#include "assets/GltfLoader.h"
#include "integration/SceneRenderer.h"
#include "reference/AnimationReference.h"
#include "reference/CpuReference.h"

using namespace fe;

namespace {

#define FE_REQUIRE_ASSETS()                                               \
    if (!std::filesystem::exists(std::string(FE_SHARED_ASSETS) + "/Fox")) \
    GTEST_SKIP() << "the sample models (../shared/assets) are not here"

assets::AnimationSampler sampler(assets::Interpolation interpolation, std::vector<float> times,
                                 std::vector<float> values, uint32_t width) {
    return {.times = std::move(times),
            .values = std::move(values),
            .interpolation = interpolation,
            .width = width};
}

std::vector<float> at(const assets::AnimationSampler& s, float t, bool rotation = false) {
    std::vector<float> out(s.width);
    assets::sampleAnimation(s, t, rotation, out.data());
    return out;
}

// The animated sample models, each at several instants (the last after its end).
struct Case {
    const char* path;
    std::vector<double> fractions;  // of the animation's duration
};
const std::vector<Case> kCases = {
    {"SimpleSkin/glTF/SimpleSkin.gltf", {0.0, 0.37, 0.81, 1.3}},
    {"RiggedSimple/glTF/RiggedSimple.gltf", {0.0, 0.29, 0.66, 1.2}},
    {"SimpleMorph/glTF/SimpleMorph.gltf", {0.0, 0.41, 0.77, 1.1}},
    {"BoxAnimated/glTF/BoxAnimated.gltf", {0.0, 0.23, 0.58, 0.91}},
    {"Fox/glTF/Fox.gltf", {0.0, 0.31, 0.74}},
    {"CesiumMilkTruck/glTF/CesiumMilkTruck.gltf", {0.0, 0.45, 0.88}},
};

assets::Scene loadSample(const char* rel) {
    return assets::loadGltf(std::string(FE_SHARED_ASSETS) + "/" + rel);
}

// A length the model's coordinates are measured against: its rest bounds' diagonal.
double modelSize(const assets::Scene& scene) {
    return std::max(1e-6, double(glm::length(scene.bounds.size())));
}

}  // namespace

TEST(AnimationSampling, LinearStepAndHoldingBeforeAndAfterTheKeys) {
    const auto linear =
        sampler(assets::Interpolation::Linear, {0, 1, 3}, {0, 0, 0, 2, 4, 6, 2, 0, 0}, 3);
    EXPECT_EQ(at(linear, 0.5f), (std::vector<float>{1, 2, 3}));
    EXPECT_EQ(at(linear, 2.0f), (std::vector<float>{2, 2, 3}));
    EXPECT_EQ(at(linear, -1.0f),
              (std::vector<float>{0, 0, 0}));  // before the first key: the first value
    EXPECT_EQ(at(linear, 5.0f), (std::vector<float>{2, 0, 0}));  // after the last: the last
    const auto step =
        sampler(assets::Interpolation::Step, {0, 1, 3}, {0, 0, 0, 2, 4, 6, 2, 0, 0}, 3);
    EXPECT_EQ(at(step, 0.99f), (std::vector<float>{0, 0, 0}));
    EXPECT_EQ(at(step, 1.0f), (std::vector<float>{2, 4, 6}));
    EXPECT_EQ(at(step, 2.9f), (std::vector<float>{2, 4, 6}));
}

TEST(AnimationSampling, CubicSplineTangentsAreScaledByTheKeyInterval) {
    // Keys at 0 and 2: (in, value, out) = (0, 0, 1) then (0, 1, 0). Halfway, u = 1/2:
    // h00 v0 + h10 dt b0 + h01 v1 + h11 dt a1 = 0 + 0.125 x 2 x 1 + 0.5 x 1 + 0 = 0.75
    // (0.625 with unscaled tangents).
    const auto cubic = sampler(assets::Interpolation::CubicSpline, {0, 2}, {0, 0, 1, 0, 1, 0}, 1);
    EXPECT_NEAR(at(cubic, 1.0f)[0], 0.75f, 1e-6f);
    EXPECT_EQ(at(cubic, -1.0f)[0], 0.0f);  // the value, not a tangent, outside the keys
    EXPECT_EQ(at(cubic, 3.0f)[0], 1.0f);
    // Rotations are normalised after the spline.
    const glm::quat a = glm::angleAxis(0.0f, glm::vec3(0, 1, 0)),
                    b = glm::angleAxis(1.0f, glm::vec3(0, 1, 0));
    const auto spin = sampler(
        assets::Interpolation::CubicSpline, {0, 1},
        {0, 0, 0, 0, a.x, a.y, a.z, a.w, 0, 0, 0, 0, 0, 0, 0, 0, b.x, b.y, b.z, b.w, 0, 0, 0, 0},
        4);
    const std::vector<float> q = at(spin, 0.5f, true);
    EXPECT_NEAR(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]), 1.0f, 1e-6f);
}

TEST(AnimationSampling, RotationsTakeTheShorterArc) {
    // The same 90-degree turn about Y stored as its negative: halfway is 45 degrees, not 225.
    const glm::quat a(1, 0, 0, 0), b = -glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
    const auto s =
        sampler(assets::Interpolation::Linear, {0, 1}, {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w}, 4);
    const std::vector<float> v = at(s, 0.5f, true);
    const glm::quat q(v[3], v[0], v[1], v[2]);
    EXPECT_NEAR(glm::degrees(glm::angle(q)), 45.0f, 1e-3f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
    // Slerp, not a normalised lerp: a quarter of the way along a 90-degree arc is 22.5 degrees.
    const glm::quat c = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
    const auto s2 =
        sampler(assets::Interpolation::Linear, {0, 1}, {a.x, a.y, a.z, a.w, c.x, c.y, c.z, c.w}, 4);
    const std::vector<float> w = at(s2, 0.25f, true);
    EXPECT_NEAR(glm::degrees(glm::angle(glm::quat(w[3], w[0], w[1], w[2]))), 22.5f, 1e-3f);
}

TEST(AnimationSampling, LoopWrapsTheTimeOnlyWhenAsked) {
    FE_REQUIRE_ASSETS();
    assets::Scene box = loadSample("BoxAnimated/glTF/BoxAnimated.gltf");
    const float d = box.animations[0].duration;
    ASSERT_GT(d, 1.0f);
    auto worlds = [&](double t, bool loop) {
        assets::poseScene(box, {.animation = 0, .seconds = t, .loop = loop});
        std::vector<glm::mat4> w;
        for (const auto& i : box.instances) w.push_back(i.world);
        return w;
    };
    EXPECT_EQ(worlds(0.4 + d, true), worlds(0.4, false));
    EXPECT_EQ(worlds(0.4 + d, false), worlds(d, false));
    EXPECT_NE(worlds(0.4, false), worlds(d, false));
}

TEST(AnimationSampling, AnimationsAndCamerasAreFoundByIndexOrName) {
    FE_REQUIRE_ASSETS();
    const assets::Scene fox = loadSample("Fox/glTF/Fox.gltf");
    EXPECT_EQ(assets::findAnimation(fox, "Run"), 2);
    EXPECT_EQ(assets::findAnimation(fox, "1"), 1);
    try {
        assets::findAnimation(fox, "Jump");
        FAIL() << "no animation Jump";
    } catch (const assets::AssetError& e) {
        EXPECT_NE(std::string(e.what()).find("'Survey', 1 'Walk', 2 'Run'"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(assets::findAnimation(fox, "3"), assets::AssetError);
    EXPECT_EQ(assets::findAnimation(fox, "all"), assets::kAllAnimations);
    EXPECT_THROW(assets::poseScene(const_cast<assets::Scene&>(fox), {.animation = 7}),
                 assets::AssetError);
}

// Cameras and lights hung from animated nodes follow them; a camera of one's own (cameraIndex
// -1) stays where it was put.
TEST(AnimationSampling, CamerasAndLightsFollowTheirNodes) {
    assets::Scene scene;
    assets::Node parent, child;
    parent.name = "rig";
    child.name = "head";
    child.parent = 0;
    child.translation = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.nodes = {parent, child};
    assets::Camera camera =
        assets::Camera::lookAlong({0, 1, 0}, {0, 0, -1}, {0, 1, 0}, 0.8f, 0.1f, 100.0f);
    camera.node = 1;
    scene.cameras = {camera};
    scene.cameraIndex = 0;
    scene.camera = camera;
    assets::Light lamp;
    lamp.node = 1;
    scene.lights = {lamp};
    assets::Animation slide{.name = "slide", .duration = 2.0f};
    slide.samplers.push_back(sampler(assets::Interpolation::Linear, {0, 2}, {0, 0, 0, 4, 0, 0}, 3));
    slide.channels.push_back({.sampler = 0, .node = 0, .path = assets::AnimationPath::Translation});
    scene.animations = {slide};
    assets::poseScene(scene, {.animation = 0, .seconds = 1.0});
    EXPECT_EQ(scene.camera->eye(),
              glm::vec3(2.0f, 1.0f, 0.0f));  // the parent's translation under the child's
    EXPECT_EQ(scene.cameras[0].eye(), glm::vec3(2.0f, 1.0f, 0.0f));
    EXPECT_EQ(scene.lights[0].position, glm::vec3(2.0f, 1.0f, 0.0f));
    // A camera of one's own stays, whether or not cameraIndex still names the file's.
    scene.camera =
        assets::Camera::lookAlong({5, 5, 5}, {-1, -1, -1}, {0, 1, 0}, 0.8f, 0.1f, 100.0f);
    assets::poseScene(scene, {.animation = 0, .seconds = 2.0});
    EXPECT_EQ(scene.camera->eye(), glm::vec3(5.0f));
    scene.cameraIndex = -1;
    assets::poseScene(scene, {.animation = 0, .seconds = 1.5});
    EXPECT_EQ(scene.camera->eye(), glm::vec3(5.0f));
    EXPECT_EQ(scene.cameras[0].eye(),
              glm::vec3(3.0f, 1.0f, 0.0f));  // the file's camera still follows its node
}

// assets::poseScene (float, what the renderer draws) against the reference (double, from the keys).
TEST(AnimationReference, CpuPosingMatchesTheReference) {
    FE_REQUIRE_ASSETS();
    for (const Case& c : kCases) {
        assets::Scene scene = loadSample(c.path);
        const double size = modelSize(scene);
        // Each animation, and all of them at once (the later wins where two animate the same).
        for (int32_t a = assets::kAllAnimations; a < int32_t(scene.animations.size()); ++a)
            for (double f : c.fractions) {
                if (a == -1) continue;
                const float duration = a >= 0 ? scene.animations[size_t(a)].duration
                                              : scene.animations.back().duration;
                const assets::PoseTime time{.animation = a, .seconds = f * duration};
                SCOPED_TRACE(std::string(c.path) + " animation " + std::to_string(a) + " at " +
                             std::to_string(time.seconds) + " s");
                assets::poseScene(scene, time);
                const render::ReferencePose ref = render::evaluatePose(scene, time);
                for (size_t i = 0; i < scene.instances.size(); ++i) {
                    const assets::MeshInstance& inst = scene.instances[i];
                    for (int col = 0; col < 4; ++col)
                        for (int row = 0; row < 4; ++row)
                            ASSERT_NEAR(inst.world[col][row], ref.instanceWorld[i][col][row],
                                        1e-5 * (col == 3 ? size : 1.0));
                    ASSERT_EQ(inst.joints.size(), ref.joints[i].size());
                    for (size_t j = 0; j < inst.joints.size(); ++j)
                        for (int col = 0; col < 4; ++col)
                            for (int row = 0; row < 4; ++row)
                                ASSERT_NEAR(inst.joints[j][col][row], ref.joints[i][j][col][row],
                                            1e-5 * (col == 3 ? size : 1.0));
                    ASSERT_EQ(inst.weights.size(), ref.weights[i].size());
                    for (size_t w = 0; w < inst.weights.size(); ++w)
                        ASSERT_NEAR(inst.weights[w], ref.weights[i][w], 1e-6);
                }
            }
    }
}

// The deformed vertices the device wrote, read back, against the reference's, in world space
// (instances the animation only moves are checked through their posed transform).
class MeshDeformationTest : public fe::testing::BackendTest {
protected:
    MeshDeformationTest() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

TEST_P(MeshDeformationTest, DeviceDeformationMatchesTheReference) {
    FE_REQUIRE_ASSETS();
    for (const Case& c : kCases) {
        assets::Scene scene = loadSample(c.path);
        const double size = modelSize(scene);
        render::SceneRenderer renderer(*device, scene,
                                       {.technique = "forward", .width = 32, .height = 32});
        const render::GpuScene& gpu = renderer.gpuScene();
        for (int32_t a = 0; a < int32_t(scene.animations.size()); ++a)
            for (double f : c.fractions) {
                const assets::PoseTime time{.animation = a,
                                            .seconds = f * scene.animations[size_t(a)].duration};
                SCOPED_TRACE(std::string(c.path) + " animation " + std::to_string(a) + " at " +
                             std::to_string(time.seconds) + " s");
                assets::poseScene(scene, time);
                renderer.updatePose();
                renderer.renderFrame();
                device->waitIdle();
                const std::vector<uint8_t> bytes = device->readBuffer(
                    gpu.vertexBuffer(), 0, device->desc(gpu.vertexBuffer()).size);
                const auto* gpuVertices = reinterpret_cast<const assets::Vertex*>(bytes.data());
                const render::ReferencePose ref = render::evaluatePose(scene, time);
                double worst = 0.0;
                for (const render::DrawItem& d : gpu.draws()) {
                    const assets::MeshInstance& inst = scene.instances[d.instance];
                    // The draw's primitive: the one of its mesh whose indices start at d.firstIndex.
                    const assets::Mesh& mesh = scene.meshes[inst.meshIndex];
                    const assets::Primitive* prim = nullptr;
                    size_t p = 0;
                    for (; p < mesh.primitives.size(); ++p)
                        if (mesh.primitives[p].indices.size() == d.indexCount) {
                            prim = &mesh.primitives[p];
                            break;
                        }
                    ASSERT_NE(prim, nullptr);
                    const std::vector<render::DeformedVertex> expected = render::deformVertices(
                        *prim, ref.joints[d.instance], ref.weights[d.instance]);
                    for (size_t v = 0; v < prim->vertices.size(); ++v) {
                        const glm::dvec3 got = glm::dvec3(
                            glm::dmat4(inst.world) *
                            glm::dvec4(glm::dvec3(gpuVertices[size_t(d.baseVertex) + v].position),
                                       1.0));
                        const glm::dvec3 want = glm::dvec3(ref.instanceWorld[d.instance] *
                                                           glm::dvec4(expected[v].position, 1.0));
                        worst = std::max(worst, glm::length(got - want) / size);
                    }
                }
                EXPECT_LT(worst, 1e-5)
                    << "the largest distance from the reference, relative to the model's size";
            }
    }
}

// A skin changed by hand after the renderer was made (more joint matrices than it laid out) is
// the same gdi::Error on every backend, not another instance's matrices.
TEST_P(MeshDeformationTest, AJointCountChangedByHandIsRefused) {
    FE_REQUIRE_ASSETS();
    assets::Scene scene = loadSample("SimpleSkin/glTF/SimpleSkin.gltf");
    render::SceneRenderer renderer(*device, scene,
                                   {.technique = "forward", .width = 32, .height = 32});
    scene.instances[0].joints.push_back(glm::mat4(1.0f));
    renderer.updatePose();
    EXPECT_NE(fe::testing::errorOf([&] {
                  renderer.renderFrame();
              }).find("joint matrices where the renderer was made for 2"),
              std::string::npos);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(MeshDeformationTest);

namespace {

gdi::Image referenceImage(const render::ReferenceImage& ref) {
    std::vector<std::array<float, 4>> texels;
    for (const glm::dvec3& v : ref.radiance)
        texels.push_back({float(v.x), float(v.y), float(v.z), 1.0f});
    return gdi::Image::fromTexels(ref.width, ref.height, gdi::Format::RGBA32F, texels);
}

// Pixels (off the reference's silhouettes) whose radiance differs by more than 1 % (0.01 floor),
// and pixels whose coverage differs, as fractions of the image.
struct Agreement {
    double radiance = 0, coverage = 0;
};
Agreement agreement(const gdi::Image& gpu, const render::ReferenceImage& ref) {
    const gdi::Image cpu = referenceImage(ref);
    uint32_t radiance = 0, coverage = 0;
    for (uint32_t y = 0; y < gpu.height; ++y)
        for (uint32_t x = 0; x < gpu.width; ++x) {
            if (ref.nearEdge(x, y)) continue;
            const auto a = gpu.texel(x, y), b = cpu.texel(x, y);
            const bool covered = a[0] + a[1] + a[2] > 0.0f,
                       expected = ref.surface[size_t(y) * gpu.width + x] >= 0;
            coverage += covered != expected;
            bool bad = false;
            for (int c = 0; c < 3; ++c)
                bad = bad ||
                      !(std::abs(a[c] - b[c]) <=
                        0.01 * std::max({std::abs(double(a[c])), std::abs(double(b[c])), 0.01}));
            radiance += bad;
        }
    const double n = double(gpu.width) * gpu.height;
    return {radiance / n, coverage / n};
}

// The pixel box the glTF 2.0 specification's projection (3.10.3, written out here on its own)
// puts the scene's vertices in: y up in NDC, pixel rows from the top.
struct PixelBox {
    double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
};
PixelBox specBox(const assets::Scene& scene, const assets::Camera& camera, uint32_t w, uint32_t h) {
    PixelBox b;
    const glm::dmat4 view = glm::inverse(glm::dmat4(camera.worldFromView));
    for (const assets::MeshInstance& inst : scene.instances)
        for (const assets::Primitive& p : scene.meshes[inst.meshIndex].primitives)
            for (const assets::Vertex& v : p.vertices) {
                const glm::dvec4 e =
                    view * glm::dmat4(inst.world) * glm::dvec4(glm::dvec3(v.position), 1.0);
                double nx, ny;
                if (camera.orthographic) {
                    nx = e.x / camera.orthographic->x;
                    ny = e.y / camera.orthographic->y;
                } else {
                    const double a =
                        camera.aspectRatio ? double(*camera.aspectRatio) : double(w) / h;
                    const double t = std::tan(0.5 * camera.yfov);
                    nx = e.x / (a * t * -e.z);
                    ny = e.y / (t * -e.z);
                }
                const double px = (nx * 0.5 + 0.5) * w, py = (0.5 - ny * 0.5) * h;
                b.x0 = std::min(b.x0, px), b.x1 = std::max(b.x1, px), b.y0 = std::min(b.y0, py),
                b.y1 = std::max(b.y1, py);
            }
    return b;
}
PixelBox coveredBox(const gdi::Image& image) {
    PixelBox b;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const auto t = image.texel(x, y);
            if (t[0] + t[1] + t[2] <= 0.0f) continue;
            b.x0 = std::min(b.x0, double(x)), b.x1 = std::max(b.x1, x + 1.0),
            b.y0 = std::min(b.y0, double(y)), b.y1 = std::max(b.y1, y + 1.0);
        }
    return b;
}

}  // namespace

// What every technique draws of an animated model is what the reference traces of it: the
// deformation reaches the G-buffer and visibility-buffer techniques as it reaches forward.
class AnimatedRender : public fe::testing::BackendTest {
protected:
    AnimatedRender() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

TEST_P(AnimatedRender, PosedModelsMatchTheReferenceOnEveryTechniqueKind) {
    FE_REQUIRE_ASSETS();
    struct Posed {
        const char* path;
        const char* animation;
        double seconds;
        std::vector<const char*> techniques;
    };
    for (const Posed& c :
         {Posed{"Fox/glTF/Fox.gltf", "Walk", 0.43, {"forward", "deferred", "visibility-buffer"}},
          Posed{"RiggedSimple/glTF/RiggedSimple.gltf", "0", 0.6, {"forward"}},
          Posed{"SimpleMorph/glTF/SimpleMorph.gltf", "0", 1.1, {"forward"}},
          Posed{"CesiumMilkTruck/glTF/CesiumMilkTruck.gltf", "Wheels", 0.5, {"forward"}}}) {
        assets::Scene scene = loadSample(c.path);
        // Untextured: texture filtering differs between rasterizer and ray tracer, and the
        // deformed normals' shading is what is compared.
        for (assets::Material& m : scene.materials) m.baseColorTexture = {};
        assets::poseScene(
            scene, {.animation = assets::findAnimation(scene, c.animation), .seconds = c.seconds});
        const render::ReferenceImage ref = render::renderReference(scene, *scene.camera, 64, 48);
        for (const char* t : c.techniques) {
            SCOPED_TRACE(std::string(c.path) + " " + t);
            render::SceneRenderer r(*device, scene, {.technique = t, .width = 64, .height = 48});
            r.renderFrame();
            const Agreement a = agreement(r.readOutput(), ref);
            EXPECT_EQ(a.coverage, 0.0);
            EXPECT_LE(a.radiance, 0.002);
        }
    }
}

TEST_P(AnimatedRender, CamerasProjectAsTheSpecificationSays) {
    FE_REQUIRE_ASSETS();
    assets::Scene scene = loadSample("Cameras/glTF/Cameras.gltf");
    // 96x48: the perspective camera's aspectRatio 1 is not the viewport's 2, and it is used.
    for (int32_t camera : {0, 1}) {
        SCOPED_TRACE("camera " + std::to_string(camera));
        const assets::Camera& cam = scene.cameras[size_t(camera)];
        render::SceneRenderer r(*device, scene,
                                {.technique = "forward", .width = 96, .height = 48});
        r.setCamera(cam);
        r.renderFrame();
        const gdi::Image gpu = r.readOutput();
        const PixelBox want = specBox(scene, cam, 96, 48), got = coveredBox(gpu);
        EXPECT_NEAR(got.x0, want.x0, 1.0);
        EXPECT_NEAR(got.x1, want.x1, 1.0);
        EXPECT_NEAR(got.y0, want.y0, 1.0);
        EXPECT_NEAR(got.y1, want.y1, 1.0);
        const Agreement a = agreement(gpu, render::renderReference(scene, cam, 96, 48));
        EXPECT_EQ(a.coverage, 0.0);
        EXPECT_LE(a.radiance, 0.002);
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(AnimatedRender);
