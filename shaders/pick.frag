#version 330 core
// Pick pass: the face id and the eye depth (distance along the view direction) per pixel.

in vec3 view_position;
in vec3 view_normal;

uniform isamplerBuffer triangle_face;
uniform samplerBuffer face_color;  // red without coverage: a hidden face, never picked

layout(location = 0) out int face_id;
layout(location = 1) out float eye_depth;

void main() {
  face_id = texelFetch(triangle_face, gl_PrimitiveID).r;
  vec4 overlay = texelFetch(face_color, face_id);
  if (overlay.a == 0.0 && overlay.r > 0.5) discard;
  eye_depth = -view_position.z;
}
