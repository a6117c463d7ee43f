// Projection conventions shared by the GPU renderers and the CPU reference: right-handed view
// space (camera looks along -Z), Vulkan clip space (depth 0..1, y down), so that the same
// pixel centre maps to the same ray on the CPU and the GPU.
#pragma once
#include <glm/glm.hpp>

#include <cmath>
#include <limits>

#include "assets/Scene.h"

namespace fe::render {

// Perspective projection to depth [0,1] with y flipped for a top-left framebuffer origin.
// zfar = +inf gives the infinite-far-plane limit.
inline glm::mat4 projection(float yfov, float aspect, float znear, float zfar) {
    const float f = 1.0f / std::tan(yfov * 0.5f);
    glm::mat4 p(0.0f);
    p[0][0] = f / aspect;
    p[1][1] = -f;  // y down in framebuffer space
    p[2][3] = -1.0f;
    if (std::isinf(zfar)) {
        p[2][2] = -1.0f;
        p[3][2] = -znear;
    } else {
        p[2][2] = zfar / (znear - zfar);
        p[3][2] = znear * zfar / (znear - zfar);
    }
    return p;
}

// Orthographic projection of glTF's camera.orthographic (half extents xmag, ymag) to depth [0,1]
// with y flipped: view z = -znear maps to 0, -zfar to 1.
inline glm::mat4 orthographicProjection(glm::vec2 halfExtent, float znear, float zfar) {
    glm::mat4 p(1.0f);
    p[0][0] = 1.0f / halfExtent.x;
    p[1][1] = -1.0f / halfExtent.y;
    p[2][2] = 1.0f / (znear - zfar);
    p[3][2] = znear / (znear - zfar);
    return p;
}

// The aspect ratio a camera projects with: its own when it has one (glTF: aspectRatio, when
// given, is the field of view's, whatever the viewport's: the image stretches when they differ),
// else the viewport's.
inline float projectionAspect(const assets::Camera& camera, float viewportAspect) {
    return camera.aspectRatio.value_or(viewportAspect);
}

// The camera's projection for a viewport of `viewportAspect` (width / height).
inline glm::mat4 projection(const assets::Camera& camera, float viewportAspect) {
    if (camera.orthographic)
        return orthographicProjection(*camera.orthographic, camera.znear, camera.zfar);
    return projection(camera.yfov, projectionAspect(camera, viewportAspect), camera.znear,
                      camera.zfar);
}

inline glm::mat4 viewProjection(const assets::Camera& camera, float aspect) {
    return projection(camera, aspect) * camera.viewFromWorld();
}

}  // namespace fe::render
