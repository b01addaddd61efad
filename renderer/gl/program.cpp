#include "renderer/gl/program.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace deepgi::gl {

namespace {

ProgramChecks defaultChecks() {
    if (const char* e = std::getenv("DEEPGI_STRICT_PROGRAMS")) return std::string(e) == "0" ? ProgramChecks::Warn : ProgramChecks::Throw;
#ifdef NDEBUG
    return ProgramChecks::Warn;
#else
    return ProgramChecks::Throw;
#endif
}

ProgramChecks& checksSetting() {
    static ProgramChecks c = defaultChecks();
    return c;
}

bool isSamplerType(GLenum t) {
    switch (t) {
    case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE: case GL_SAMPLER_1D_SHADOW:
    case GL_SAMPLER_2D_SHADOW: case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_1D_ARRAY_SHADOW:
    case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_2D_MULTISAMPLE: case GL_SAMPLER_2D_MULTISAMPLE_ARRAY:
    case GL_SAMPLER_CUBE_SHADOW: case GL_SAMPLER_BUFFER: case GL_SAMPLER_2D_RECT: case GL_SAMPLER_2D_RECT_SHADOW:
    case GL_SAMPLER_CUBE_MAP_ARRAY: case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW: case GL_INT_SAMPLER_2D:
    case GL_INT_SAMPLER_2D_ARRAY: case GL_UNSIGNED_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
        return true;
    }
    return false;
}

thread_local int lenientDepth = 0;

}  // namespace

LenientProgramChecks::LenientProgramChecks() { ++lenientDepth; }
LenientProgramChecks::~LenientProgramChecks() { --lenientDepth; }

ProgramChecks programChecks() { return checksSetting(); }
void setProgramChecks(ProgramChecks c) { checksSetting() = c; }

void programMistake(const std::string& message) {
    if (programChecks() == ProgramChecks::Throw && lenientDepth == 0) throw ProgramError(message);
    static std::mutex m;
    static std::set<std::string> reported;
    std::lock_guard<std::mutex> lock(m);
    if (reported.insert(message).second) std::fprintf(stderr, "deepgi: warning: %s\n", message.c_str());
}

Program::Program(GLuint id, std::string name) : id_(id), name_(std::move(name)), reloaded_(lenientDepth > 0) {
    GLint count = 0;
    glGetProgramInterfaceiv(id_, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count; ++i) {
        const GLenum props[] = {GL_TYPE, GL_LOCATION, GL_BLOCK_INDEX};
        GLint values[3] = {0, -1, -1};
        glGetProgramResourceiv(id_, GL_UNIFORM, GLuint(i), 3, props, 3, nullptr, values);
        if (!isSamplerType(GLenum(values[0])) || values[2] != -1) continue;
        char buf[256] = {0};
        glGetProgramResourceName(id_, GL_UNIFORM, GLuint(i), sizeof(buf), nullptr, buf);
        samplers_.push_back(buf);
        samplerLocations_[buf] = values[1];
    }
}

GLint Program::location(const std::string& uniform, bool optional) {
    const GLint loc = glGetUniformLocation(id_, uniform.c_str());
    if (loc < 0 && !optional)
        programMistake("program '" + name_ + "' has no uniform '" + uniform +
                       "' (misspelt, or unused and removed by the GLSL compiler: declare it OptionalUniform if a variant lacks it)");
    return loc;
}

void Program::setSampler(const std::string& sampler, int unit) const {
    auto it = samplerLocations_.find(sampler);
    if (it != samplerLocations_.end()) glProgramUniform1i(id_, it->second, unit);
}

void Program::externalSampler(const std::string& sampler) {
    samplers_.erase(std::remove(samplers_.begin(), samplers_.end(), sampler), samplers_.end());
}

namespace detail {
void setUniform(GLuint p, GLint l, int v) { glProgramUniform1i(p, l, v); }
void setUniform(GLuint p, GLint l, float v) { glProgramUniform1f(p, l, v); }
void setUniform(GLuint p, GLint l, bool v) { glProgramUniform1i(p, l, v ? 1 : 0); }
void setUniform(GLuint p, GLint l, const glm::vec2& v) { glProgramUniform2fv(p, l, 1, glm::value_ptr(v)); }
void setUniform(GLuint p, GLint l, const glm::ivec2& v) { glProgramUniform2iv(p, l, 1, glm::value_ptr(v)); }
void setUniform(GLuint p, GLint l, const glm::vec3& v) { glProgramUniform3fv(p, l, 1, glm::value_ptr(v)); }
void setUniform(GLuint p, GLint l, const glm::vec4& v) { glProgramUniform4fv(p, l, 1, glm::value_ptr(v)); }
void setUniform(GLuint p, GLint l, const glm::mat4& v) { glProgramUniformMatrix4fv(p, l, 1, GL_FALSE, glm::value_ptr(v)); }
void setUniformArray(GLuint p, GLint l, const float* v, int n) { glProgramUniform1fv(p, l, n, v); }
}  // namespace detail

}  // namespace deepgi::gl
