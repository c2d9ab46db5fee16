#version 330 core
// Shadow-map pass: only depth matters; the colour is never read.
out vec4 frag_color;

void main()
{
    frag_color = vec4(1.0);
}
