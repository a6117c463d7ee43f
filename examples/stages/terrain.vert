#version 450
// A control point of the terrain's patches (terrain.tesc, terrain.tese).
layout(location = 0) in vec2 inPosition;  // x, z
layout(location = 0) out vec2 vPosition;
void main() { vPosition = inPosition; }
