// The scene's parts: current and previous model matrices (vertices stay as loaded), indexed by the per-vertex part
// index. Mirrors SceneObjectStd430 in renderer/scene/scene_gpu.cpp.
struct SceneObject {
    mat4 model;         // current
    mat4 prevModel;     // last frame's (= model without history)
    mat4 normalMatrix;  // inverse transpose of mat3(model) up to a positive scale
    uvec4 id;           // x = node index + 1 (0 = none)
};
layout(std430, binding = 5) readonly buffer SceneObjects { SceneObject uObjects[]; };
layout(location = 7) in uint aObject;
