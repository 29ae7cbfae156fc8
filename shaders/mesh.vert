// Mesh vertex shader, shared by every draw mode (filled, edges, points, normals).
// Push constants carry the model's matrices; specialization constants pick the mode.
#version 450

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_color;

layout(push_constant) uniform Push {
    mat4 clip_from_model;
    mat4 view_from_model;
} pc;

// Overlays (edges, points, normals) are pulled towards the eye by this fraction of the
// clip-space depth range so that they win the depth test against the surface they lie on.
layout(constant_id = 0) const float DEPTH_NUDGE = 0.0;
layout(constant_id = 1) const float POINT_SIZE = 1.0;

layout(location = 0) out vec3 out_view_position;
layout(location = 1) out vec3 out_view_normal;
layout(location = 2) out vec4 out_color;

void main() {
    vec4 view_position = pc.view_from_model * vec4(in_position, 1.0);
    out_view_position = view_position.xyz;
    // Inverse transpose: correct under the non-uniform scales VRML transforms allow.
    out_view_normal = transpose(inverse(mat3(pc.view_from_model))) * in_normal;
    out_color = in_color;
    vec4 clip = pc.clip_from_model * vec4(in_position, 1.0);
    clip.z -= DEPTH_NUDGE * clip.w;
    gl_Position = clip;
    gl_PointSize = POINT_SIZE;
}
