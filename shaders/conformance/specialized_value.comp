#version 450
// Writes a specialization constant (default 7) into a storage buffer.
layout(local_size_x = 1) in;
layout(constant_id = 0) const uint kValue = 7u;
layout(binding = 0, std430) buffer Out { uint outValue; };
void main() { outValue = kValue; }
