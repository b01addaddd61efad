#pragma once
// An OpenGL 4.5 core context without a window: OSMesa (llvmpipe). Loads glad on creation.
#include <memory>
#include <string>

namespace deepgi::gl {

class HeadlessContext {
public:
    // Throws std::runtime_error when no 4.5 core context can be created.
    HeadlessContext();
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;
    std::string renderer() const;  // GL_RENDERER
    bool isSoftware() const;       // llvmpipe/softpipe: GPU timer queries are not trustworthy

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace deepgi::gl
