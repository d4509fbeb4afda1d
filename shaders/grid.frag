#version 330 core
// The ground grid fades out towards its rim (a round floor with no hard edge, as in Blender)
// and where the plane is seen edge-on, where the lines would crowd into a shimmering band.

in vec3 world_position;
in float line_major;

uniform vec3 center;      // the grid's centre, on the ground
uniform vec3 normal;      // the model's up
uniform float radius;     // the grid's half size: fully faded there
uniform vec3 eye;
uniform vec3 view_direction;
uniform bool orthographic;
uniform vec4 minor_color;
uniform vec4 major_color;

out vec4 frag_color;

void main() {
  vec3 d = world_position - center;
  float r = length(d - dot(d, normal) * normal);
  float rim = 1.0 - smoothstep(0.45 * radius, radius, r);
  vec3 ray = orthographic ? view_direction : normalize(world_position - eye);
  float facing = smoothstep(0.02, 0.3, abs(dot(ray, normal)));
  vec4 color = mix(minor_color, major_color, line_major);
  frag_color = vec4(color.rgb, color.a * rim * facing);
}
