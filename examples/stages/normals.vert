#version 450
// The mesh's vertices in world space, for normals.geom.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 0) out vec3 vPosition;
layout(location = 1) out vec3 vNormal;
void main() {
    vPosition = inPosition;
    vNormal = inNormal;
}
