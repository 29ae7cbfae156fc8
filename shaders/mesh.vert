// Mesh vertex shader, shared by every draw mode (filled, edges, points, normals).
// Push constants carry the model's matrices; specialization constants pick the mode.
#version 450

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_color;
// Geomorph start of this vertex: it is drawn at mix(in_morph_from, in_position, pc.morph).
layout(location = 3) in vec3 in_morph_from;
layout(location = 4) in vec2 in_uv;

layout(push_constant) uniform Push {
    mat4 clip_from_model;
    // The top three rows of the affine view-from-model matrix (v * view_rows = view xyz).
    mat3x4 view_rows;
    float morph;
    // 1: the bound texture replaces the vertex colour (VRML 2.0's rule for RGB textures;
    // lighting still applies); 0: the vertex colour, times a white texel.
    float textured;
} pc;

// Overlays (edges, points, normals) are pulled towards the eye by this fraction of the
// clip-space depth range so that they win the depth test against the surface they lie on.
layout(constant_id = 0) const float DEPTH_NUDGE = 0.0;
layout(constant_id = 1) const float POINT_SIZE = 1.0;

layout(location = 0) out vec3 out_view_position;
layout(location = 1) out vec3 out_view_normal;
layout(location = 2) out vec4 out_color;
layout(location = 3) out vec2 out_uv;

void main() {
    vec4 position = vec4(mix(in_morph_from, in_position, pc.morph), 1.0);
    out_view_position = position * pc.view_rows;
    // The normal matrix, inverse transpose of the view's 3x3 (correct under the non-uniform
    // scales VRML transforms allow): mat3(view_rows) is that 3x3 transposed already.
    out_view_normal = inverse(mat3(pc.view_rows)) * in_normal;
    out_color = pc.textured > 0.5 ? vec4(1.0, 1.0, 1.0, in_color.a) : in_color;
    out_uv = in_uv;
    vec4 clip = pc.clip_from_model * position;
    clip.z -= DEPTH_NUDGE * clip.w;
    gl_Position = clip;
    gl_PointSize = POINT_SIZE;
}
