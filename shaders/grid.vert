#version 330 core
// The ground grid's lines: world positions, and 1 on major lines.

layout(location = 0) in vec3 position;
layout(location = 1) in float major;

uniform mat4 view;
uniform mat4 projection;

out vec3 world_position;
out float line_major;

void main() {
  world_position = position;
  line_major = major;
  gl_Position = projection * view * vec4(position, 1.0);
}
