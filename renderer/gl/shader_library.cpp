#include "renderer/gl/shader_library.h"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace deepgi::gl {

std::string ProgramDesc::key() const {
    std::string k = vertex + "|" + geometry + "|" + fragment + "|" + compute;
    for (const auto& d : defines) k += "|" + d;
    return k;
}

std::string ProgramDesc::label() const {
    std::string l = fragment.empty() ? (compute.empty() ? vertex : compute) : fragment;
    if (!defines.empty()) {
        l += " [";
        for (size_t i = 0; i < defines.size(); ++i) l += (i ? " " : "") + defines[i];
        l += "]";
    }
    return l;
}

namespace {

int64_t mtimeOf(const std::string& path) {
    struct stat st {};
    if (stat(path.c_str(), &st) != 0) return -1;
    return int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
}

std::string readFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw ShaderError(path + ": cannot read shader file");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// Expands #include lines; `names` maps GLSL source-string numbers (used in #line) to file names.
struct Preprocessor {
    std::string dir;
    std::vector<std::string> names;
    std::map<std::string, int64_t>* files;
    std::set<std::string> included;

    std::string expand(const std::string& file, int depth) {
        if (depth > 16) throw ShaderError(file + ": #include nested too deeply");
        const std::string path = dir + "/" + file;
        (*files)[path] = mtimeOf(path);
        std::string src = readFile(path);
        const int index = int(names.size());
        names.push_back(file);
        std::istringstream in(src);
        std::ostringstream out;
        std::string line;
        int lineNo = 0;
        static const std::regex includeRe(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
        std::smatch m;
        while (std::getline(in, line)) {
            ++lineNo;
            if (std::regex_match(line, m, includeRe)) {
                std::string inc = m[1];
                if (!included.count(inc)) {  // each include once per program
                    included.insert(inc);
                    out << "#line 1 " << names.size() << "\n" << expand(inc, depth + 1);
                }
                out << "#line " << lineNo + 1 << " " << index << "\n";
            } else {
                out << line << "\n";
            }
        }
        return out.str();
    }
};

// The info log of a shader (program = false) or a program.
std::string infoLog(GLuint object, bool program) {
    GLint len = 0;
    if (program) glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len);
    else glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
    std::string log(std::max(len, 1), '\0');
    if (program) glGetProgramInfoLog(object, len, nullptr, log.data());
    else glGetShaderInfoLog(object, len, nullptr, log.data());
    return log.c_str();
}

std::string stageName(GLenum stage) {
    switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    }
    return "shader";
}

// Mesa and NVIDIA both print "<string>:<line>(<col>)" or "<string>(<line>)"; rewrite to "file:line".
std::string mapLog(const std::string& log, const std::vector<std::string>& names) {
    static const std::regex mesaRe(R"((\d+):(\d+)\((\d+)\))");
    static const std::regex nvRe(R"(^(\d+)\((\d+)\))");
    std::istringstream in(log);
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, mesaRe)) {
            size_t idx = std::stoul(m[1]);
            std::string file = idx < names.size() ? names[idx] : "?";
            line = m.prefix().str() + file + ":" + m[2].str() + ":" + m[3].str() + m.suffix().str();
        } else if (std::regex_search(line, m, nvRe)) {
            size_t idx = std::stoul(m[1]);
            std::string file = idx < names.size() ? names[idx] : "?";
            line = file + ":" + m[2].str() + m.suffix().str();
        }
        if (!line.empty()) out << line << "\n";
    }
    return out.str();
}

}  // namespace

ShaderLibrary::ShaderLibrary(std::string dir) : dir_(std::move(dir)) {}

ShaderLibrary::~ShaderLibrary() {
    for (auto& [k, e] : entries_) {
        if (e.program) glDeleteProgram(e.program);
        if (e.previous) glDeleteProgram(e.previous);
    }
}

void ShaderLibrary::setDirectory(const std::string& dir) {
    dir_ = dir;
    reloadAll();
}

