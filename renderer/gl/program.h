#pragma once
// A typed shader program (in the spirit of Magnum's AbstractShaderProgram): a subclass per shader names its
// uniforms once as members, whose locations are looked up when the program is linked. Asking for a uniform the
// linked program lacks is an error (ProgramChecks::Throw: tests and debug builds) or a warning, never silent.
// GLSL compilers drop uniforms a variant does not use: such a uniform is declared OptionalUniform explicitly.
#include "renderer/gl/shader_library.h"

#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace deepgi::gl {

enum class ProgramChecks { Warn, Throw };
// Default: Throw in debug builds (no NDEBUG) or with DEEPGI_STRICT_PROGRAMS=1 in the environment, else Warn.
ProgramChecks programChecks();
void setProgramChecks(ProgramChecks checks);

struct ProgramError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Reports a program mistake (throws ProgramError or prints it once to stderr, per programChecks()).
void programMistake(const std::string& message);

// While one exists, mistakes only warn: a shader hot-reloaded while someone edits it (which may well drop a
// uniform) must not stop the viewer; the shipped shaders are checked when first linked.
class LenientProgramChecks {
public:
    LenientProgramChecks();
    ~LenientProgramChecks();
    LenientProgramChecks(const LenientProgramChecks&) = delete;
    LenientProgramChecks& operator=(const LenientProgramChecks&) = delete;
};

class Program {
public:
    Program(GLuint id, std::string name);
    virtual ~Program() = default;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    GLuint id() const { return id_; }
    const std::string& name() const { return name_; }
    // Location of a uniform; a required one the program lacks is a programMistake(). -1 when absent.
    GLint location(const std::string& uniform, bool optional);
    // The sampler uniforms the linked program uses (reflection), without those bound outside the pass tables.
    const std::vector<std::string>& activeSamplers() const { return samplers_; }
    // Linked by a hot reload (its mistakes only warn, LenientProgramChecks).
    bool reloaded() const { return reloaded_; }
    // Sets a sampler uniform to a texture unit.
    void setSampler(const std::string& sampler, int unit) const;

protected:
    // A sampler whose texture is bound by someone else at a fixed unit (SceneGpu's material textures).
    void externalSampler(const std::string& sampler);

private:
    GLuint id_;
    std::string name_;
    bool reloaded_;
    std::vector<std::string> samplers_;
    std::map<std::string, GLint> samplerLocations_;
};

namespace detail {
void setUniform(GLuint p, GLint loc, int v);
void setUniform(GLuint p, GLint loc, float v);
void setUniform(GLuint p, GLint loc, bool v);
void setUniform(GLuint p, GLint loc, const glm::vec2& v);
void setUniform(GLuint p, GLint loc, const glm::ivec2& v);
void setUniform(GLuint p, GLint loc, const glm::vec3& v);
void setUniform(GLuint p, GLint loc, const glm::vec4& v);
void setUniform(GLuint p, GLint loc, const glm::mat4& v);
void setUniformArray(GLuint p, GLint loc, const float* v, int count);
}  // namespace detail

// A uniform of type T (int, float, bool as int, vec2/3/4, ivec2, mat4) of one program.
template <class T>
class Uniform {
public:
    Uniform(Program& p, const char* name) : program_(p.id()), location_(p.location(name, false)) {}
    void set(const T& v) const { detail::setUniform(program_, location_, v); }
    bool present() const { return location_ >= 0; }

protected:
    Uniform(Program& p, const char* name, bool optional) : program_(p.id()), location_(p.location(name, optional)) {}

private:
    GLuint program_;
    GLint location_;
};

// A uniform that some variants of the shader (#ifdef) do not have: setting it there does nothing.
template <class T>
class OptionalUniform : public Uniform<T> {
public:
    OptionalUniform(Program& p, const char* name) : Uniform<T>(p, name, true) {}
};

// float name[N]
template <int N>
class UniformFloatArray {
public:
    UniformFloatArray(Program& p, const char* name) : program_(p.id()), location_(p.location(name, false)) {}
    void set(const float* v) const { detail::setUniformArray(program_, location_, v, N); }

private:
    GLuint program_;
    GLint location_;
};

// The typed programs of one pass, one per variant (set of defines), re-created when the library rebuilds the
// GL program (hot reload), so locations are looked up once per link.
template <class P>
class ProgramSlot {
public:
    P& get(ShaderLibrary& library, const ProgramDesc& desc) {
        const ShaderLibrary::Built b = library.getBuilt(desc);
        auto& e = programs_[desc.key()];
        if (!e.program || e.serial != b.serial) {
            const bool reloaded = e.serial != 0;
            e.program.reset();  // a failed construction (ProgramError) leaves no stale wrapper behind
            std::optional<LenientProgramChecks> lenient;
            if (reloaded) lenient.emplace();
            e.program = std::make_unique<P>(b.id, desc.label());
            e.serial = b.serial;
        }
        return *e.program;
    }

private:
    struct Entry {
        std::unique_ptr<P> program;
        uint64_t serial = 0;
    };
    std::map<std::string, Entry> programs_;
};

}  // namespace deepgi::gl
