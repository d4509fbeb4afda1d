#version 330 core
// The surface: a clay material under a key, fill and rim light, with a per-face overlay
// (selection, handles, painted factors or the energy heat map) looked up by face id.

in vec3 view_position;
in vec3 view_normal;

uniform isamplerBuffer triangle_face;  // fan triangle -> mesh face
uniform samplerBuffer face_color;      // per face RGBA: overlay colour and coverage; red
                                       // without coverage: a hidden face
uniform bool smooth_shading;
uniform vec3 base_color;

out vec4 frag_color;

void main() {
  vec3 v = normalize(-view_position);
  vec3 n;
  if (smooth_shading) {
    n = normalize(view_normal);
    if (!gl_FrontFacing) n = -n;
  } else {
    n = normalize(cross(dFdx(view_position), dFdy(view_position)));  // faces the viewer
  }

  int face = texelFetch(triangle_face, gl_PrimitiveID).r;
  vec4 overlay = texelFetch(face_color, face);
  if (overlay.a == 0.0 && overlay.r > 0.5) discard;
  vec3 albedo = mix(base_color, overlay.rgb, overlay.a);
  if (!gl_FrontFacing) albedo *= vec3(0.62, 0.55, 0.68);  // inside of the surface

  const vec3 key = normalize(vec3(-0.45, 0.65, 0.65));
  const vec3 fill = normalize(vec3(0.7, 0.1, 0.45));
  float diffuse = 0.72 * max(dot(n, key), 0.0) + 0.28 * max(dot(n, fill), 0.0);
  float ambient = mix(0.16, 0.30, 0.5 + 0.5 * n.y);  // sky above, ground below
  vec3 h = normalize(key + v);
  float specular = 0.22 * pow(max(dot(n, h), 0.0), 40.0);
  float rim = 0.12 * pow(1.0 - max(dot(n, v), 0.0), 3.0);
  vec3 color = albedo * (ambient + diffuse) + vec3(specular + rim);
  frag_color = vec4(pow(color, vec3(1.0 / 1.1)), 1.0);
}
