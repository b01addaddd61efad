#pragma once
// The pipeline built from the pass tables: which textures to allocate, the order of the passes (topological from
// what they read and write) and the rules, checked when the pipeline is built (an error names pass and texture):
//  - a required read of a texture no pass of this pipeline writes;
//  - two passes writing one texture in one frame (one must declare an update, ordered with after());
//  - two updates of one texture without an order between them; an update of a texture nobody writes;
//  - a read of another pass's scratch; two declarations of one texture that differ; a cycle.
#include "renderer/passes/pass.h"

#include <string>
#include <vector>

namespace deepgi {

struct PassInfo {
    std::string name;
    PassTable table;
    bool enabled = true;
};

// The textures every table allocates (Write and Scratch declarations, enabled or not, merged by name).
std::vector<TextureDecl> allocations(const std::vector<PassInfo>& passes);

// Indices into `passes` of the enabled passes, in execution order (ties keep the given order). Throws
// std::runtime_error ("pipeline: pass 'Composite' reads 'Foo', which no pass of this pipeline writes").
std::vector<size_t> schedulePasses(const std::vector<PassInfo>& passes);

}  // namespace deepgi
