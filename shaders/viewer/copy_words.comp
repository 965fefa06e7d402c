#version 460
// Copies push.count 32-bit words from one device address to another. The renderer uses it once,
// when an interactive session first changes the camera or the film, to take a host-editable
// copy of the scene's GpuSceneParams (whose buffer addresses only the device-side block holds).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SourceRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer DestinationRef { uint v[]; };

layout(push_constant) uniform PushBlock {
    uint64_t source;
    uint64_t destination;
    uint count;
}
push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < push.count) DestinationRef(push.destination).v[i] = SourceRef(push.source).v[i];
}
