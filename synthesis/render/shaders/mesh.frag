#version 330 core
// SignStudy's skin shader, fragment stage: Lambert diffuse plus a soft Blinn-Phong
// highlight, directional lights (the key may carry a shadow map) and point lights with
// inverse-square falloff. Much cheaper than a full PBR model on a software rasteriser,
// which is where stimuli are rendered (Mesa llvmpipe), and enough for matte skin and
// cloth. Colours arrive in sRGB, are lit in linear light and leave in sRGB.

struct DirectionalLight {
    vec3 color;
    float intensity;
    vec3 direction;
#ifdef DIRECTIONAL_LIGHT_SHADOWS
    sampler2D shadow_map;
    mat4 light_matrix;
#endif
};

struct PointLight {
    vec3 color;
    float intensity;
    float range;
    vec3 position;
};

struct Material {
    vec4 base_color_factor;
    float roughness_factor;
};

// The scene's lights of each kind: the renderer's LIGHT_COUNT_* defines, constants so
// that the loops over them unroll (on llvmpipe a loop bounded by a uniform count,
// indexing the light uniforms, cost a sixth of the frame).
const int N_DIRECTIONAL = min(LIGHT_COUNT_DIRECTIONAL, MAX_DIRECTIONAL_LIGHTS);
const int N_POINT = min(LIGHT_COUNT_POINT, MAX_POINT_LIGHTS);

uniform DirectionalLight directional_lights[MAX_DIRECTIONAL_LIGHTS];
uniform PointLight point_lights[MAX_POINT_LIGHTS];
uniform Material material;
uniform vec3 cam_pos;
uniform vec3 ambient_light;

in vec3 world_position;
in vec3 world_normal;
in vec3 albedo_srgb;
#ifdef TEXCOORD_0_LOC
in float edge_m;
in vec3 across_srgb;
#endif

out vec4 frag_color;

vec3 reflected(vec3 n, vec3 v, vec3 l, vec3 radiance, vec3 albedo)
{
    float lambert = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    // Rough surfaces spread a dim highlight; roughness 0.75 gives a shininess of ~10.
    float shininess = 2.0 / max(material.roughness_factor * material.roughness_factor, 0.01);
    float highlight = lambert > 0.0 ? pow(max(dot(n, h), 0.0), shininess) : 0.0;
    return radiance * (albedo * lambert + 0.04 * highlight);
}

#ifdef DIRECTIONAL_LIGHT_SHADOWS
const float SHADOW_FLOOR = 0.5;

float lit_fraction(mat4 light_matrix, sampler2D shadow_map, vec3 n, float facing)
{
    // Looked up a little off the surface, along its normal, the more so the more the
    // surface turns from the light (normal-offset shadows): a 1024-px map's texel is
    // about 2 mm over the scene, and without the offset a face's slopes shadowed
    // themselves in texel-sized steps.
    vec3 lifted = world_position + n * (0.0015 + 0.005 * (1.0 - facing));
    vec4 projected = light_matrix * vec4(lifted, 1.0);
    vec3 coords = projected.xyz / projected.w * 0.5 + 0.5;
    if (coords.z > 1.0) {
        return 1.0;
    }
    float bias = max(0.0015 * (1.0 - facing), 0.0003);
    vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
    // Nine taps spread over about 1 cm: a soft penumbra, not a hand-shaped stain with
    // jagged edges (issue 52); and a shadow keeps half the key's light, so a hand's
    // shadow shades the chest or the face without blackening it.
    float lit = 0.0;
    for (int k = 0; k < 9; k++) {
        vec2 offset = (vec2(k % 3, k / 3) - 1.0) * 2.0 * texel;
        lit += coords.z - bias > texture(shadow_map, coords.xy + offset).r ? 0.0 : 1.0;
    }
    return mix(SHADOW_FLOOR, 1.0, lit / 9.0);
}
#endif

void main()
{
    vec3 surface_srgb = albedo_srgb;
#ifdef TEXCOORD_0_LOC
    // The edge where the interpolated distance crosses zero, blended over one pixel.
    float pixel_m = max(fwidth(edge_m), 1e-6);
    surface_srgb = mix(across_srgb, albedo_srgb, clamp(0.5 + edge_m / pixel_m, 0.0, 1.0));
#endif
    vec3 albedo = pow(surface_srgb * material.base_color_factor.rgb, vec3(2.2));
    vec3 n = normalize(world_normal);
    vec3 v = normalize(cam_pos - world_position);
    if (dot(n, v) < 0.0) {
        n = -n;  // the inside of a fold seen through a gap: light it like the outside
    }
    vec3 color = ambient_light * albedo;
    for (int i = 0; i < N_DIRECTIONAL; i++) {
        vec3 l = normalize(-directional_lights[i].direction);
        vec3 radiance = directional_lights[i].intensity * directional_lights[i].color;
        vec3 light = reflected(n, v, l, radiance, albedo);
#ifdef DIRECTIONAL_LIGHT_SHADOWS
        light *= lit_fraction(directional_lights[i].light_matrix,
                              directional_lights[i].shadow_map, n,
                              clamp(dot(n, l), 0.0, 1.0));
#endif
        color += light;
    }
    for (int i = 0; i < N_POINT; i++) {
        vec3 to_light = point_lights[i].position - world_position;
        float falloff = 1.0 / max(dot(to_light, to_light), 1e-4);
        vec3 radiance = point_lights[i].intensity * falloff * point_lights[i].color;
        color += reflected(n, v, normalize(to_light), radiance, albedo);
    }
    vec3 srgb = pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2));
    // Alpha carries the pixel's luma for the anti-aliasing pass (fxaa.frag): Rec. 601
    // weights, the renderer's define, the same as its clear colour's.
    frag_color = vec4(srgb, dot(srgb, LUMA_WEIGHTS));
}
