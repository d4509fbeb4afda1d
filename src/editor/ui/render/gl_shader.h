#pragma once
// GLSL programs read from the shader folder at run time. Failures throw primo::Error naming
// the full path of the file and the driver's info log.

#include <string>

#include "gl.h"

namespace primo::editor {

class ShaderProgram {
 public:
  ShaderProgram() = default;
  // Compiles `folder/vertex` and `folder/fragment` and links them.
  ShaderProgram(const std::string& folder, const std::string& vertex, const std::string& fragment);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  GLuint id() const { return program_; }
  void use() const { glUseProgram(program_); }
  GLint uniform(const char* name) const { return glGetUniformLocation(program_, name); }

 private:
  GLuint program_ = 0;
};

}  // namespace primo::editor
