#version 330 core
// SignStudy's anti-aliasing pass, vertex stage: one triangle that covers the viewport,
// made from the vertex number alone (no vertex buffer).
void main()
{
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
