#version 450
// A colour made only of specialization constants of every kind: float, uint, bool, int.
layout(constant_id = 0) const float kRed = 0.0;
layout(constant_id = 1) const uint kGreen255 = 0u;
layout(constant_id = 2) const bool kBlue = false;
layout(constant_id = 3) const int kAlphaSteps = 4;  // alpha = steps / 4
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(kRed, float(kGreen255) / 255.0, kBlue ? 1.0 : 0.0, float(kAlphaSteps) / 4.0); }
