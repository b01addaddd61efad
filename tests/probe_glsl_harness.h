#pragma once
// Runs a GLSL probe lookup (probe_volume.glsl, environment.glsl) at a list of points on the GPU, so that a test can
// compare it with its C++ twin: the probe atlases as textures, and one fragment per point.

#include "renderer/gl/gl.h"
#include "renderer/probes/probe_volume.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace deepgi::test {

inline std::string readShaderSource(const std::string& name) {
    std::ifstream f(std::string(DEEPGI_SHADER_DIR) + "/" + name);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// One texture per probe atlas, filtered as the renderer samples it (Probe Data: nearest).
inline std::vector<gl::TextureHandle> probeAtlasTextures(const std::vector<ProbeTextureDesc>& descs) {
    std::vector<gl::TextureHandle> tex;
    for (const ProbeTextureDesc& d : descs) {
        tex.push_back(gl::createTexture(GL_TEXTURE_2D, d.name));
        glTextureStorage2D(tex.back().id(), 1, d.internalFormat, d.width, d.height);
        const GLenum filter = d.name == "Probe Data" ? GL_NEAREST : GL_LINEAR;
        glTextureParameteri(tex.back().id(), GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(tex.back().id(), GL_TEXTURE_MAG_FILTER, filter);
        glTextureParameteri(tex.back().id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(tex.back().id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    return tex;
}

inline GLuint compileTestShader(GLenum type, const std::string& src) {
    GLuint sh = glCreateShader(type);
    const char* p = src.c_str();
    glShaderSource(sh, 1, &p, nullptr);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(sh, sizeof log, nullptr, log);
        ADD_FAILURE() << log;
    }
    return sh;
}

// Draws `header` (version, defines, libraries) + a main() writing `expression` (a vec4 of uPoints[i], uNormals[i])
// for each point i, and returns the RGBA results; `setUniforms` sets what else the program reads. Empty on a link
// failure (reported).
inline std::vector<float> evaluateAtPoints(const std::string& header, const std::string& expression,
                                           const std::vector<glm::vec3>& ps, const std::vector<glm::vec3>& ns,
                                           const std::function<void(GLuint)>& setUniforms = {}) {
    const int N = int(ps.size());
    const std::string fs = header + "uniform vec3 uPoints[" + std::to_string(N) + "];\nuniform vec3 uNormals[" +
                           std::to_string(N) + "];\nout vec4 oColor;\nvoid main() { int i = int(gl_FragCoord.x);\n  oColor = " +
                           expression + "; }\n";
    GLuint prog = glCreateProgram();
    GLuint v1 = compileTestShader(GL_VERTEX_SHADER, readShaderSource("fullscreen.vert")),
           f1 = compileTestShader(GL_FRAGMENT_SHADER, fs);
    glAttachShader(prog, v1);
    glAttachShader(prog, f1);
    glLinkProgram(prog);
    GLint linked = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &linked);
    std::vector<float> out;
    if (!linked) {
        ADD_FAILURE() << "the point-evaluation program does not link";
    } else {
        glProgramUniform3fv(prog, glGetUniformLocation(prog, "uPoints"), N, &ps[0].x);
        glProgramUniform3fv(prog, glGetUniformLocation(prog, "uNormals"), N, &ns[0].x);
        if (setUniforms) setUniforms(prog);
        gl::TextureHandle target = gl::createTexture(GL_TEXTURE_2D, "point evaluation target");
        glTextureStorage2D(target.id(), 1, GL_RGBA32F, N, 1);
        gl::FramebufferHandle fbo = gl::createFramebuffer("point evaluation");
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, N, 1);
        gl::VertexArrayHandle vao = gl::createVertexArray("point evaluation");
        glBindVertexArray(vao.id());
        glUseProgram(prog);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        out.resize(size_t(N) * 4);
        glGetTextureImage(target.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(float)), out.data());
    }
    glDeleteProgram(prog);
    glDeleteShader(v1);
    glDeleteShader(f1);
    return out;
}

}  // namespace deepgi::test
