#include "gl_shader.h"

#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "primo/util/error.h"

namespace primo::editor {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error(path + ": cannot read the shader (set PRIMO_SHADER_DIR to the folder with the "
                       "editor's .vert/.frag files)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The driver's log of a shader or program, without trailing blanks.
template <class Get, class GetLog>
std::string info_log(GLuint object, Get get, GetLog get_log) {
  GLint length = 0;
  get(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> text(size_t(std::max(length, 1)), '\0');
  get_log(object, length, nullptr, text.data());
  std::string log(text.data());
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log;
}

GLuint compile(GLenum type, const std::string& path) {
  const std::string source = read_file(path);
  const GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    throw Error(path + ": shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(const std::string& folder, const std::string& vertex,
                             const std::string& fragment) {
  const std::string vpath = folder + "/" + vertex, fpath = folder + "/" + fragment;
  const GLuint vs = compile(GL_VERTEX_SHADER, vpath);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fpath);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(program_, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(program_);
    program_ = 0;
    throw Error(vpath + " + " + fpath + ": shaders do not link: " + log);
  }
}

ShaderProgram::~ShaderProgram() {
  if (program_) glDeleteProgram(program_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (program_) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
  }
  return *this;
}

}  // namespace primo::editor
