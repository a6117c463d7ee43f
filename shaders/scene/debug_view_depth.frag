#version 450
#extension GL_GOOGLE_include_directive : require
// A debug view of a depth texture (SceneRenderer, RenderSettings::debugView).
#define FE_DEBUG_VIEW 1
#define FE_DEBUG_DEPTH 1
#include "fe_debug_view.glsl"
