#version 330 core
#extension GL_ARB_texture_gather : require
#extension GL_ARB_gpu_shader5 : require
// SignStudy's anti-aliasing pass, fragment stage: fast approximate anti-aliasing after
// Lottes (NVIDIA, FXAA 3.11, its "quality" form), in pixel units with north at +y.
// A pixel whose neighbourhood spans enough luma contrast lies on an edge; the edge runs
// along x or y (whichever second derivative is smaller), and its pixels blend towards
// the neighbour across the edge by how far they are from the nearer end of the edge
// (found by walking along it), which turns a staircase into a ramp. A pixel brighter
// or darker than all around it (a thin feature) blends with them too. Flat areas keep
// their colour, so skin shading and the background pass through unchanged.
// The scene's pass leaves each pixel's luma in its alpha (mesh.frag, the renderer's
// clear colour), so the neighbourhood is two gathers of one channel: on llvmpipe the
// neighbourhood test over every pixel was most of this pass's cost (issue 52).

uniform sampler2D frame;
uniform vec2 texel;

out vec4 frag_color;

// Contrast below which a neighbourhood is no edge: absolute, and relative to its
// brightest pixel. Subpixel blending's strength (0 off, 1 full).
const float EDGE_MIN = 1.0 / 16.0;
const float EDGE_RELATIVE = 1.0 / 8.0;
const float SUBPIXEL = 0.75;
// The walk along an edge: steps of growing length in pixels, up to 19 px each way
// (longer walks cost more than they smoothed, bench/bench_antialias.py).
const int STEPS = 5;
const float STEP_PX[STEPS] = float[](1.0, 2.0, 4.0, 4.0, 8.0);

float luma_at(ivec2 pixel)
{
    ivec2 last = textureSize(frame, 0) - 1;
    return texelFetch(frame, clamp(pixel, ivec2(0), last), 0).a;
}

void main()
{
    // The four neighbours' lumas in two gathers (texels around a corner; the texture
    // clamps at the frame's border). A flat pixel keeps its colour: nothing is written.
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 south_west = textureGather(frame, vec2(pixel) * texel, 3);
    vec4 north_east = textureGather(frame, vec2(pixel + 1) * texel, 3);
    float l_m = south_west.y;
    float l_w = south_west.x;
    float l_s = south_west.z;
    float l_n = north_east.x;
    float l_e = north_east.z;
    float l_min = min(l_m, min(min(l_n, l_s), min(l_e, l_w)));
    float l_max = max(l_m, max(max(l_n, l_s), max(l_e, l_w)));
    float contrast = l_max - l_min;
    if (contrast < max(EDGE_MIN, l_max * EDGE_RELATIVE)) {
        discard;
    }
    float l_ne = north_east.y;
    float l_nw = luma_at(pixel + ivec2(-1, 1));
    float l_se = luma_at(pixel + ivec2(1, -1));
    float l_sw = south_west.w;

    // An edge along x changes most from south to north.
    float across_y = abs(l_nw + l_sw - 2.0 * l_w) + 2.0 * abs(l_n + l_s - 2.0 * l_m)
                   + abs(l_ne + l_se - 2.0 * l_e);
    float across_x = abs(l_nw + l_ne - 2.0 * l_n) + 2.0 * abs(l_e + l_w - 2.0 * l_m)
                   + abs(l_sw + l_se - 2.0 * l_s);
    bool along_x = across_y >= across_x;
    vec2 along = along_x ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    vec2 across = along_x ? vec2(0.0, 1.0) : vec2(1.0, 0.0);
    float l_plus = along_x ? l_n : l_e;
    float l_minus = along_x ? l_s : l_w;
    // Blend towards the side across the edge with the steeper step.
    bool to_plus = abs(l_plus - l_m) >= abs(l_minus - l_m);
    float l_side = to_plus ? l_plus : l_minus;
    float side = to_plus ? 1.0 : -1.0;
    float step_threshold = 0.25 * abs(l_side - l_m);
    float l_edge = 0.5 * (l_side + l_m);

    // Walk both ways along the edge, on the line between this pixel and its side
    // neighbour (a bilinear sample there averages the two), until the luma leaves the
    // edge's.
    vec2 start = gl_FragCoord.xy + 0.5 * side * across;
    float d_back = 0.0;
    float d_ahead = 0.0;
    float end_back = 0.0;
    float end_ahead = 0.0;
    bool done_back = false;
    bool done_ahead = false;
    for (int i = 0; i < STEPS; i++) {
        if (!done_back) {
            d_back += STEP_PX[i];
            end_back = texture(frame, (start - d_back * along) * texel).a - l_edge;
            done_back = abs(end_back) >= step_threshold;
        }
        if (!done_ahead) {
            d_ahead += STEP_PX[i];
            end_ahead = texture(frame, (start + d_ahead * along) * texel).a - l_edge;
            done_ahead = abs(end_ahead) >= step_threshold;
        }
        if (done_back && done_ahead) {
            break;
        }
    }
    // The staircase's nearer end decides: a pixel whose luma lies on the other side of
    // the edge's from that end's is on the step that the ramp lifts.
    bool back_nearer = d_back < d_ahead;
    float end_nearer = back_nearer ? end_back : end_ahead;
    bool on_step = ((l_m - l_edge) < 0.0) != (end_nearer < 0.0);
    float edge_offset = on_step ? 0.5 - min(d_back, d_ahead) / (d_back + d_ahead) : 0.0;

    // A thin feature: the neighbourhood's mean is far from this pixel's luma.
    float l_mean = (2.0 * (l_n + l_s + l_e + l_w) + l_ne + l_nw + l_se + l_sw) / 12.0;
    float lone = clamp(abs(l_mean - l_m) / contrast, 0.0, 1.0);
    lone = smoothstep(0.0, 1.0, lone);
    float subpixel_offset = lone * lone * SUBPIXEL;

    float offset = max(edge_offset, subpixel_offset);
    vec2 uv = (gl_FragCoord.xy + offset * side * across) * texel;
    frag_color = vec4(texture(frame, uv).rgb, 1.0);
}
