#version 330 core
// SignStudy's skin shader, vertex stage: world position, normal and vertex colour.
// pyrender binds attributes at the locations it passes in as *_LOC defines.
layout(location = 0) in vec3 position;
#ifdef NORMAL_LOC
layout(location = NORMAL_LOC) in vec3 normal;
#endif
#ifdef COLOR_0_LOC
layout(location = COLOR_0_LOC) in vec4 color_0;
#endif
#ifdef TEXCOORD_0_LOC
// A colour edge through the mesh: (signed distance to it, red) and (green, blue) of the
// colour on its negative side.
layout(location = TEXCOORD_0_LOC) in vec2 texcoord_0;
layout(location = TEXCOORD_1_LOC) in vec2 texcoord_1;
out float edge_m;
out vec3 across_srgb;
#endif
layout(location = INST_M_LOC) in mat4 inst_m;

uniform mat4 M;
uniform mat4 V;
uniform mat4 P;

out vec3 world_position;
out vec3 world_normal;
out vec3 albedo_srgb;

void main()
{
    mat4 model = M * inst_m;
    vec4 world = model * vec4(position, 1.0);
    world_position = world.xyz;
#ifdef NORMAL_LOC
    // Avatar meshes are placed by rigid transforms only, so the model matrix itself turns
    // normals (no per-vertex inverse-transpose, which is costly on a software rasteriser).
    world_normal = normalize(mat3(model) * normal);
#else
    world_normal = vec3(0.0, 0.0, 1.0);
#endif
#ifdef COLOR_0_LOC
    albedo_srgb = color_0.rgb;
#else
    albedo_srgb = vec3(1.0);
#endif
#ifdef TEXCOORD_0_LOC
    edge_m = texcoord_0.x;
    across_srgb = vec3(texcoord_0.y, texcoord_1);
#endif
    gl_Position = P * V * world;
}
