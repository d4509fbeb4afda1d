#version 330 core
// Surface and pick passes: positions and smooth normals in view space.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat4 view;
uniform mat4 projection;

out vec3 view_position;
out vec3 view_normal;

void main() {
  vec4 p = view * vec4(position, 1.0);
  view_position = p.xyz;
  view_normal = mat3(view) * normal;  // the view matrix is rigid
  gl_Position = projection * p;
}
