#pragma once
// Shader programs built from files in the shader folder, with `#include "file"` and injected #defines.
// Compile errors name the file and line. A program that fails to rebuild keeps its last good version; one that
// rebuilds is on trial for its first uses (the slow-shader watchdog, Renderer::render) and can be given its
// previous version back.
#include <glad/gl.h>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepgi::gl {

struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ProgramDesc {
    std::string vertex, geometry, fragment, compute;  // file names relative to the shader folder ("" = none)
    std::vector<std::string> defines;                 // "NAME" or "NAME VALUE"
    std::string key() const;
    std::string label() const;  // "radiosity_gather.frag [DEEPGI_SINGLE_LAYER]", for messages
};

class ShaderLibrary {
public:
    explicit ShaderLibrary(std::string shaderDir);
    ~ShaderLibrary();
    ShaderLibrary(const ShaderLibrary&) = delete;
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    // The program for desc, compiled on first use. Throws ShaderError ("file:line: message") if it has never
    // compiled successfully.
    GLuint get(const ProgramDesc& desc);
    // The same, with a serial number that changes whenever the program is (re)linked: typed wrappers
    // (gl::ProgramSlot) look their uniforms up again when it does.
    struct Built {
        GLuint id;
        uint64_t serial;
    };
    Built getBuilt(const ProgramDesc& desc);

    // Recompiles the programs whose source files (includes too) changed on disk. Returns how many were rebuilt;
    // failures keep the last good program and are listed in errors().
    int reloadChanged();
    int reloadAll();
    const std::vector<std::string>& errors() const { return errors_; }

    // Trials: a program rebuilt by a reload keeps the one it replaced alive until it has finished kTrialUses uses in
    // time (passTrial) or failed one (failTrial: the previous program is back, the reason listed in errors()).
    static constexpr int kTrialUses = 3;
    bool anyOnTrial() const { return trials_ > 0; }
    // Keys of the programs on trial that get()/getBuilt() returned since the last call.
    std::vector<std::string> takeTrialUses();
    void passTrial(const std::string& key);
    // Restores the previous program (a new serial: typed wrappers look their uniforms up again); `reason` follows
    // the program's file in the message ("<dir>/composite.frag: <reason>").
    void failTrial(const std::string& key, const std::string& reason);
    const std::string& directory() const { return dir_; }
    void setDirectory(const std::string& dir);

private:
    struct Entry {
        ProgramDesc desc;
        GLuint program = 0;
        uint64_t serial = 0;
        std::map<std::string, int64_t> files;  // path -> mtime at last build attempt
        std::string error;
        GLuint previous = 0;   // the program `program` replaced, kept while `program` is on trial
        int trialUsesLeft = 0; // > 0: on trial
    };
    void endTrial(Entry& e, bool keepNew);
    GLuint build(const ProgramDesc& desc, std::map<std::string, int64_t>& files);
    std::string dir_;
    std::map<std::string, Entry> entries_;
    std::vector<std::string> errors_;
    uint64_t nextSerial_ = 1;
    int trials_ = 0;                     // entries on trial
    std::vector<std::string> trialUses_; // keys of programs on trial handed out since takeTrialUses()
};

}  // namespace deepgi::gl
