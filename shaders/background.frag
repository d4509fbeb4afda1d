#version 330 core
// Vertical gradient behind the model.

in float v;

uniform vec3 top_color;
uniform vec3 bottom_color;

out vec4 frag_color;

void main() { frag_color = vec4(mix(bottom_color, top_color, clamp(v, 0.0, 1.0)), 1.0); }
