// Mesh fragment shader: two-sided headlight lighting, smooth (interpolated normals) or flat
// (face normal from screen-space derivatives, so no vertex is duplicated), or unlit colour.
// The surface colour is the vertex colour times the bound texture (a white texel for an
// untextured model or with textures off; a textured model's vertex colour is white).
#version 450

layout(location = 0) in vec3 in_view_position;
layout(location = 1) in vec3 in_view_normal;
layout(location = 2) in vec4 in_color;
layout(location = 3) in vec2 in_uv;

layout(set = 0, binding = 0) uniform sampler2D u_texture;

layout(location = 0) out vec4 out_color;

// 0: lit smooth, 1: lit flat, 2: unlit vertex colour, 3: constant colour.
layout(constant_id = 2) const int SHADING = 0;
layout(constant_id = 3) const float CONST_R = 0.0;
layout(constant_id = 4) const float CONST_G = 0.0;
layout(constant_id = 5) const float CONST_B = 0.0;
// Points are drawn as round dots (the original's "point smoothing") rather than squares.
layout(constant_id = 6) const bool ROUND_POINTS = false;

void main() {
    if (ROUND_POINTS && length(gl_PointCoord - vec2(0.5)) > 0.5) {
        discard;
    }
    if (SHADING == 3) {
        out_color = vec4(CONST_R, CONST_G, CONST_B, 1.0);
        return;
    }
    // Texture coordinates have their origin at the image's bottom left, Vulkan's rows start
    // at the top.
    vec4 surface = in_color * texture(u_texture, vec2(in_uv.x, 1.0 - in_uv.y));
    if (SHADING == 2) {
        out_color = surface;
        return;
    }
    vec3 n = SHADING == 1
        ? cross(dFdx(in_view_position), dFdy(in_view_position))
        : in_view_normal;
    n = normalize(n);
    vec3 to_eye = normalize(-in_view_position);
    // Two-sided: back faces of open meshes are lit like front faces.
    if (dot(n, to_eye) < 0.0) {
        n = -n;
    }
    // A headlight slightly above and left of the eye, so flat faces facing it still show shape.
    vec3 light = normalize(vec3(-0.3, 0.4, 1.0));
    float diffuse = max(dot(n, light), 0.0);
    vec3 h = normalize(light + to_eye);
    float specular = pow(max(dot(n, h), 0.0), 32.0) * 0.25;
    vec3 rgb = surface.rgb * (0.25 + 0.75 * diffuse) + vec3(specular);
    out_color = vec4(rgb, surface.a);
}
