#include "tests/oracle/fsr1_shader.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <map>
#include <stdexcept>
#include <string>

#include "tests/oracle/third_party_sources.h"

namespace aalab::oracle {

namespace {

// The shader text: our defines, bindings and callbacks around the two original headers.
std::string ShaderText(bool easu, bool precise) {
  std::string s = "#version 450\n#define A_GPU 1\n#define A_GLSL 1\n";
  s += ReadThirdParty("fidelityfx-fsr1/ffx_a.h");
  s += "\nlayout(binding = 0) uniform sampler2D InputTexture;\n"
       "layout(rgba32f, binding = 0) uniform writeonly image2D OutputTexture;\n"
       "uniform uvec4 Const0;\nuniform uvec4 Const1;\nuniform uvec4 Const2;\nuniform uvec4 Const3;\n";
  if (easu) {
    s += "#define FSR_EASU_F 1\n"
         "AF4 FsrEasuRF(AF2 p) { return textureGather(InputTexture, p, 0); }\n"
         "AF4 FsrEasuGF(AF2 p) { return textureGather(InputTexture, p, 1); }\n"
         "AF4 FsrEasuBF(AF2 p) { return textureGather(InputTexture, p, 2); }\n";
  } else {
    s += "#define FSR_RCAS_F 1\n"
         "AF4 FsrRcasLoadF(ASU2 p) { return texelFetch(InputTexture, clamp(p, ASU2(0), "
         "textureSize(InputTexture, 0) - ASU2(1)), 0); }\n"
         "void FsrRcasInputF(inout AF1 r, inout AF1 g, inout AF1 b) {}\n";
  }
  s += ReadThirdParty("fidelityfx-fsr1/ffx_fsr1.h");
  s += std::string("\nvoid CurrFilter(AU2 pos) {\n  ") + (precise ? "precise " : "") + "AF3 c;\n";
  s += easu ? "  FsrEasuF(c, pos, Const0, Const1, Const2, Const3);\n" : "  FsrRcasF(c.r, c.g, c.b, pos, Const0);\n";
  s += "  imageStore(OutputTexture, ASU2(pos), AF4(c, 1));\n}\n"
       "layout(local_size_x = 64) in;\n"
       "void main() {\n"
       "  AU2 gxy = ARmp8x8(gl_LocalInvocationID.x) + AU2(gl_WorkGroupID.x << 4u, gl_WorkGroupID.y << 4u);\n"
       "  CurrFilter(gxy);\n  gxy.x += 8u;\n  CurrFilter(gxy);\n  gxy.y += 8u;\n  CurrFilter(gxy);\n"
       "  gxy.x -= 8u;\n  CurrFilter(gxy);\n}\n";
  return s;
}

GLuint ComputeProgram(bool easu, bool precise) {
  static std::map<std::pair<bool, bool>, GLuint> programs;
  if (auto it = programs.find({easu, precise}); it != programs.end()) return it->second;
  const std::string src = ShaderText(easu, precise);
  const char* p = src.c_str();
  GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(sh, 1, &p, nullptr);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  std::vector<char> log(16384);
  if (!ok) {
    glGetShaderInfoLog(sh, static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw std::runtime_error(std::string("compiling ffx_fsr1.h (") + (easu ? "EASU" : "RCAS") +
                             ") failed: " + log.data());
  }
  GLuint prog = glCreateProgram();
  glAttachShader(prog, sh);
  glLinkProgram(prog);
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramInfoLog(prog, static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw std::runtime_error(std::string("linking ffx_fsr1.h failed: ") + log.data());
  }
  programs[{easu, precise}] = prog;
  return prog;
}

std::vector<float> Dispatch(GLuint prog, const Image8& frame, int out_w, int out_h,
                            const std::array<std::array<uint32_t, 4>, 4>& con) {
  GLuint tex[2] = {0, 0};
  glGenTextures(2, tex);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, tex[0]);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, frame.Width(), frame.Height(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
               frame.Data().data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, tex[1]);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, out_w, out_h);
  glBindImageTexture(0, tex[1], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, tex[0]);
  glUseProgram(prog);
  glUniform1i(glGetUniformLocation(prog, "InputTexture"), 0);
  const char* names[4] = {"Const0", "Const1", "Const2", "Const3"};
  for (int i = 0; i < 4; ++i) {
    const GLint loc = glGetUniformLocation(prog, names[i]);
    if (loc >= 0) glUniform4uiv(loc, 1, con[static_cast<size_t>(i)].data());
  }
  glDispatchCompute(static_cast<GLuint>((out_w + 15) / 16), static_cast<GLuint>((out_h + 15) / 16), 1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  std::vector<float> out(static_cast<size_t>(out_w) * static_cast<size_t>(out_h) * 4);
  glBindTexture(GL_TEXTURE_2D, tex[1]);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, out.data());
  const GLenum err = glGetError();
  glDeleteTextures(2, tex);
  if (err != GL_NO_ERROR) throw std::runtime_error("OpenGL error " + std::to_string(err) + " while running ffx_fsr1.h");
  return out;
}

}  // namespace

std::vector<float> RunFsr1EasuShader(const Image8& frame, int out_w, int out_h,
                                     const std::array<std::array<uint32_t, 4>, 4>& con, bool precise) {
  return Dispatch(ComputeProgram(true, precise), frame, out_w, out_h, con);
}

std::vector<float> RunFsr1RcasShader(const Image8& frame, uint32_t con_x, bool precise) {
  return Dispatch(ComputeProgram(false, precise), frame, frame.Width(), frame.Height(),
                  {{{con_x, 0u, 0u, 0u}, {}, {}, {}}});
}

}  // namespace aalab::oracle
