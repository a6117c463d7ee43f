#version 450
#extension GL_GOOGLE_include_directive : require
// A debug view of an intermediate texture (SceneRenderer, RenderSettings::debugView).
#define FE_DEBUG_VIEW 2
#define FE_DEBUG_DEPTH 1  // the engine's layered and cube intermediates are shadow maps
#include "fe_debug_view.glsl"