GLuint ShaderLibrary::build(const ProgramDesc& desc, std::map<std::string, int64_t>& files) {
    files.clear();
    std::vector<GLuint> shaders;
    auto cleanup = [&] { for (GLuint s : shaders) glDeleteShader(s); };
    const std::pair<GLenum, const std::string*> stages[] = {{GL_VERTEX_SHADER, &desc.vertex},
                                                            {GL_GEOMETRY_SHADER, &desc.geometry},
                                                            {GL_FRAGMENT_SHADER, &desc.fragment},
                                                            {GL_COMPUTE_SHADER, &desc.compute}};
    try {
        for (auto [stage, file] : stages) {
            if (file->empty()) continue;
            Preprocessor pp{dir_, {}, &files, {}};
            std::string body = pp.expand(*file, 0);
            // Put the defines right after the #version line of the main file.
            size_t ver = body.find("#version");
            if (ver == std::string::npos) throw ShaderError(*file + ":1: missing #version");
            size_t eol = body.find('\n', ver);
            std::string header = body.substr(0, eol + 1);
            header += "#define DEEPGI_STAGE_" + stageName(stage) + "\n";
            for (const auto& d : desc.defines) header += "#define " + d + "\n";
            header += "#line 2 0\n";
            std::string src = header + body.substr(eol + 1);
            GLuint sh = glCreateShader(stage);
            shaders.push_back(sh);
            const char* p = src.c_str();
            glShaderSource(sh, 1, &p, nullptr);
            glCompileShader(sh);
            GLint ok = 0;
            glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
            if (!ok)
                throw ShaderError(dir_ + "/" + *file + ": " + stageName(stage) + " shader failed to compile:\n" +
                                  mapLog(infoLog(sh, false), pp.names));
        }
        GLuint prog = glCreateProgram();
        for (GLuint s : shaders) glAttachShader(prog, s);
        glLinkProgram(prog);
        GLint ok = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            const std::string log = infoLog(prog, true);
            glDeleteProgram(prog);
            std::string what = desc.vertex + (desc.fragment.empty() ? desc.compute : " + " + desc.fragment);
            throw ShaderError(what + " (in " + dir_ + "): program failed to link:\n" + std::string(log.c_str()));
        }
        glObjectLabel(GL_PROGRAM, prog, -1, (desc.fragment.empty() ? desc.compute : desc.fragment).c_str());
        cleanup();
        return prog;
    } catch (...) {
        cleanup();
        throw;
    }
}

GLuint ShaderLibrary::get(const ProgramDesc& desc) { return getBuilt(desc).id; }

ShaderLibrary::Built ShaderLibrary::getBuilt(const ProgramDesc& desc) {
    const std::string key = desc.key();
    auto it = entries_.find(key);
    if (it != entries_.end() && it->second.program) {
        if (it->second.trialUsesLeft > 0 && std::find(trialUses_.begin(), trialUses_.end(), key) == trialUses_.end())
            trialUses_.push_back(key);
        return {it->second.program, it->second.serial};
    }
    Entry e;
    e.desc = desc;
    e.program = build(desc, e.files);  // throws on the first build
    e.serial = nextSerial_++;
    const Entry& stored = entries_.insert_or_assign(key, std::move(e)).first->second;
    return {stored.program, stored.serial};
}

int ShaderLibrary::reloadChanged() {
    int rebuilt = 0;
    errors_.clear();
    for (auto& [key, e] : entries_) {
        bool changed = e.files.empty();
        for (const auto& [path, mt] : e.files) if (mtimeOf(path) != mt) changed = true;
        if (!changed) {
            if (!e.error.empty()) errors_.push_back(e.error);
            continue;
        }
        std::map<std::string, int64_t> files;
        try {
            GLuint p = build(e.desc, files);
            // The last program that passed its trial stays as the one to go back to; an untried one is dropped.
            if (e.trialUsesLeft > 0) endTrial(e, false);
            if (e.program) {
                e.previous = e.program;
                e.trialUsesLeft = kTrialUses;
                ++trials_;
            }
            e.program = p;
            e.serial = nextSerial_++;
            e.error.clear();
            ++rebuilt;
        } catch (const ShaderError& err) {
            e.error = err.what();  // keep the last good program
            errors_.push_back(e.error);
        }
        e.files = files.empty() ? e.files : files;
        // Remember the mtimes we tried, so an unchanged broken file is not recompiled every frame.
        for (auto& [path, mt] : e.files) mt = mtimeOf(path);
    }
    return rebuilt;
}

void ShaderLibrary::endTrial(Entry& e, bool keepNew) {  // e is on trial
    if (keepNew) {
        glDeleteProgram(e.previous);
    } else {
        glDeleteProgram(e.program);
        e.program = e.previous;
        e.serial = nextSerial_++;
    }
    e.previous = 0;
    e.trialUsesLeft = 0;
    --trials_;
}

std::vector<std::string> ShaderLibrary::takeTrialUses() {
    std::vector<std::string> used;
    used.swap(trialUses_);
    return used;
}

void ShaderLibrary::passTrial(const std::string& key) {
    auto it = entries_.find(key);
    if (it == entries_.end() || it->second.trialUsesLeft <= 0) return;
    if (it->second.trialUsesLeft == 1) endTrial(it->second, true);
    else --it->second.trialUsesLeft;
}

void ShaderLibrary::failTrial(const std::string& key, const std::string& reason) {
    auto it = entries_.find(key);
    if (it == entries_.end() || it->second.trialUsesLeft <= 0) return;
    Entry& e = it->second;
    endTrial(e, false);
    // Listed like a compile error, until a file of the program changes again (reloadChanged).
    e.error = dir_ + "/" + e.desc.label() + ": " + reason;
    errors_.push_back(e.error);
}

int ShaderLibrary::reloadAll() {
    for (auto& [key, e] : entries_) e.files.clear();
    return reloadChanged();
}

}  // namespace deepgi::gl
